// The solver options' table read from scenes, written back, set from the command line's list,
// and listed in docs/scenes.md.
#include "engine/scene/solver_options_json.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <type_traits>

#include "solver/io/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

SolverOptions read(const nlohmann::json& solver) {
  return readSolverOptions(JsonObject(solver, "$.solver", "s.json"));
}

// Options unlike the paper preset's in every row (and numbers unlike either preset's).
SolverOptions unusual() {
  SolverOptions o = solverPreset(SolverPreset::Paper);
  o.type = SolverType::Reference;
  o.grid = "30/500/all";
  o.fineSweeps = 7;
  o.coarseIterations = 11;
  o.smoother = Smoother::Jacobi;
  o.coarseSolver = CoarseSolver::Cholesky;
  o.newtonIterations = 9;
  o.cycles = 2;
  o.pcgTolerance = 0.05;
  o.residualTolerance = 0.003;
  o.frameBudgetMs = 25.0;
  o.reuseStiffness = true;
  o.localNewton = true;
  o.predictedStart = true;
  o.acceleratedStart = true;
  o.convergePieces = true;
  o.energyGuard = EnergyGuard::Vertex;
  o.stiffnessTolerance = 0.002;
  o.backend = BackendRequest::Cpu;
  o.splitAggregates = false;
  return o;
}

TEST(SolverOptionsJson, EveryRowIsWrittenAndReadBack) {
  const SolverOptions o = unusual();
  forEachSolverOption([&](const auto& f) {
    // Read back over the paper preset (the JSON names it), each row proves it was read.
    EXPECT_FALSE(o.*f.member == f.paper) << f.key << ": the test sets every row";
  });
  const nlohmann::json j = solverOptionsJson(o);
  EXPECT_EQ(j["preset"], "paper");
  EXPECT_EQ(j["smoother"], "jacobi");
  EXPECT_EQ(j["grid"], "30/500/all");
  EXPECT_EQ(read(j), o);
}

// A preset gives the defaults; keys beside it override them.
TEST(SolverOptionsJson, ThePresetGivesTheDefaultsOfTheKeysNotGiven) {
  EXPECT_EQ(read(nlohmann::json::object()), SolverOptions{});
  const SolverOptions paper = read({{"preset", "paper"}, {"newton_iters", 3}});
  SolverOptions expected = solverPreset(SolverPreset::Paper);
  expected.newtonIterations = 3;
  EXPECT_EQ(paper, expected);
}

TEST(SolverOptionsJson, BadValuesNameTheirKey) {
  EXPECT_THROW_WITH(read({{"newton_iters", 500}}), InputError, "s.json: $.solver.newton_iters");
  EXPECT_THROW_WITH(read({{"pcg_tolerance", -1.0}}), InputError, "$.solver.pcg_tolerance");
  EXPECT_THROW_WITH(read({{"smoother", "sor"}}), InputError, "gauss_seidel");
  EXPECT_THROW_WITH(read({{"grid", "50"}}), InputError, "$.solver.grid: grid '50' must list");
  EXPECT_THROW_WITH(read({{"reuse_stiffness", 1}}), InputError, "$.solver.reuse_stiffness");
  EXPECT_THROW_WITH(read({{"preset", "fast"}}), InputError, "$.solver.preset");
  EXPECT_THROW_WITH(read({{"newton_iterations", 5}}), InputError, "newton_iterations");
}

TEST(SolverOptionsJson, CommandLineListsParseToJsonValues) {
  const SolverOverrides list = parseSolverOptionList(
      "newton_iters=10,preset=paper,grid=50/1000/all,pcg_tolerance=1e-3,"
      "reuse_stiffness=false");
  ASSERT_EQ(list.size(), 5u);
  EXPECT_EQ(list[0].first, "newton_iters");
  EXPECT_EQ(list[0].second, 10);
  EXPECT_EQ(list[1].second, "paper");
  EXPECT_EQ(list[2].second, "50/1000/all");
  EXPECT_EQ(list[3].second, 1e-3);
  EXPECT_EQ(list[4].second, false);
  EXPECT_THROW_WITH(parseSolverOptionList("newton_iters"), std::invalid_argument, "KEY=VALUE");
  EXPECT_THROW_WITH(parseSolverOptionList("=3"), std::invalid_argument, "KEY=VALUE");
  EXPECT_THROW_WITH(parseSolverOptionList("newton_iters=3,"), std::invalid_argument, "KEY=VALUE");
  EXPECT_THROW_WITH(parseSolverOptionList("sweeps=3"), std::invalid_argument,
                    "unknown solver option 'sweeps' (options: preset, type, grid");
}

TEST(SolverOptionsJson, OverridesAreReadAsTheScenesOwnKeys) {
  test::TempDir dir;
  test::writeText(dir / "s.json", R"({"mesh": {"generate": "sphere", "tets": 500},
      "solver": {"newton_iters": 7, "grid": "20/all"}})");
  const SceneDescription scene = loadScene(dir / "s.json");
  EXPECT_EQ(withSolverOverrides(scene, {}).solver, scene.solver);
  const SceneDescription paper =
      withSolverOverrides(scene, {{"preset", "paper"}, {"backend", "cpu"}});
  EXPECT_EQ(paper.solver.preset, SolverPreset::Paper);
  EXPECT_EQ(paper.solver.newtonIterations, 7) << "the scene's own key stays";
  EXPECT_EQ(paper.solver.grid, "20/all");
  EXPECT_EQ(paper.solver.coarseSolver, CoarseSolver::Cg) << "the preset's default";
  EXPECT_EQ(paper.solver.backend, BackendRequest::Cpu);
  EXPECT_EQ(paper.source["solver"]["preset"], "paper") << "a saved project keeps them";
  EXPECT_THROW_WITH(withSolverOverrides(scene, {{"fine_sweeps", -2}}), InputError,
                    "solver options fine_sweeps=-2: ");
}

std::string docValue(bool v) {
  return v ? "true" : "false";
}
std::string docValue(int v) {
  return std::to_string(v);
}
std::string docValue(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}
std::string docValue(const std::string& v) {
  return "`" + v + "`";
}
template <NamedEnum E>
std::string docValue(E v) {
  return std::string("`") + enumName(v) + "`";
}

// docs/scenes.md's `solver` section: the presets' table lists exactly the rows in which they
// differ, with both values, and the keys' table has a row for every key of the table.
TEST(SolverOptionsJson, TheScenesPageListsEveryOptionAndThePresetsDifferences) {
  std::ifstream in(fs::path(GALSCULPT_SOURCE_DIR) / "docs" / "scenes.md");
  ASSERT_TRUE(in) << "docs/scenes.md";
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const size_t begin = text.find("### `solver`");
  ASSERT_NE(begin, std::string::npos);
  const std::string section = text.substr(begin, text.find("\n## ", begin) - begin);
  std::set<std::string> presetRows, keyRows;
  const std::regex row(R"(\n\| `([a-z_]+)` \| ([^|\n]*) \| ([^|\n]*) \|)");
  const size_t keysTable = section.find("| key | default | meaning |");
  ASSERT_NE(keysTable, std::string::npos);
  for (auto it = std::sregex_iterator(section.begin(), section.end(), row);
       it != std::sregex_iterator(); ++it) {
    const size_t at = static_cast<size_t>(it->position());
    (at < keysTable ? presetRows : keyRows).insert((*it)[1]);
  }
  std::set<std::string> differing, keys = {"preset"};
  forEachSolverOption([&](const auto& f) {
    keys.insert(f.key);
    if (f.converged == f.paper) return;
    differing.insert(f.key);
    const std::string line = std::string("| `") + f.key + "` | " + docValue(f.converged) + " | " +
                             docValue(f.paper) + " |";
    EXPECT_NE(section.find(line), std::string::npos) << "docs/scenes.md lacks: " << line;
  });
  EXPECT_EQ(presetRows, differing);
  EXPECT_EQ(keyRows, keys);
}

}  // namespace
}  // namespace galsculpt
