// `galsculpt run SCENE --frames N [--solver reference] --out DIR --metrics FILE.csv
//  [--export-every K]`: headless simulation with a progress bar and per-frame metrics.
// `galsculpt play SCRIPT --out DIR [--export-every K]`: the same for a playback script.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <sstream>

#include "app/cli.h"
#include "app/cli_args.h"
#include "engine/playback.h"
#include "engine/scene_mesh.h"
#include "engine/simulation.h"
#include "engine/surface_io.h"
#include "solver/atomic_file.h"
#include "solver/input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

void drawProgress(std::ostream& err, int done, int total, double msPerFrame, bool interactive) {
  if (interactive) {
    const int width = 30;
    const int filled = total > 0 ? width * done / total : width;
    err << "\r[" << std::string(filled, '#') << std::string(width - filled, ' ') << "] " << done
        << '/' << total << std::fixed << std::setprecision(1) << "  " << msPerFrame << " ms/frame"
        << std::defaultfloat << (done == total ? "\n" : "") << std::flush;
  } else if (total > 0 && (done == total || done % std::max(1, total / 10) == 0)) {
    err << "frame " << done << '/' << total << "  " << std::fixed << std::setprecision(1)
        << msPerFrame << " ms/frame" << std::defaultfloat << '\n';
  }
}

std::string frameName(int frame) {
  std::ostringstream s;
  s << "frame_" << std::setw(5) << std::setfill('0') << frame << ".obj";
  return s.str();
}

// The frame loop shared by run and play: metrics CSV, OBJ exports, final.obj, summary.
int simulateFrames(const std::string& name, int frames, Simulation& sim, const fs::path& outDir,
                   const fs::path& metricsPath, int exportEvery,
                   const std::function<FrameMetrics()>& advance, std::ostream& out,
                   std::ostream& err) {
  for (const std::string& note : sim.notes()) err << "note: " << note << '\n';
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (ec) throw OutputError("cannot create " + outDir.string() + ": " + ec.message());

  std::ostringstream csv;
  csv << metricsCsvHeader() << '\n';
  const bool interactive = isatty(STDERR_FILENO);
  double msSum = 0.0;
  int warnings = 0;
  FrameMetrics last;
  for (int f = 1; f <= frames; ++f) {
    last = advance();
    csv << metricsCsvRow(last) << '\n';
    msSum += last.msTotal;
    warnings += last.warnings;
    drawProgress(err, f, frames, msSum / f, interactive);
    if (exportEvery > 0 && f % exportEvery == 0) writeSurface(outDir / frameName(f), sim.surface());
  }
  writeSurface(outDir / "final.obj", sim.surface());
  writeFileAtomically(metricsPath, [&](std::ostream& o) { o << csv.str(); });
  out << name << ": " << frames << " frames, " << std::fixed << std::setprecision(2)
      << msSum / frames << " ms/frame, volume change " << std::setprecision(3)
      << sim.volumeChangePercent() << " %, " << last.damagedEdges << " damaged edges, "
      << last.pieces << " piece(s), " << warnings << " warning(s)\n"
      << std::defaultfloat;
  out << "wrote " << metricsPath.string() << " and " << (outDir / "final.obj").string() << '\n';
  return kExitOk;
}

// What run and play share: where outputs go, how often surfaces are exported, which solver.
struct RunOptions {
  fs::path outDir, metricsPath;
  int exportEvery = 0;
  SolverChoice solver = SolverChoice::FromScene;
};

RunOptions readRunOptions(const CliArgs& a, const std::string& command) {
  if (!a.has("--out")) throw UsageError(command + " needs --out DIR");
  RunOptions o;
  o.exportEvery = a.intValue("--export-every", 0, 1, 10000000);
  const std::string solver = a.value("--solver").value_or("scene");
  if (solver != "scene" && solver != "reference")
    throw UsageError("--solver must be 'reference' (or omitted)");
  o.solver = solver == "reference" ? SolverChoice::Reference : SolverChoice::FromScene;
  o.outDir = *a.value("--out");
  o.metricsPath = a.value("--metrics").value_or((o.outDir / "metrics.csv").string());
  return o;
}

TetMesh loadMeshReporting(const SceneDescription& scene, std::ostream& err) {
  return loadSceneMesh(scene, [&err](const std::string& line) { err << line << '\n'; });
}

}  // namespace

int runCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  const CliArgs a(args, {"--frames", "--solver", "--out", "--metrics", "--export-every"}, {});
  a.expectPositional(
      1, 1,
      "galsculpt run SCENE --frames N [--solver reference] --out DIR --metrics FILE.csv "
      "[--export-every K]");
  const RunOptions o = readRunOptions(a, "run");
  const int frames = a.intValue("--frames", 0, 1, 10000000);
  if (!a.has("--frames")) throw UsageError("run needs --frames N");
  const SceneDescription scene = loadScene(a.positional()[0]);
  Simulation sim(scene, loadMeshReporting(scene, err), o.solver);
  return simulateFrames(
      scene.name, frames, sim, o.outDir, o.metricsPath, o.exportEvery,
      [&sim] { return sim.advance(); }, out, err);
}

int playCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  const CliArgs a(args, {"--out", "--metrics", "--export-every", "--solver"}, {});
  a.expectPositional(1, 1,
                     "galsculpt play SCRIPT --out DIR [--export-every K] [--metrics FILE.csv] "
                     "[--solver reference]");
  const RunOptions o = readRunOptions(a, "play");
  const PlaybackScript script = loadPlaybackScript(a.positional()[0]);
  Simulation sim(script.scene, loadMeshReporting(script.scene, err), o.solver);
  Playback playback(script, sim);
  return simulateFrames(
      script.scene.name, script.frames, sim, o.outDir, o.metricsPath, o.exportEvery,
      [&playback] { return playback.advance(); }, out, err);
}

}  // namespace galsculpt
