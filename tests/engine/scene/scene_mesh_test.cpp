#include "engine/scene/scene_mesh.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "solver/io/input_error.h"
#include "solver/io/tetgen_io.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

// Generated meshes are made once and read back from the cache, identical; a file mesh is
// scaled and moved as the scene says.
TEST(SceneMesh, GeneratedMeshesAreCachedAndFileMeshesTransformed) {
  test::TempDir dir;
  const char* old = std::getenv("GALSCULPT_CACHE_DIR");
  const std::string saved = old ? old : "";
  setenv("GALSCULPT_CACHE_DIR", (dir / "cache").c_str(), 1);
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
  if (old)
    setenv("GALSCULPT_CACHE_DIR", saved.c_str(), 1);
  else
    unsetenv("GALSCULPT_CACHE_DIR");

  const TetMesh bar = test::gridBar(2, 2, 2, 0.1);
  writeTetGen(dir / "bar", bar);
  test::writeText(dir / "file.json",
                  R"({"mesh": {"file": "bar.node", "scale": 2.0, "translate": [1, 0, 0]}})");
  const TetMesh moved = loadSceneMesh(loadScene(dir / "file.json"));
  ASSERT_EQ(moved.numVertices(), bar.numVertices());
  for (int v = 0; v < bar.numVertices(); ++v)
    EXPECT_LT((moved.vertices[v] - (2.0 * bar.vertices[v] + Vec3(1, 0, 0))).norm(), 1e-12);
}

}  // namespace
}  // namespace galsculpt
