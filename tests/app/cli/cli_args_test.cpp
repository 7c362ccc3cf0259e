#include "app/cli/cli.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "gpu/cuda_step_backend.h"
#include "tests/app/cli/cli_run.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::run;

// --backend on run (and play, bench, open): cpu and auto run without a note; cuda runs on the GPU
// or says why not; anything else is a usage error.
TEST(Cli, BackendFlag) {
  test::TempDir dir;
  const fs::path scene = test::kDefaultSceneFile;
  const CliRun cpu = run(
      {"run", scene.string(), "--frames", "1", "--out", (dir / "a").string(), "--backend", "cpu"});
  ASSERT_EQ(cpu.code, kExitOk) << cpu.err;
  EXPECT_EQ(cpu.err.find("running on the CPU"), std::string::npos) << cpu.err;
  const CliRun cuda = run(
      {"run", scene.string(), "--frames", "1", "--out", (dir / "b").string(), "--backend", "cuda"});
  ASSERT_EQ(cuda.code, kExitOk) << cuda.err;
  std::string reason;
  const SimModel probe = buildSimModel(test::gridBar(1, 1, 1, 0.1), MaterialParams{});
  StepSettings multigrid;
  multigrid.type = SolverType::Multigrid;
  if (!gpu::makeCudaStepBackend(probe, multigrid, reason)) {
    EXPECT_NE(cuda.err.find("note: the CUDA backend is not available (" + reason + ")"),
              std::string::npos)
        << cuda.err;
  }
  // auto (the scene's default) falls back without a word: the user did not ask for the GPU.
  const CliRun automatic = run(
      {"run", scene.string(), "--frames", "1", "--out", (dir / "d").string(), "--backend", "auto"});
  ASSERT_EQ(automatic.code, kExitOk) << automatic.err;
  EXPECT_EQ(automatic.err.find("note:"), std::string::npos) << automatic.err;
  const fs::path script = fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scripts" / "sphere_cut.json";
  const std::vector<std::vector<std::string>> bad = {
      {"run", scene.string(), "--frames", "1", "--out", (dir / "c").string()},
      {"play", script.string(), "--out", (dir / "c").string()},
      {"bench"},
      {"open", scene.string(), "--headless", "--out", (dir / "c").string()}};
  for (std::vector<std::string> args : bad) {
    args.insert(args.end(), {"--backend", "gpu"});
    const CliRun r = run(args);
    EXPECT_EQ(r.code, kExitUsage) << args[0];
    EXPECT_NE(r.err.find("--backend must be auto, cpu, cuda or device-like"), std::string::npos)
        << args[0] << ": " << r.err;
  }
}

// --solver-option sets the scene's solver keys (run, play, bench, open): the frames take them;
// an unknown key or a malformed list is a usage error naming the keys, a value out of range an
// input error naming the option.
TEST(Cli, SolverOptionFlag) {
  test::TempDir dir;
  const fs::path scene = test::kDefaultSceneFile;
  const CliRun one = run({"run", scene.string(), "--frames", "3", "--out", (dir / "a").string(),
                          "--solver-option", "newton_iters=1,pcg_tolerance=0", "--backend", "cpu"});
  ASSERT_EQ(one.code, kExitOk) << one.err;
  std::istringstream csv(test::readText(dir / "a" / "metrics.csv"));
  std::string header, line;
  std::getline(csv, header);
  std::vector<std::string> names;
  for (std::istringstream h(header); std::getline(h, line, ',');) names.push_back(line);
  const size_t column = std::find(names.begin(), names.end(), "newton_iterations") - names.begin();
  ASSERT_LT(column, names.size());
  int rows = 0;
  while (std::getline(csv, line)) {
    std::vector<std::string> cells;
    for (std::istringstream r(line); std::getline(r, header, ',');) cells.push_back(header);
    ASSERT_EQ(cells.size(), names.size());
    EXPECT_EQ(cells[column], "1") << "newton_iters=1: one Newton iteration a frame";
    ++rows;
  }
  EXPECT_EQ(rows, 3);
  const fs::path script = fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scripts" / "sphere_cut.json";
  const std::vector<std::vector<std::string>> commands = {
      {"run", scene.string(), "--frames", "1", "--out", (dir / "c").string()},
      {"play", script.string(), "--out", (dir / "c").string()},
      {"bench"},
      {"open", scene.string(), "--headless", "--out", (dir / "c").string()}};
  for (std::vector<std::string> args : commands) {
    args.insert(args.end(), {"--solver-option", "newton_iters=2,sweeps=3"});
    const CliRun r = run(args);
    EXPECT_EQ(r.code, kExitUsage) << args[0];
    EXPECT_NE(r.err.find("--solver-option: unknown solver option 'sweeps' (options: preset, "),
              std::string::npos)
        << args[0] << ": " << r.err;
  }
  const CliRun malformed = run({"run", scene.string(), "--frames", "1", "--out",
                                (dir / "d").string(), "--solver-option", "newton_iters"});
  EXPECT_EQ(malformed.code, kExitUsage);
  EXPECT_NE(malformed.err.find("'newton_iters' is not KEY=VALUE"), std::string::npos)
      << malformed.err;
  const CliRun outOfRange = run({"run", scene.string(), "--frames", "1", "--out",
                                 (dir / "e").string(), "--solver-option=newton_iters=500"});
  EXPECT_EQ(outOfRange.code, kExitBadInput);
  EXPECT_NE(outOfRange.err.find("solver options newton_iters=500: "), std::string::npos)
      << outOfRange.err;
  EXPECT_NE(outOfRange.err.find("$.solver.newton_iters"), std::string::npos) << outOfRange.err;
}

}  // namespace
}  // namespace galsculpt
