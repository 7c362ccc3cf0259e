#include "app/cli/cli.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "tests/app/cli/cli_run.h"

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

}  // namespace
}  // namespace galsculpt
