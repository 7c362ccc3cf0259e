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

TEST(Cli, SceneCheck) {
  const fs::path scene = fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json";
  const CliRun r = run({"scene", "check", scene.string(), "--load-mesh"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("material: clay"), std::string::npos);
  EXPECT_NE(r.out.find("tets\n"), std::string::npos);
}

}  // namespace
}  // namespace galsculpt
