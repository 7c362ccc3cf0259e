#include "app/cli/cli.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/surface/surface_io.h"
#include "gpu/cuda_step_backend.h"
#include "solver/mesh/shape_generators.h"
#include "tests/app/cli/cli_run.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
CliRun run(const std::vector<std::string>& args) {
  return test::runCliCapture(args);
}

TEST(Cli, HelpAndVersion) {
  EXPECT_EQ(run({"--help"}).code, kExitOk);
  EXPECT_NE(run({"help"}).out.find("mesh import SURFACE OUT --tets N"), std::string::npos);
  EXPECT_NE(run({"--version"}).out.find("galsculpt "), std::string::npos);
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run({"frobnicate"}).code, kExitUsage);
  EXPECT_EQ(run({"mesh"}).code, kExitUsage);
  EXPECT_EQ(run({"mesh", "info"}).code, kExitUsage);
  EXPECT_EQ(run({"mesh", "info", "a.node", "--bogus"}).code, kExitUsage);
  const CliRun r = run({"mesh", "import", "a.obj", "b.node"});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_NE(r.err.find("needs --tets N"), std::string::npos);
  EXPECT_EQ(run({"mesh", "import", "a.obj", "b.node", "--tets", "ten"}).code, kExitUsage);
  EXPECT_EQ(run({"mesh", "convert", "a.node", "b.docx"}).code, kExitUsage);
}

TEST(Cli, BadInputExitsThreeWithFileAndLine) {
  const fs::path broken = fs::path(GALSCULPT_TEST_DATA) / "broken" / "nan_coordinate.node";
  const CliRun r = run({"mesh", "info", broken.string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("nan_coordinate.node:3: coordinate is not finite"), std::string::npos)
      << r.err;
  EXPECT_EQ(run({"mesh", "info", "/nonexistent/x.obj"}).code, kExitBadInput);
}

}  // namespace
}  // namespace galsculpt
