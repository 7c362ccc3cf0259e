// What `galsculpt run` and `galsculpt play` do, callable without a command line (the Python
// module's `play` calls playScript with typed options): where a run's outputs go, the frame loop
// that writes them and what it ends with.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "engine/scene/solver_options_json.h"
#include "engine/session/simulation.h"

namespace galsculpt {

// What run and play share: where outputs go, how often surfaces are exported, which solver.
// Each field is a flag of theirs (app/cli/command_table.cpp); checkRunOptions checks the values.
struct RunOptions {
  std::filesystem::path outDir;       // --out
  std::filesystem::path metricsPath;  // --metrics (empty: outDir/metrics.csv)
  int exportEvery = 0;                // --export-every (0: never)
  std::string exportFormat = "obj";   // --export-format: obj, ply, stl, gltf or glb
  bool exportTets = false;            // --export-tets
  int pngEvery = 0;                   // --png-every: render the surface every K frames (0: never)
  int width = 1280, height = 800;     // --size
  SolverChoice solver = SolverChoice::FromScene;  // --solver reference
};

// A UsageError naming the flag for a value out of its range (an export format not known, a
// negative period, an empty --out, a size not in [16, 8192]).
void checkRunOptions(const RunOptions& options);

// What a run ends with, beside the files it wrote and the summary it printed.
struct RunSummary {
  std::string name;  // the scene's
  int frames = 0;
  int warnings = 0;  // frames' warnings and tools that acted on nothing
  std::filesystem::path metricsPath, finalSurface;
  std::vector<std::string> written;  // the files written in outDir
};

// Called after each frame with its figures (the metrics CSV's row), on the running thread.
using FrameSink = std::function<void(const FrameMetrics&)>;

// `galsculpt play SCRIPT`: the script replayed with `solver` over its scene's solver keys.
// Throws as the command's readers do (InputError, UsageError, OutputError, Interrupted).
RunSummary playScript(const std::string& scriptPath, const RunOptions& options,
                      const SolverOverrides& solver, std::ostream& out, std::ostream& err,
                      const FrameSink& onFrame = {});

}  // namespace galsculpt
