// The solver options' table (solver/model/solver_options.h) read from and written to a scene's
// "solver" object, and set from the command line's --solver-option KEY=VALUE: every key the
// table has, and no other, with the table's ranges and checks.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/scene/json_reader.h"
#include "engine/scene/scene.h"
#include "solver/model/solver_options.h"

namespace galsculpt {

// A scene's "solver" object: `preset` first (its values are the defaults), then every other key
// of the table; throws InputError naming the file and JSON path for an unknown key or a value
// out of range.
SolverOptions readSolverOptions(JsonObject o);

// Every option as a scene's "solver" object holds it (the preset and each key of the table).
nlohmann::json solverOptionsJson(const SolverOptions& options);

// Solver keys and values set over a scene's own (--solver-option, --backend, bench --preset).
using SolverOverrides = std::vector<std::pair<std::string, nlohmann::json>>;

// "newton_iters=10,preset=paper": KEY=VALUE pairs, comma-separated; a value that is not JSON
// (paper, 50/all) is a string. Throws std::invalid_argument for a pair without '=' or a key
// the table does not have.
SolverOverrides parseSolverOptionList(const std::string& list);

// The scene with `overrides` merged into its "solver" object and read again, as if its file
// said so: a `preset` among them gives the defaults of the keys the scene does not set. Throws
// InputError naming the option for a value the table refuses.
SceneDescription withSolverOverrides(const SceneDescription& scene,
                                     const SolverOverrides& overrides);

}  // namespace galsculpt
