#include "engine/surface/surface_io.h"

#include <gtest/gtest.h>

#include <sstream>

#include "engine/surface/surface_builder.h"
#include "solver/fracture/knife.h"
#include "solver/io/input_error.h"
#include "solver/mesh/shape_generators.h"
#include "solver/mesh/surface_checks.h"
#include "tests/surface_expectations.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

class SurfaceRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(SurfaceRoundTrip, SameCountsAndPositions) {
  test::TempDir dir;
  const TriMesh sphere = makeIcosphere(0.25, 2);
  const fs::path file = dir / ("sphere" + GetParam());
  writeSurface(file, sphere);
  const TriMesh back = readSurface(file);
  ASSERT_EQ(back.numVertices(), sphere.numVertices());
  ASSERT_EQ(back.numFaces(), sphere.numFaces());
  EXPECT_TRUE(analyzeSurface(back).closedManifold()) << "welded back into a closed surface";
  EXPECT_NEAR(enclosedVolume(back), enclosedVolume(sphere), 1e-6 * enclosedVolume(sphere));
  // Positions come back within float precision, in some order.
  const BoundingBox a = boundingBox(sphere.vertices), b = boundingBox(back.vertices);
  EXPECT_LT((a.min - b.min).norm(), 1e-6);
  EXPECT_LT((a.max - b.max).norm(), 1e-6);
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename().string().rfind(".galsculpt-export", 0), std::string::npos)
        << "temporary export folder left behind";
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, SurfaceRoundTrip,
                         ::testing::Values(".obj", ".ply", ".stl", ".gltf", ".glb"),
                         [](const auto& info) { return info.param.substr(1); });

// A bar cut in two whose halves have moved apart: the visualization surface of two pieces.
VisualSurface cutBarSurface() {
  SimModel model = buildSimModel(test::gridBar(4, 3, 2, 0.1), MaterialParams{});
  SimState state = initialState(model);
  cutAlongSurface(model, state,
                  sweptBladeSurface(Vec3(0.21, -1, -1), Vec3(0.21, -1, 1), Vec3(0.21, 1, -1),
                                    Vec3(0.21, 1, 1)));
  for (int v = 0; v < model.numVertices(); ++v) {
    if (model.mesh.vertices[v].x() > 0.21) state.x[v] += Vec3(0.05, 0.01, 0);
  }
  SurfaceBuilder builder(model);
  builder.update(model, state);
  return builder.surface();
}

class VisualSurfaceRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(VisualSurfaceRoundTrip, SameCountsPositionsAndPieces) {
  test::TempDir dir;
  const VisualSurface s = cutBarSurface();
  ASSERT_TRUE(analyzeSurface(s.mesh).closedManifold());
  const fs::path file = dir / ("cut" + GetParam());
  writeVisualSurface(file, s);
  const TriMesh back = readSurface(file);
  ASSERT_EQ(back.numFaces(), s.mesh.numFaces());
  ASSERT_EQ(back.numVertices(), s.mesh.numVertices()) << "outer and crack parts weld back";
  EXPECT_TRUE(analyzeSurface(back).closedManifold()) << analyzeSurface(back).describeProblem();
  EXPECT_EQ(countSurfacePieces(back), 2);
  EXPECT_NEAR(enclosedVolume(back), enclosedVolume(s.mesh), 1e-6 * enclosedVolume(s.mesh));
  // Every vertex comes back (float precision), in some order.
  for (const Vec3& p : s.mesh.vertices) {
    double nearest = 1e9;
    for (const Vec3& q : back.vertices) nearest = std::min(nearest, (p - q).norm());
    ASSERT_LT(nearest, 1e-6);
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, VisualSurfaceRoundTrip,
                         ::testing::Values(".obj", ".ply", ".stl", ".gltf", ".glb"),
                         [](const auto& info) { return info.param.substr(1); });

TEST(SurfaceIo, ObjKeepsTagsAsGroupsAndCoincidentCopiesApart) {
  test::TempDir dir;
  // An uncut-open slit: both sides' copies sit at the same positions.
  SimModel model = buildSimModel(test::gridBar(4, 3, 2, 0.1), MaterialParams{});
  SimState state = initialState(model);
  cutAlongSurface(model, state,
                  sweptBladeSurface(Vec3(0.21, -1, -1), Vec3(0.21, -1, 0.1), Vec3(0.21, 1, -1),
                                    Vec3(0.21, 1, 0.1)));
  SurfaceBuilder builder(model);
  builder.update(model, state);
  writeVisualSurface(dir / "slit.obj", builder.surface());
  const std::string text = test::readText(dir / "slit.obj");
  EXPECT_NE(text.find("\ng outer\n"), std::string::npos);
  EXPECT_NE(text.find("\ng crack\n"), std::string::npos);
  int vertices = 0, normals = 0;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    vertices += line.rfind("v ", 0) == 0;
    normals += line.rfind("vn ", 0) == 0;
  }
  EXPECT_EQ(vertices, builder.surface().mesh.numVertices()) << "no vertex merged by position";
  // Smooth normals per vertex for the outer faces, one per crack face (shaded flat).
  const int crackFaces = facesWithTag(builder.surface(), SurfaceTag::Crack).numFaces();
  ASSERT_GT(crackFaces, 0);
  EXPECT_EQ(normals, builder.surface().mesh.numVertices() + crackFaces);
  const TriMesh indexed = test::readObjByIndex((dir / "slit.obj").string());
  EXPECT_EQ(indexed.faces, builder.surface().mesh.faces);
  EXPECT_TRUE(analyzeSurface(indexed).closedManifold());
  EXPECT_THROW(writeVisualSurface(dir / "missing" / "slit.obj", builder.surface()), OutputError);
}

TEST(SurfaceIo, ObjWritesNoMaterialFileAndGltfKeepsItsBuffer) {
  test::TempDir dir;
  writeSurface(dir / "a.obj", makeIcosphere(1.0, 1));
  EXPECT_FALSE(fs::exists(dir / "a.mtl"));
  writeSurface(dir / "b.gltf", makeIcosphere(1.0, 1));
  EXPECT_TRUE(fs::exists(dir / "b.gltf"));
  EXPECT_EQ(readSurface(dir / "b.gltf").numFaces(), 80);
}

TEST(SurfaceIo, ReadsOff) {
  test::TempDir dir;
  test::writeText(dir / "t.off",
                  "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  const TriMesh m = readSurface(dir / "t.off");
  EXPECT_EQ(m.numVertices(), 4);
  EXPECT_EQ(m.numFaces(), 4);
  EXPECT_TRUE(analyzeSurface(m).closedManifold());
  EXPECT_NEAR(enclosedVolume(m), 1.0 / 6.0, 1e-12);
}

TEST(SurfaceIo, Errors) {
  test::TempDir dir;
  EXPECT_THROW_WITH(readSurface(dir / "missing.obj"), InputError, "missing.obj: file not found");
  test::writeText(dir / "garbage.stl", std::string(100, '\x01'));
  EXPECT_THROW(readSurface(dir / "garbage.stl"), InputError);
  EXPECT_THROW_WITH(writeSurface(dir / "x.xyz", makeIcosphere(1, 0)), OutputError,
                    "unknown surface format");
  EXPECT_THROW_WITH(writeSurface(dir / "no" / "x.obj", makeIcosphere(1, 0)), OutputError,
                    "does not exist");
}

TEST(SurfaceIo, FailedRenameIsReportedAndCleanedUp) {
  test::TempDir dir;
  fs::create_directories(dir / "s.stl" / "occupied");
  EXPECT_THROW_WITH(writeSurface(dir / "s.stl", makeIcosphere(1.0, 1)), OutputError,
                    "cannot write");
  size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 1u) << "the temporary export folder is removed";
  EXPECT_TRUE(fs::is_directory(dir / "s.stl" / "occupied"));
}

}  // namespace
}  // namespace galsculpt
