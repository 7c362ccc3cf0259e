#include "app/window/tool_controller.h"

#include <gtest/gtest.h>

#include "engine/scene/scene_mesh.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

struct Ball {
  SceneDescription scene =
      loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json");
  SculptSession session{scene, loadSceneMesh(scene)};
  OrbitCamera camera;
  ToolSettings settings;
  ToolController controller{session, camera, settings};
  Ball() {
    camera.frame(boundingBox(session.simulation().model().mesh.vertices));
    controller.setViewport(800, 600);
  }
};

// A knife stroke dragged across the whole view, with every cursor sample used, cuts the ball
// into two pieces, and is recorded as one action.
TEST(ToolController, AKnifeDragAcrossTheViewCutsTheBallInTwo) {
  Ball b;
  b.settings.tool = Tool::Knife;
  b.controller.mouseMove(400, 5);
  b.controller.mouseButton(MouseButton::Left, true, false);
  EXPECT_TRUE(b.controller.strokeActive());
  for (int y = 5; y <= 595; y += 30) b.controller.mouseMove(400, y);
  b.controller.mouseButton(MouseButton::Left, false, false);
  EXPECT_FALSE(b.controller.strokeActive());
  const Simulation& sim = b.session.simulation();
  EXPECT_EQ(countDamagePieces(sim.model(), sim.state()), 2);
  EXPECT_FALSE(b.session.recording().empty());
}

// A knife dragged along the top edge of the view, above the ball, crosses nothing and says so
// once; a stroke through the ball says nothing.
TEST(ToolController, AKnifeThatCrossesNothingSaysSo) {
  Ball b;
  b.settings.tool = Tool::Knife;
  b.controller.mouseMove(5, 5);
  b.controller.mouseButton(MouseButton::Left, true, false);
  for (int x = 5; x <= 795; x += 30) b.controller.mouseMove(x, 5);
  b.controller.mouseButton(MouseButton::Left, false, false);
  EXPECT_EQ(b.session.simulation().state().damageRevision, 0u) << "nothing was cut";
  EXPECT_EQ(b.controller.takeNotice(), "the knife crossed no edge: drag it across the body");
  EXPECT_EQ(b.controller.takeNotice(), "") << "said once";
  b.controller.mouseMove(400, 5);
  b.controller.mouseButton(MouseButton::Left, true, false);
  for (int y = 5; y <= 595; y += 30) b.controller.mouseMove(400, y);
  b.controller.mouseButton(MouseButton::Left, false, false);
  EXPECT_EQ(b.controller.takeNotice(), "");
}

// Picking hits the ball's surface in the middle of the view and nothing at a corner; the right
// button orbits (the camera turns, the body stays).
TEST(ToolController, PickingAndOrbiting) {
  Ball b;
  const std::optional<RayHit> hit = b.controller.pick(400, 300);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->point.norm(), 0.1, 0.01) << "on the ball of radius 0.1";
  EXPECT_FALSE(b.controller.pick(2, 2).has_value());
  const double yaw = b.camera.yaw;
  const std::vector<Vec3> before = b.session.simulation().state().x;
  b.controller.mouseMove(400, 300);
  b.controller.mouseButton(MouseButton::Right, true, false);
  b.controller.mouseMove(500, 300);
  b.controller.mouseButton(MouseButton::Right, false, false);
  EXPECT_NE(b.camera.yaw, yaw);
  EXPECT_EQ(b.session.simulation().state().x, before);
  EXPECT_TRUE(b.session.recording().empty()) << "navigation records nothing";
}

}  // namespace
}  // namespace galsculpt
