#include "app/render/render_mesh.h"

#include <gtest/gtest.h>

#include "engine/scene/scene_mesh.h"
#include "engine/session/simulation.h"
#include "solver/fracture/knife.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

TEST(HeatColor, RunsFromBlueToRedAndClamps) {
  EXPECT_GT(heatColor(0.0).z(), 0.8);
  EXPECT_GT(heatColor(1.0).x(), 0.8);
  EXPECT_EQ(heatColor(-3.0), heatColor(0.0));
  EXPECT_EQ(heatColor(7.0), heatColor(1.0));
  EXPECT_EQ(heatColor(std::nan("")), heatColor(0.0));
  for (double t = 0.0; t < 1.0; t += 0.01)
    EXPECT_LT((heatColor(t + 0.01) - heatColor(t)).norm(), 0.1) << "continuous at " << t;
}

// The damage view colours the faces around a cut hot and the untouched surface cold; the
// geometry is the shaded view's.
TEST(SurfaceViews, DamageViewMarksTheCutAndKeepsTheGeometry) {
  const SceneDescription scene =
      loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json");
  Simulation sim(scene, loadSceneMesh(scene));
  sim.cut(sweptBladeSurface(Vec3(0, 0.3, -0.3), Vec3(0, 0.3, 0.3), Vec3(0, 0.05, -0.3),
                            Vec3(0, 0.05, 0.3)));
  const VisualSurface& surface = sim.surface();
  const RenderMesh shaded = makeRenderMesh(surface, SurfaceStyle{}, {});
  SurfaceStyle damageStyle;
  damageStyle.view = SurfaceView::Damage;
  damageStyle.tintCracks = false;
  const RenderMesh damage = makeRenderMesh(surface, damageStyle, sim.vertexDamage());
  EXPECT_EQ(damage.positions, shaded.positions);
  EXPECT_EQ(damage.indices, shaded.indices);
  int hot = 0, cold = 0;
  for (size_t i = 0; i < damage.colors.size() / 3; ++i) {
    const Vec3 c(damage.colors[3 * i], damage.colors[3 * i + 1], damage.colors[3 * i + 2]);
    const double y = damage.positions[3 * i + 1];
    if (y < -0.05) cold += (c - heatColor(0.0)).norm() < 1e-6;  // far below the cut
    if ((c - heatColor(0.0)).norm() > 0.2) ++hot;
  }
  EXPECT_GT(hot, 10) << "damaged vertices show warmer than the cold blue";
  EXPECT_GT(cold, 50) << "the untouched bottom shows cold";
}

// Crack faces are shaded flat (each its own three vertices, all with the face's normal); outer
// faces share their vertices and are shaded smooth.
TEST(SurfaceViews, CrackFacesAreFlatAndOuterFacesSmooth) {
  const SceneDescription scene =
      loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json");
  Simulation sim(scene, loadSceneMesh(scene));
  sim.cut(sweptBladeSurface(Vec3(0.01, 0.3, -0.3), Vec3(0.01, 0.3, 0.3), Vec3(0.03, -0.3, -0.3),
                            Vec3(0.03, -0.3, 0.3)));
  const VisualSurface& surface = sim.surface();
  const RenderMesh r = makeRenderMesh(surface, SurfaceStyle{}, {});
  const int outerFaces = facesWithTag(surface, SurfaceTag::Outer).numFaces();
  const int crackFaces = facesWithTag(surface, SurfaceTag::Crack).numFaces();
  ASSERT_GT(crackFaces, 100);
  ASSERT_EQ(r.indices.size(), 3u * (outerFaces + crackFaces));
  auto vec = [](const std::vector<float>& a, unsigned i) {
    return Vec3(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
  };
  std::vector<int> uses(r.positions.size() / 3, 0);
  for (unsigned i : r.indices) ++uses[i];
  for (int f = outerFaces; f < outerFaces + crackFaces; ++f) {
    const unsigned* c = &r.indices[3 * f];
    const Vec3 n = (vec(r.positions, c[1]) - vec(r.positions, c[0]))
                       .cross(vec(r.positions, c[2]) - vec(r.positions, c[0]))
                       .normalized();
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(uses[c[k]], 1) << "crack face " << f << " shares a vertex";
      // n from the float positions of small faces: agrees to float rounding only.
      ASSERT_LT((vec(r.normals, c[k]) - n).norm(), 1e-3) << "crack face " << f;
      ASSERT_LT((vec(r.colors, c[k]) - kCrackColor).norm(), 1e-6);
    }
  }
  int shared = 0;
  for (int f = 0; f < outerFaces; ++f)
    for (int k = 0; k < 3; ++k) shared += uses[r.indices[3 * f + k]] > 1;
  EXPECT_GT(shared, 3 * outerFaces * 9 / 10) << "outer faces share their vertices";
}

}  // namespace
}  // namespace galsculpt
