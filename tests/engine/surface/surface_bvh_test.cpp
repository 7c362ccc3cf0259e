#include "engine/surface/surface_bvh.h"

#include <gtest/gtest.h>

#include <random>

#include "engine/scene/scene_mesh.h"
#include "engine/session/simulation.h"
#include "solver/mesh/tet_mesh.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

// The nearest hit by testing every face: what the BVH must reproduce.
double bruteForceHit(const TriMesh& m, const Vec3& o, const Vec3& d) {
  double best = 1e300;
  for (const Tri& t : m.faces) {
    const Vec3 a = m.vertices[t[0]], e1 = m.vertices[t[1]] - a, e2 = m.vertices[t[2]] - a;
    const Vec3 p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-300) continue;
    const Vec3 s = o - a;
    const double u = s.dot(p) / det, v = d.dot(s.cross(e1)) / det, h = e2.dot(s.cross(e1)) / det;
    if (u >= 0 && v >= 0 && u + v <= 1 && h > 0) best = std::min(best, h);
  }
  return best;
}

TriMesh sphereSurface() {
  const SceneDescription scene =
      loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json");
  Simulation sim(scene, loadSceneMesh(scene));
  return sim.surface().mesh;
}

// The distance to the nearest face equals the least over every face (closest points by
// barycentric minimization on a fine grid of each face, an independent route).
TEST(SurfaceBvh, DistanceIsTheLeastOverEveryFace) {
  TriMesh m = sphereSurface();
  SurfaceBvh bvh;
  bvh.build(m);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 p(u(rng), u(rng), u(rng));
    double brute = 1e300;
    for (const Tri& t : m.faces) {
      const Vec3 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
      constexpr int kSteps = 20;
      for (int i = 0; i <= kSteps; ++i)
        for (int j = 0; i + j <= kSteps; ++j) {
          const Vec3 q = a + (b - a) * (double(i) / kSteps) + (c - a) * (double(j) / kSteps);
          brute = std::min(brute, (q - p).norm());
        }
    }
    const double d = bvh.distance(m, p);
    EXPECT_LE(d, brute + 1e-12) << trial;
    EXPECT_GT(d, brute - 3e-4) << trial << " (the grid's spacing bounds its error)";
  }
  EXPECT_EQ(bvh.distance(m, m.vertices[7]), 0.0);
}

TEST(SurfaceBvh, HitsTheSameNearestFaceAsTestingEveryFace) {
  TriMesh m = sphereSurface();
  SurfaceBvh bvh;
  bvh.build(m);
  EXPECT_EQ(bvh.numFaces(), m.numFaces());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int hits = 0;
  for (int i = 0; i < 500; ++i) {
    const Vec3 origin = 0.3 * Vec3(u(rng), u(rng), u(rng)).normalized();
    const Vec3 dir = (0.08 * Vec3(u(rng), u(rng), u(rng)) - origin).normalized();
    const double expected = bruteForceHit(m, origin, dir);
    const std::optional<RayHit> hit = bvh.intersect(m, origin, dir);
    if (expected > 1e299) {
      EXPECT_FALSE(hit.has_value()) << "ray " << i;
      continue;
    }
    ASSERT_TRUE(hit.has_value()) << "ray " << i;
    EXPECT_NEAR(hit->distance, expected, 1e-12) << "ray " << i;
    EXPECT_NEAR((hit->point - (origin + expected * dir)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(hit->normal.norm(), 1.0, 1e-12);
    ++hits;
  }
  EXPECT_GT(hits, 300);
  // From outside, the first hit on a sphere faces the ray.
  const auto top = bvh.intersect(m, Vec3(0, 1, 0), Vec3(0, -1, 0));
  ASSERT_TRUE(top.has_value());
  EXPECT_GT(top->normal.y(), 0.9);
  EXPECT_NEAR(top->point.y(), 0.1, 0.005);
  EXPECT_FALSE(bvh.intersect(m, Vec3(0, 1, 0), Vec3(0, 1, 0)).has_value()) << "pointing away";
  EXPECT_FALSE(bvh.intersect(m, Vec3(0, 1, 0), Vec3(0, -1, 0), 0.5).has_value()) << "beyond maxT";
}

TEST(SurfaceBvh, RefitFollowsMovedVerticesLikeARebuild) {
  TriMesh m = sphereSurface();
  SurfaceBvh refitted;
  refitted.build(m);
  for (Vec3& p : m.vertices) p = Vec3(2.0 * p.x() + 0.5, p.y() + 0.1 * p.x() * p.x(), p.z());
  refitted.refit(m);
  SurfaceBvh rebuilt;
  rebuilt.build(m);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Vec3 origin = Vec3(0.5, 0.0, 0.0) + 0.5 * Vec3(u(rng), u(rng), u(rng)).normalized();
    const Vec3 dir = (Vec3(0.5, 0.0, 0.0) + 0.1 * Vec3(u(rng), u(rng), u(rng)) - origin);
    const auto a = refitted.intersect(m, origin, dir), b = rebuilt.intersect(m, origin, dir);
    ASSERT_EQ(a.has_value(), b.has_value());
    if (a) {
      EXPECT_DOUBLE_EQ(a->distance, b->distance);
    }
  }
}

// After a cut the pick tells the pieces apart: each side's faces belong to their own piece.
TEST(SurfaceBvh, APickAfterACutReachesThePieceUnderTheCursor) {
  const SceneDescription scene =
      loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json");
  Simulation sim(scene, loadSceneMesh(scene));
  sim.cut(sweptBladeSurface(Vec3(0, 0.3, -0.3), Vec3(0, 0.3, 0.3), Vec3(0, -0.3, -0.3),
                            Vec3(0, -0.3, 0.3)));
  const VisualSurface& surface = sim.surface();
  SurfaceBvh bvh;
  bvh.build(surface.mesh);
  const auto left = bvh.intersect(surface.mesh, Vec3(-0.05, 1, 0), Vec3(0, -1, 0));
  const auto right = bvh.intersect(surface.mesh, Vec3(0.05, 1, 0), Vec3(0, -1, 0));
  ASSERT_TRUE(left && right);
  const int leftPiece = sim.pieceOf(surface.cellVertex[left->face]);
  const int rightPiece = sim.pieceOf(surface.cellVertex[right->face]);
  EXPECT_NE(leftPiece, rightPiece);
  EXPECT_EQ(leftPiece, sim.pieceOf(sim.nearestVertex(Vec3(-0.09, 0, 0))));
  EXPECT_EQ(rightPiece, sim.pieceOf(sim.nearestVertex(Vec3(0.09, 0, 0))));
}

// The picker follows its surface: moved positions under a new generation (a refit), other faces
// under the same topology key (the face count changed: a rebuild), and another key.
TEST(SurfacePicker, RefitsOnANewGenerationAndRebuildsOnNewFaces) {
  TriMesh m = sphereSurface();
  SurfacePicker picker;
  const Vec3 down(0, -1, 0), above(0, 2, 0);
  const auto first = picker.intersect(m, 1, 1, above, down);
  ASSERT_TRUE(first);
  for (Vec3& p : m.vertices) p.y() += 0.25;
  const auto moved = picker.intersect(m, 1, 2, above, down);
  ASSERT_TRUE(moved);
  EXPECT_NEAR(moved->distance, first->distance - 0.25, 1e-12);
  const int face = moved->face;
  m.faces.erase(m.faces.begin() + face);  // the face under the ray goes: another face count
  const auto rebuilt = picker.intersect(m, 1, 2, above, down);
  ASSERT_TRUE(rebuilt);
  EXPECT_NE(rebuilt->face, face);
  SurfaceBvh fresh;
  fresh.build(m);
  EXPECT_DOUBLE_EQ(rebuilt->distance, fresh.intersect(m, above, down)->distance);
  // The same count under another key (new damage) is rebuilt too.
  std::swap(m.faces.front(), m.faces.back());
  fresh.build(m);
  const auto swapped = picker.intersect(m, 2, 2, above, down);
  ASSERT_TRUE(swapped);
  EXPECT_EQ(swapped->face, fresh.intersect(m, above, down)->face);
}

}  // namespace
}  // namespace galsculpt
