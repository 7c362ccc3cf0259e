// `galsculpt run SCENE --frames N [--solver reference] --out DIR --metrics FILE.csv
//  [--export-every K]`: headless simulation with a progress bar and per-frame metrics.
// `galsculpt play SCRIPT --out DIR [--export-every K]`: the same for a playback script.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <memory>
#include <sstream>
#include <tuple>

#include "app/cli/cli.h"
#include "app/cli/cli_args.h"
#include "app/cli/command_table.h"
#include "app/cli/progress_text.h"
#include "app/cli/run_command.h"
#include "app/cli/run_outputs.h"
#include "app/render/render_mesh.h"
#include "app/render/snapshot_renderer.h"
#include "app/window/camera.h"
#include "engine/scene/scene_mesh.h"
#include "engine/session/playback.h"
#include "engine/session/simulation.h"
#include "engine/surface/surface_io.h"
#include "solver/io/appending_file.h"
#include "solver/io/folder_lock.h"
#include "solver/io/input_error.h"
#include "solver/io/stop_request.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

// An export is written whatever it holds; one that is not clean, or whose pieces overlap, says
// so.
void writeExport(const fs::path& path, const ExportedSurface& exported, std::ostream& err) {
  writeVisualSurface(path, exported.surface);
  if (exported.crossings > 0 || exported.invertedShells > 0 || exported.contacts > 0)
    err << "warning: " << path.string() << ": " << exported.summary() << '\n';
}

// The progress line: frames done, ms a frame, the time since the first frame and an estimate of
// the time left (the frames left at the mean pace so far).
void drawProgress(std::ostream& err, int done, int total, double msPerFrame, double elapsedS,
                  bool interactive) {
  std::ostringstream pace;
  pace << std::fixed << std::setprecision(1) << msPerFrame << " ms/frame, "
       << paceText(done, total, elapsedS);
  if (interactive) {
    const int width = 30;
    const int filled = total > 0 ? width * done / total : width;
    err << "\r[" << std::string(filled, '#') << std::string(width - filled, ' ') << "] " << done
        << '/' << total << "  " << pace.str() << "\x1b[K" << (done == total ? "\n" : "")
        << std::flush;
  } else if (total > 0 && (done == total || done % std::max(1, total / 10) == 0)) {
    err << "frame " << done << '/' << total << "  " << pace.str() << '\n';
  }
}

std::string frameName(int frame, const std::string& extension) {
  std::ostringstream s;
  s << "frame_" << std::setw(5) << std::setfill('0') << frame << '.' << extension;
  return s.str();
}

// Offscreen snapshots of the visualization surface (crack faces tinted, anchored vertices as
// blue dots), framed on the body at rest and seen from the standard perspective view (the
// camera's default angles) - or from a script's latest camera event.
class FrameRenderer {
 public:
  FrameRenderer(const Simulation& sim, int width, int height) : snapshots_(width, height) {
    camera_.frame(boundingBox(sim.model().mesh.vertices));
  }
  void write(const Simulation& sim, const fs::path& file, const std::optional<CameraPose>& pose) {
    snapshots_.setMesh(makeRenderMesh(sim.surface(), kSurfaceColor, kCrackColor));
    std::vector<Vec3> anchored;
    for (int v : sim.anchors().heldVertices()) anchored.push_back(sim.state().x[v]);
    snapshots_.setPoints(anchored, kAnchorColor);
    OrbitCamera camera = camera_;
    if (pose) camera.setPose(*pose);
    snapshots_.write(camera, file);
  }

 private:
  SnapshotRenderer snapshots_;
  OrbitCamera camera_;
};

// The frame loop shared by run and play: metrics CSV, surface exports, final.obj, summary. The
// callers check the options (checkRunOptions) before any work, meshing included.
RunSummary simulateFrames(const std::string& name, int frames, Simulation& sim, const RunOptions& o,
                          const std::function<FrameMetrics()>& advance, std::ostream& out,
                          std::ostream& err, const FrameSink& onFrame = {},
                          const std::function<std::optional<CameraPose>()>& camera = {},
                          const std::function<std::vector<std::string>()>& toolReports = {}) {
  auto pose = [&camera]() -> std::optional<CameraPose> { return camera ? camera() : std::nullopt; };
  const fs::path& outDir = o.outDir;
  const fs::path metricsPath = o.metricsPath.empty() ? outDir / "metrics.csv" : o.metricsPath;
  const int exportEvery = o.exportEvery;
  std::unique_ptr<FrameRenderer> pictures;
  if (o.pngEvery > 0) pictures = std::make_unique<FrameRenderer>(sim, o.width, o.height);
  for (const std::string& note : sim.notes()) err << "note: " << note << '\n';
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (ec) throw OutputError("cannot create " + outDir.string() + ": " + ec.message());
  const FolderLock lock(outDir);  // one writer at a time
  const std::vector<std::string> cleared = clearRunOutputs(outDir);
  if (!cleared.empty()) {
    err << "note: removed " << cleared.size() << " file(s) an earlier run left in "
        << outDir.string() << ": " << describeWritten(cleared) << '\n';
  }
  std::vector<std::string> written;  // names in outDir
  const bool metricsInside = fs::absolute(metricsPath).parent_path().lexically_normal() ==
                             fs::absolute(outDir).lexically_normal();
  if (metricsInside) written.push_back(metricsPath.filename().string());

  // Rows reach the file frame by frame: a run stopped by a signal or killed keeps its metrics.
  AppendingFile csv(metricsPath);
  csv.append(metricsCsvHeader() + '\n');
  const bool interactive = isatty(STDERR_FILENO);
  double msSum = 0.0;
  int warnings = 0;
  // Frames whose worst piece ended above the tolerance of its own loads: said at the end (with
  // solver.converge_pieces false the body's residual alone decides convergence and can hide
  // them; with it, such frames are also not converged; docs/physics.md).
  int pieceFrames = 0;
  double worstPiece = 0.0;
  FrameMetrics last;
  const auto started = std::chrono::steady_clock::now();
  // Between frames, or within one (the frame cut short is rolled back: Simulation::advance).
  auto sayStopped = [&](int done) {
    if (interactive) err << '\n';
    err << "stopped after " << done << " of " << frames << " frames; " << metricsPath.string()
        << " holds their rows\n";
  };
  for (int f = 1; f <= frames; ++f) {
    if (stopRequested()) {
      sayStopped(f - 1);
      throwIfStopRequested();
    }
    const std::size_t notesBefore = sim.notes().size();
    try {
      last = advance();
    } catch (const Interrupted&) {
      sayStopped(f - 1);
      throw;
    }
    csv.append(metricsCsvRow(last) + '\n');
    if (onFrame) onFrame(last);
    for (std::size_t n = notesBefore; n < sim.notes().size(); ++n)
      err << "note: " << sim.notes()[n] << '\n';
    msSum += last.msTotal;
    warnings += last.warnings;
    // Tools that acted on nothing (a knife that crossed no edge, a brush in empty space).
    if (toolReports) {
      for (const std::string& report : toolReports()) {
        if (interactive) err << "\r\x1b[K";
        err << "warning: " << report << '\n';
        ++warnings;
      }
    }
    if (pieceAboveTolerance(last, sim.settings().residualTolerance)) {
      ++pieceFrames;
      worstPiece = std::max(worstPiece, last.pieceResidual);
    }
    drawProgress(err, f, frames, msSum / f,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(),
                 interactive);
    if (exportEvery > 0 && f % exportEvery == 0) {
      writeExport(outDir / frameName(f, o.exportFormat), sim.exportSurface(), err);
      written.push_back(frameName(f, o.exportFormat));
    }
    if (pictures && f % o.pngEvery == 0) {
      pictures->write(sim, outDir / frameName(f, "png"), pose());
      written.push_back(frameName(f, "png"));
    }
  }
  if (pictures) {
    pictures->write(sim, outDir / "final.png", pose());
    written.push_back("final.png");
  }
  const ExportedSurface exported = sim.exportSurface();
  writeExport(outDir / "final.obj", exported, err);
  written.push_back("final.obj");
  if (o.exportFormat != "obj") {
    writeExport(outDir / ("final." + o.exportFormat), exported, err);
    written.push_back("final." + o.exportFormat);
  }
  if (o.exportTets) {
    const int leftOut = sim.writeTetsWithDamage(outDir / "final");
    out << "wrote " << (outDir / "final").string() << ".node/.ele/.face/.damage/.vtk";
    if (leftOut > 0)
      out << " (" << leftOut
          << " tet(s) parted between pieces and crushed flat left out of .node/.ele)";
    out << '\n';
    for (const char* extension : {".node", ".ele", ".face", ".damage", ".vtk"})
      written.push_back(std::string("final") + extension);
  }
  // What else landed under a run output's name (a .gltf's .bin) is this run's: the folder held
  // none before it.
  for (const std::string& name : runOutputsIn(outDir)) written.push_back(name);
  csv.close();
  out << name << ": " << frames << " frames, " << std::fixed << std::setprecision(2)
      << msSum / frames << " ms/frame, volume change " << std::setprecision(3)
      << sim.volumeChangePercent() << " %, " << last.damagedEdges << " damaged edges, "
      << last.pieces << " piece(s), " << warnings << " warning(s)\n"
      << std::defaultfloat;
  out << "wrote " << metricsPath.string() << " and " << (outDir / "final.obj").string() << '\n';
  out << "files in " << outDir.string() << ": " << describeWritten(written) << '\n';
  out << "final surface: " << exported.summary() << '\n';
  if (pieceFrames > 0)
    err << "note: " << pieceFrames << " frame(s) left a piece above the residual tolerance of its "
        << "own loads (worst " << worstPiece << "; metrics column piece_residual)\n";
  RunSummary summary;
  summary.name = name;
  summary.frames = frames;
  summary.warnings = warnings;
  summary.metricsPath = metricsPath;
  summary.finalSurface = outDir / "final.obj";
  summary.written = std::move(written);
  return summary;
}

RunOptions readRunOptions(const CliArgs& a) {
  RunOptions o;
  o.exportEvery = a.intValue("--export-every", 0, 1, 10000000);
  o.exportFormat = a.value("--export-format").value_or("obj");
  o.exportTets = a.has("--export-tets");
  o.pngEvery = a.intValue("--png-every", 0, 1, 10000000);
  std::tie(o.width, o.height) = a.sizeValue("--size", {1280, 800});
  const std::string solver = a.value("--solver").value_or("scene");
  if (solver != "scene" && solver != "reference")
    throw UsageError("--solver must be 'reference' (or omitted)");
  o.solver = solver == "reference" ? SolverChoice::Reference : SolverChoice::FromScene;
  o.outDir = *a.value("--out");
  o.metricsPath = a.value("--metrics").value_or("");
  return o;
}

TetMesh loadMeshReporting(const SceneDescription& scene, std::ostream& err) {
  return loadSceneMesh(scene, [&err](const std::string& line) { err << line << '\n'; });
}

}  // namespace

void checkRunOptions(const RunOptions& o) {
  if (o.outDir.empty()) throw UsageError("--out must name a folder");
  if (o.exportFormat != "obj" && o.exportFormat != "ply" && o.exportFormat != "stl" &&
      o.exportFormat != "gltf" && o.exportFormat != "glb") {
    throw UsageError("--export-format must be obj, ply, stl, gltf or glb, got '" + o.exportFormat +
                     "'");
  }
  if (o.exportEvery < 0) throw UsageError("--export-every must be at least 0 (0: never)");
  if (o.pngEvery < 0) throw UsageError("--png-every must be at least 0 (0: never)");
  // (the bounds --size's reader keeps: app/cli/cli_args.cpp)
  if (o.width < 16 || o.height < 16 || o.width > 8192 || o.height > 8192)
    throw UsageError("--size expects WIDTHxHEIGHT between 16 and 8192, got " +
                     std::to_string(o.width) + "x" + std::to_string(o.height));
}

RunSummary playScript(const std::string& scriptPath, const RunOptions& o,
                      const SolverOverrides& solver, std::ostream& out, std::ostream& err,
                      const FrameSink& onFrame) {
  checkRunOptions(o);
  PlaybackScript script = loadPlaybackScript(scriptPath);
  script.scene = withSolverOverrides(script.scene, solver);
  Simulation sim(script.scene, loadMeshReporting(script.scene, err), o.solver);
  Playback playback(script, sim);
  return simulateFrames(
      script.scene.name, script.frames, sim, o, [&playback] { return playback.advance(); }, out,
      err, onFrame, [&playback] { return playback.camera(); },
      [&playback, &scriptPath] {
        std::vector<std::string> reports = playback.takeIdleReports();
        for (std::string& r : reports) r = scriptPath + ": " + r;
        return reports;
      });
}

int runCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  const CliArgs a(args, commandSpec("run"));
  applyThreadsOption(a);
  const RunOptions o = readRunOptions(a);
  checkRunOptions(o);
  const int frames = a.intValue("--frames", 0, 1, 10000000);
  const SolverOverrides solver = solverOverrides(a);
  const SceneDescription scene = withSolverOverrides(loadScene(a.positional()[0]), solver);
  Simulation sim(scene, loadMeshReporting(scene, err), o.solver);
  simulateFrames(
      scene.name, frames, sim, o, [&sim] { return sim.advance(); }, out, err);
  return kExitOk;
}

int playCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  const CliArgs a(args, commandSpec("play"));
  applyThreadsOption(a);
  playScript(a.positional()[0], readRunOptions(a), solverOverrides(a), out, err);
  return kExitOk;
}

}  // namespace galsculpt
