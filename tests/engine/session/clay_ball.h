// The default scene's clay ball and helpers shared by the sculpt session's and the sculptor's
// tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "engine/scene/scene_mesh.h"
#include "engine/session/sculpt_session.h"
#include "solver/fracture/knife.h"
#include "tests/test_util.h"

namespace galsculpt::test {

namespace fs = std::filesystem;

inline const fs::path kAssets = fs::path(GALSCULPT_SOURCE_DIR) / "assets";

// The default scene: a clay ball of radius 0.1 m (1498 vertices) held at its bottom.
struct ClayBall {
  SceneDescription scene = loadScene(kAssets / "scenes" / "default.json");
  TetMesh mesh = loadSceneMesh(scene);
};

inline const ClayBall& clayBall() {
  static const ClayBall ball;
  return ball;
}

inline SceneDescription rubberBall() {
  SceneDescription s = clayBall().scene;
  s.material = materialPreset("rubber");
  return s;
}

inline double weightAt(double distance, double radius) {
  const double s = 1.0 - distance * distance / (radius * radius);
  return s > 0.0 ? s * s : 0.0;
}

inline BrushStroke brushAt(Tool kind, const Vec3& center, const Vec3& normal, double radius,
                           double strength = 0.1) {
  BrushStroke b;
  b.kind = kind;
  b.center = center;
  b.normal = normal;
  b.radius = radius;
  b.strength = strength;
  return b;
}

inline void expectSameState(const SimulationSnapshot& a, const SimulationSnapshot& b) {
  ASSERT_EQ(a.x.size(), b.x.size());
  EXPECT_EQ(a.frame, b.frame);
  EXPECT_EQ(a.time, b.time);
  EXPECT_TRUE(a.x == b.x) << "positions differ";
  EXPECT_TRUE(a.v == b.v) << "velocities differ";
  EXPECT_TRUE(a.damaged == b.damaged) << "damage differs";
  EXPECT_TRUE(a.crossing == b.crossing) << "where blades crossed differs";
  EXPECT_TRUE(a.plasticStrain == b.plasticStrain) << "plastic strain differs";
  ASSERT_EQ(a.plasticInverse.size(), b.plasticInverse.size());
  for (size_t t = 0; t < a.plasticInverse.size(); ++t)
    ASSERT_TRUE(a.plasticInverse[t] == b.plasticInverse[t]) << "plastic state of tet " << t;
  ASSERT_EQ(a.anchors.size(), b.anchors.size());
  for (size_t i = 0; i < a.anchors.size(); ++i) {
    EXPECT_EQ(a.anchors[i].vertices, b.anchors[i].vertices);
    EXPECT_TRUE(a.anchors[i].origin == b.anchors[i].origin);
    EXPECT_EQ(a.anchors[i].springWeights, b.anchors[i].springWeights);
  }
  EXPECT_EQ(a.anchorTags, b.anchorTags);
}

// A blade that passes through the whole ball in the plane x = planeX.
inline void cutThrough(SculptSession& s, double planeX, const Symmetry& symmetry = {}) {
  s.knife(Vec3(planeX, 0.3, -0.3), Vec3(planeX, 0.3, 0.3), Vec3(planeX, -0.3, -0.3),
          Vec3(planeX, -0.3, 0.3), symmetry);
}

}  // namespace galsculpt::test
