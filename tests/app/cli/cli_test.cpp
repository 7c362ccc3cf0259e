#include "app/cli/cli.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "tests/app/cli/cli_run.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::run;

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
