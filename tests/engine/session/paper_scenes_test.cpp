// The paper's generated scenes at full size: counts within +-15 %, closed, one piece, and
// bit-identical when generated twice (labelled `slow`: about ten seconds on two cores).
#include <gtest/gtest.h>
#include <stdlib.h>

#include "engine/scene/scene.h"
#include "engine/scene/scene_mesh.h"
#include "solver/mesh/mesh_stats.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

TetMesh loadWithCache(const std::string& scene, const fs::path& cache) {
  setenv("GALSCULPT_CACHE_DIR", cache.c_str(), 1);
  const SceneDescription s =
      loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / (scene + ".json"));
  TetMesh mesh = loadSceneMesh(s);
  unsetenv("GALSCULPT_CACHE_DIR");
  return mesh;
}

class PaperScene : public ::testing::TestWithParam<std::pair<std::string, int>> {};

TEST_P(PaperScene, GeneratesTheRequestedSizeClosedAndWhole) {
  test::TempDir cache;
  const auto& [scene, tets] = GetParam();
  const TetMesh mesh = loadWithCache(scene, cache.path());
  EXPECT_NEAR(mesh.numTets(), tets, 0.15 * tets);
  const TetMeshStats s = computeStats(mesh);
  EXPECT_TRUE(s.watertight) << s.boundaryProblem;
  EXPECT_EQ(s.pieces, 1);
  EXPECT_GT(s.minQuality, 0.01) << "no flat tets";
}

INSTANTIATE_TEST_SUITE_P(Scenes, PaperScene,
                         ::testing::Values(std::make_pair(std::string("hanging_sphere"), 35000),
                                           std::make_pair(std::string("charpy"), 28000),
                                           std::make_pair(std::string("steak"), 186000)),
                         [](const auto& info) { return info.param.first; });

TEST(PaperScenes, GenerationIsDeterministic) {
  test::TempDir a, b;
  const TetMesh first = loadWithCache("hanging_sphere", a.path());
  const TetMesh second = loadWithCache("hanging_sphere", b.path());
  EXPECT_EQ(first.vertices, second.vertices);
  EXPECT_EQ(first.tets, second.tets);
}

}  // namespace
}  // namespace galsculpt
