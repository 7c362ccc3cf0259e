#include "app/cli/cli.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "app/render/view_content.h"
#include "engine/scene/scene_mesh.h"
#include "engine/session/simulation.h"
#include "solver/fracture/knife.h"
#include "solver/mesh/surface_checks.h"
#include "tests/app/cli/cli_run.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::run;

TEST(Cli, SceneCheck) {
  const fs::path scene = test::kDefaultSceneFile;
  const CliRun r = run({"scene", "check", scene.string(), "--load-mesh"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("material: clay"), std::string::npos);
  EXPECT_NE(r.out.find("tets\n"), std::string::npos);
}

// `open` with no FILE opens the default scene, as its usage says (it read past the end of its
// operands and crashed).
TEST(Cli, OpenWithNoFileOpensTheDefaultScene) {
  test::TempDir dir;
  const CliRun r = run({"open", "--headless", "--out", (dir / "v").string(), "--size", "64x40"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_TRUE(fs::exists(dir / "v" / "view_front.png")) << r.out;
}

// A tet mesh exported with its damage shows its cracks (render, open): the cut ball's two
// halves are two closed shells; the same mesh without its .damage is one.
TEST(Cli, ATetMeshWithItsDamageBesideItShowsCracked) {
  test::TempDir dir;
  const SceneDescription scene = loadScene(test::kDefaultSceneFile);
  Simulation sim(scene, loadSceneMesh(scene));
  ASSERT_GT(sim.cut(sweptBladeSurface(Vec3(-0.2, 0.2, 0.02), Vec3(0.2, 0.2, 0.02),
                                      Vec3(-0.2, -0.2, 0.02), Vec3(0.2, -0.2, 0.02))),
            0);
  sim.writeTetsWithDamage(dir / "cut");
  std::ostringstream log;
  const ViewContent cracked = loadViewContent(dir / "cut.node", log);
  EXPECT_EQ(countSurfacePieces(cracked.surface), 2);
  EXPECT_TRUE(analyzeSurface(cracked.surface).closedManifold());
  bool said = false;
  for (const std::string& fact : cracked.facts)
    said |= fact.find("damaged edges (cut.damage), 2 piece(s)") != std::string::npos;
  EXPECT_TRUE(said) << ::testing::PrintToString(cracked.facts);
  fs::remove(dir / "cut.damage");
  EXPECT_EQ(countSurfacePieces(loadViewContent(dir / "cut.node", log).surface), 1);
}

}  // namespace
}  // namespace galsculpt
