// `galsculpt bench` callable without a command line (the Python module's `bench` calls runBench
// with typed options): speed against error on the paper's scenes.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "engine/scene/scene.h"
#include "engine/scene/solver_options_json.h"

namespace galsculpt {

// Each field is a flag of bench's (app/cli/command_table.cpp, docs/cli.md); runBench checks the
// values as the command line's reader does, with a UsageError naming the flag.
struct BenchOptions {
  std::vector<std::string>
      scenes;                   // --scene: names; empty: all (--quick's pair, --cracks's sphere)
  bool quick = false;           // --quick
  bool sweep = false;           // --sweep
  bool cracks = false;          // --cracks
  int frames = 0;               // --frames, in [1, 100000]; 0: 60, or 20 with --quick
  std::vector<int> settles{0};  // --settle: ascending window starts, in [0, 100000]
  std::optional<SolverPreset> preset;       // --preset
  std::optional<DebrisRule> debris;         // --debris
  SolverOverrides solver;                   // --solver-option and --backend
  std::optional<std::string> referenceDir;  // --reference-dir
  std::optional<std::string> json;          // --json: where the document is written as well
};

// Measures, printing a row per setting to `out` and progress to `err`; returns the document
// --json writes: {"machine", "frames", "settle_frames", "settle_windows", "results"}.
nlohmann::json runBench(const BenchOptions& options, std::ostream& out, std::ostream& err);

// The names --scene takes, in the order `bench` measures them.
std::vector<std::string> benchSceneNames();

}  // namespace galsculpt
