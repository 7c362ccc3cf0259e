#include "engine/scene/scene_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include "engine/surface/surface_io.h"
#include "solver/io/input_error.h"
#include "solver/io/tetgen_io.h"
#include "solver/mesh/locality_order.h"
#include "solver/mesh/shape_generators.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

// Generated meshes are made once and read back from the cache, identical; a file mesh is
// scaled and moved as the scene says.
TEST(SceneMesh, GeneratedMeshesAreCachedAndFileMeshesTransformed) {
  test::TempDir dir;
  const test::ScopedEnv cache("GALSCULPT_CACHE_DIR", (dir / "cache").string());
  EXPECT_EQ(cacheDirectory(), dir / "cache");
  test::writeText(dir / "gen.json",
                  R"({"mesh": {"generate": "sphere", "tets": 3000, "radius": 0.05}})");
  const SceneDescription gen = loadScene(dir / "gen.json");
  std::vector<std::string> progress;
  const TetMesh first = loadSceneMesh(gen, [&](const std::string& l) { progress.push_back(l); });
  EXPECT_FALSE(progress.empty()) << "meshing reports progress";
  EXPECT_GT(first.numTets(), 2500);
  int cached = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir / "cache"))
    cached += e.path().extension() == ".node";
  EXPECT_EQ(cached, 1);
  progress.clear();
  const TetMesh second = loadSceneMesh(gen, [&](const std::string& l) { progress.push_back(l); });
  EXPECT_TRUE(progress.empty()) << "read from the cache, not meshed again";
  EXPECT_EQ(second.tets, first.tets);
  EXPECT_EQ(second.vertices, first.vertices);
  // In locality order (locality_order.h), also when the cache holds another: an entry in
  // TetGen's order, written before the order existed, is read in it.
  TetMesh reordered = first;
  orderForLocality(reordered);
  EXPECT_EQ(reordered.vertices, first.vertices);
  EXPECT_EQ(reordered.tets, first.tets);
  TetMesh reversed = first;
  std::reverse(reversed.vertices.begin(), reversed.vertices.end());
  const int last = first.numVertices() - 1;
  for (Tet& t : reversed.tets)
    for (int& v : t) v = last - v;
  std::reverse(reversed.tets.begin(), reversed.tets.end());
  reversed.faces.clear();
  reversed.faceMarkers.clear();
  reversed.vertexMarkers.clear();
  for (const auto& e : fs::recursive_directory_iterator(dir / "cache"))
    if (e.path().extension() == ".node")
      writeTetGen(fs::path(e.path()).replace_extension(), reversed);
  const TetMesh third = loadSceneMesh(gen);
  EXPECT_EQ(third.vertices, first.vertices);
  EXPECT_EQ(third.tets, first.tets);

  const TetMesh bar = test::gridBar(2, 2, 2, 0.1);
  writeTetGen(dir / "bar", bar);
  test::writeText(dir / "file.json",
                  R"({"mesh": {"file": "bar.node", "scale": 2.0, "translate": [1, 0, 0]}})");
  const TetMesh moved = loadSceneMesh(loadScene(dir / "file.json"));
  ASSERT_EQ(moved.numVertices(), bar.numVertices());
  for (int v = 0; v < bar.numVertices(); ++v)
    EXPECT_LT((moved.vertices[v] - (2.0 * bar.vertices[v] + Vec3(1, 0, 0))).norm(), 1e-12);
}

// The cache's key covers what decides the mesh: two surfaces of one file name, and one surface
// moved, are three meshes; a damaged entry is meshed again, and said.
TEST(SceneMesh, TheCacheKeyHoldsTheSourcesContentAndTransformAndADamagedEntryIsRebuilt) {
  test::TempDir dir;
  const test::ScopedEnv cache("GALSCULPT_CACHE_DIR", (dir / "cache").string());
  fs::create_directories(dir / "a");
  fs::create_directories(dir / "b");
  writeSurface(dir / "a" / "ball.obj", makeIcosphere(0.05, 2));
  writeSurface(dir / "b" / "ball.obj", makeIcosphere(0.08, 2));
  auto scene = [&](const std::string& folder, const std::string& translate) {
    const fs::path file = dir / folder / ("scene" + translate.substr(1, 1) + ".json");
    test::writeText(
        file, R"({"mesh": {"import": "ball.obj", "tets": 3000, "translate": )" + translate + "}}");
    return loadScene(file);
  };
  auto extent = [](const TetMesh& m) {
    double x = -1e9;
    for (const Vec3& v : m.vertices) x = std::max(x, v.x());
    return x;
  };
  const TetMesh small = loadSceneMesh(scene("a", "[0, 0, 0]"));
  const TetMesh large = loadSceneMesh(scene("b", "[0, 0, 0]"));
  EXPECT_NEAR(extent(small), 0.05, 0.005);
  EXPECT_NEAR(extent(large), 0.08, 0.005) << "not the other ball.obj's cached mesh";
  const TetMesh moved = loadSceneMesh(scene("a", "[1, 0, 0]"));
  EXPECT_NEAR(extent(moved), 1.05, 0.005) << "translate is part of the key";

  // Cut every cached .ele short, as a full disk would have left it.
  int damaged = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir / "cache")) {
    if (e.path().extension() != ".ele") continue;
    fs::resize_file(e.path(), fs::file_size(e.path()) / 2);
    ++damaged;
  }
  EXPECT_EQ(damaged, 3);
  std::vector<std::string> progress;
  const TetMesh again =
      loadSceneMesh(scene("b", "[0, 0, 0]"), [&](const std::string& l) { progress.push_back(l); });
  EXPECT_EQ(again.tets, large.tets) << "meshed again, the same";
  ASSERT_FALSE(progress.empty());
  EXPECT_NE(progress[0].find("the cached mesh is damaged"), std::string::npos) << progress[0];
}

// Generated spheres of small counts were refused (TetGen's refinement jumped over 100 and 700
// tets on the one surface tried); a finer sphere is tried next and reaches them.
TEST(SceneMesh, SmallGeneratedSpheresReachTheirCounts) {
  test::TempDir dir;
  const test::ScopedEnv cache("GALSCULPT_CACHE_DIR", (dir / "cache").string());
  for (const int tets : {100, 150, 700, 1000, 4000}) {
    const fs::path scene = dir / ("sphere" + std::to_string(tets) + ".json");
    test::writeText(scene, R"({"mesh": {"generate": "sphere", "tets": )" + std::to_string(tets) +
                               R"(, "radius": 0.1}})");
    const TetMesh mesh = loadSceneMesh(loadScene(scene));
    EXPECT_NEAR(mesh.numTets(), tets, 0.15 * tets) << tets << " tets asked";
  }
}

// A count TetGen cannot reach for a generated surface is the scene's error: the file, the key,
// the closest count, and a count that works (or that a larger one is needed).
TEST(SceneMesh, AnUnreachableTetCountNamesTheSceneTheKeyAndACountThatWorks) {
  test::TempDir dir;
  const test::ScopedEnv cache("GALSCULPT_CACHE_DIR", (dir / "cache").string());
  for (const auto& [shape, tets] : {std::pair<std::string, int>{"charpy", 100}, {"steak", 500}}) {
    const fs::path scene = dir / (shape + std::to_string(tets) + ".json");
    test::writeText(scene, R"({"mesh": {"generate": ")" + shape + R"(", "tets": )" +
                               std::to_string(tets) + "}}");
    std::string works;
    try {
      loadSceneMesh(loadScene(scene));
      ADD_FAILURE() << shape << " " << tets << " tets: TetGen reached it after all; pick another";
      continue;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(scene.string() + ": $.mesh.tets: could not reach " +
                          std::to_string(tets) + " tets"),
                std::string::npos)
          << what;
      const size_t count = what.rfind("; ");
      ASSERT_NE(what.find(" tets is a count that works", count), std::string::npos) << what;
      works = what.substr(count + 2, what.find(' ', count + 2) - count - 2);
    }
    const fs::path suggested = dir / (shape + "_suggested.json");
    test::writeText(suggested,
                    R"({"mesh": {"generate": ")" + shape + R"(", "tets": )" + works + "}}");
    EXPECT_NO_THROW(loadSceneMesh(loadScene(suggested)))
        << "the suggested " << works << " tets work for " << shape;
  }
}

}  // namespace
}  // namespace galsculpt
