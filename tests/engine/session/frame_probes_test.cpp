#include "engine/session/frame_probes.h"

#include <gtest/gtest.h>

#include "engine/session/simulation.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

// The opening is the change of distance between the vertices nearest the two rest points; the
// load on a scene anchor is the elastic force on its vertices, 0 once it is removed.
TEST(FrameProbes, OpeningAndAnchorLoadAreReadFromTheState) {
  MaterialParams rubber;
  rubber.lame = lameFromYoungPoisson(1e6, 0.45);
  rubber.density = 1100.0;
  const SimModel model = buildSimModel(test::gridBar(3, 1, 1, 0.1), rubber);
  SimState state = initialState(model);
  AnchorRegistry anchors(model, state);
  MeasureDesc measure;
  measure.opening = {Vec3(-0.01, 0, 0), Vec3(0.31, 0.0, 0.0)};  // nearest: the bar's two ends
  measure.loadAnchor = 0;
  const FrameProbes probes(measure, model.mesh);
  std::vector<int> end;
  for (int v = 0; v < model.numVertices(); ++v)
    if (model.mesh.vertices[v].x() > 0.29) end.push_back(v);
  anchors.addSceneAnchor(0, AnchorConstraint{end, {}, {}, {}});

  FrameMetrics m;
  probes.read(model, state, anchors, {}, m);
  EXPECT_EQ(m.openingM, 0.0);
  EXPECT_LT(m.loadN, 1e-9) << "at rest";

  for (int v : end) state.x[v].x() += 0.01;  // the end pulled 1 cm
  probes.read(model, state, anchors, {}, m);
  EXPECT_NEAR(m.openingM, 0.01, 1e-12);
  EXPECT_NEAR(m.loadN, elasticGradientSum(model, state.x, state, end).norm(), 1e-9);
  EXPECT_GT(m.loadN, 0.0);

  anchors.remove(-1);
  probes.read(model, state, anchors, {}, m);
  EXPECT_EQ(m.loadN, 0.0) << "removed";
}

// A collider's load is its contact force's magnitude, its travel the distance its centre moved.
TEST(FrameProbes, ColliderLoadIsItsContactForce) {
  SimModel model = buildSimModel(test::gridBar(1, 1, 1, 0.1), MaterialParams{});
  Collider striker;
  striker.center = Vec3(0.05, 0.3, 0.05);
  model.colliders.push_back(striker);
  SimState state = initialState(model);
  state.colliders.push_back(initialColliderState(model.colliders[0]));
  AnchorRegistry anchors(model, state);
  MeasureDesc measure;
  measure.loadCollider = 0;
  const FrameProbes probes(measure, model.mesh);
  FrameMetrics m;
  probes.read(model, state, anchors, {Vec3(3.0, 4.0, 0.0)}, m);
  EXPECT_DOUBLE_EQ(m.loadN, 5.0);
  EXPECT_EQ(m.strikerDisplacementM, 0.0);
  EXPECT_EQ(m.absorbedEnergyJ, 0.0) << "a kinematic collider absorbs nothing it reports";
  FrameMetrics none;
  probes.read(model, state, anchors, {}, none);
  EXPECT_EQ(none.loadN, 0.0) << "no contact forces reported";
}

}  // namespace
}  // namespace galsculpt
