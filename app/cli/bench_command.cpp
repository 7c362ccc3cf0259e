// `galsculpt bench`: speed against error on the paper's scenes, and a solver-setting sweep.
//
// Every measurement runs in a child process (fork) so that its peak memory is its own and a
// crash cannot take the benchmark down. The reference run (Newton + direct solve) of a scene
// writes its final positions; each multigrid run is compared with them.
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>

#include "app/cli/bench.h"
#include "app/cli/bench_reference.h"
#include "app/cli/bench_table.h"
#include "app/cli/cli.h"
#include "app/cli/cli_args.h"
#include "app/cli/command_table.h"
#include "app/cli/progress_text.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_mesh.h"
#include "engine/session/simulation.h"
#include "solver/frame/parallel.h"
#include "solver/frame/wait_sites.h"
#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"
#include "solver/io/stop_request.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

// A scene of the bench: its file, the frames run untimed before every measured window (added
// to --settle's counts) and the random knife cuts made before those (applyRandomCuts), in the
// reference as in the others.
struct BenchScene {
  const char* name;
  const char* file;
  int startFrame = 0;
  int cuts = 0;
};
// Charpy after the break: the same scene measured from frame 40 on. Its bar breaks in two at
// frame 31 and the striker has left it by frame 36-38 (the converged default, 28k tets,
// docs/benchmarks.md): the window is the halves in flight, whose crack faces still touch, the
// frames a user waits on once something has broken.
constexpr int kCharpyBrokenFrame = 40;
// The cut body: the hanging sphere after --cracks's largest count of cuts, its error in motion
// measured against a reference cut the same way.
constexpr int kSphereCuts = 100;
const BenchScene kScenes[] = {{"sphere", "hanging_sphere.json"},
                              {"charpy", "charpy.json"},
                              {"human", "human.json"},
                              {"armadillo", "armadillo.json"},
                              {"steak", "steak.json"},
                              {"charpy_after_break", "charpy.json", kCharpyBrokenFrame},
                              {"sphere_cut", "hanging_sphere.json", 0, kSphereCuts}};

// The scenes' names, for messages: "sphere, charpy, ...".
std::string sceneNames() {
  std::string names;
  for (const BenchScene& s : kScenes) names += (names.empty() ? "" : ", ") + std::string(s.name);
  return names;
}

// One row: the reference, or the multigrid with a solver description (a preset and overrides).
struct Setting {
  bool reference = false;
  SolverOptions solver;
  int cuts = -1;      // >= 0: that many random knife cuts before the frames (the --cracks series)
  int sceneCuts = 0;  // the scene's own cuts (BenchScene::cuts): a scene, with its reference
};

Setting paperSetting(const std::string& grid, int sweeps, int coarse) {
  Setting s;
  s.solver = solverPreset(SolverPreset::Paper);
  s.solver.grid = grid;
  s.solver.fineSweeps = sweeps;
  s.solver.coarseIterations = coarse;
  return s;
}

// Deterministic random blade sweeps through the body's bounding box, each about a third of the
// body across: most leave slits, many together cut pieces off. `afterCut` runs after each.
template <typename AfterCut>
void applyRandomCuts(Simulation& sim, int cuts, AfterCut afterCut) {
  const BoundingBox box = boundingBox(sim.model().mesh.vertices);
  const Vec3 center = 0.5 * (box.min + box.max);
  const Vec3 half = 0.5 * box.size();
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int c = 0; c < cuts; ++c) {
    const Vec3 p = center + 0.7 * Vec3(u(rng) * half.x(), u(rng) * half.y(), u(rng) * half.z());
    const Vec3 normal = Vec3(u(rng), u(rng), u(rng)).normalized();
    const Vec3 t1 = normal.unitOrthogonal(), t2 = normal.cross(t1);
    const double r = 0.35 * half.norm();
    sim.cut(sweptBladeSurface(p - r * t1 - r * t2, p + r * t1 - r * t2, p - r * t1 + r * t2,
                              p + r * t1 + r * t2));
    afterCut();
  }
}

// The scene with the setting's solver (the backend stays the scene's or --backend's).
SceneDescription sceneWithSetting(const SceneDescription& baseScene, const Setting& setting) {
  SceneDescription scene = baseScene;
  const BackendRequest backend = scene.solver.backend;
  if (!setting.reference) scene.solver = setting.solver;
  scene.solver.backend = setting.reference ? BackendRequest::Cpu : backend;  // no device path
  scene.solver.type = setting.reference ? SolverType::Reference : SolverType::Multigrid;
  return scene;
}

// The row's description of its solver setting.
void describeSetting(const Setting& setting, nlohmann::json& r) {
  const SolverOptions& d = setting.solver;
  r["solver"] = setting.reference ? "reference" : "multigrid";
  r["grid"] = setting.reference ? "" : d.grid;
  r["fine_sweeps"] = setting.reference ? 0 : d.fineSweeps;
  r["coarse_iters"] = setting.reference ? 0 : d.coarseIterations;
  if (!setting.reference) {
    r["preset"] = enumName(d.preset);
    r["newton_iters"] = d.newtonIterations;
    r["pcg_tolerance"] = d.pcgTolerance;
    r["cycles"] = d.cycles;
    r["coarse_solver"] = enumName(d.coarseSolver);
    r["residual_tolerance"] = d.residualTolerance;
    r["energy_guard"] = enumName(d.energyGuard);
    r["stiffness_tolerance"] = d.stiffnessTolerance;
  }
}

// The frame at which the error in motion is measured: the scene's in-motion frame, within the run.
int motionFrame(int frames) {
  return std::min(frames, 20);
}

// One measured window: `frames` frames from where `sim` stands (`settle` frames after the cuts).
nlohmann::json measureWindow(Simulation& sim, const TetMesh& mesh, const Setting& setting,
                             int frames, int settle, const std::vector<double>& msCut,
                             const fs::path& referencePositions) {
  std::vector<double> ms, msSurface, msElements, msSolve, msFracture, msOther;
  FrameMetrics last;
  double newton = 0.0, cg = 0.0, residualMax = 0.0, msSum = 0.0;
  PositionError motionError;
  // What the frames cost a device (the device backends; 0 on the CPU): sums, for the means.
  double launches = 0.0, syncs = 0.0, graphs = 0.0, barriers = 0.0, h2d = 0.0, d2h = 0.0;
  std::vector<double> pieceResidual;
  int unconverged = 0;
  const int atMotion = motionFrame(frames);
  const fs::path motionPositions = fs::path(referencePositions).concat(".motion");
  for (int f = 0; f < frames; ++f) {
    throwIfStopRequested();
    last = sim.advance();
    ms.push_back(last.msTotal);
    msSum += last.msTotal;
    msElements.push_back(last.msElements);
    msSolve.push_back(last.msSolve);
    msFracture.push_back(last.msFracture);
    msOther.push_back(last.msOther);
    newton += last.newtonIterations;
    cg += last.cgIterations;
    launches += last.launches;
    syncs += last.syncs;
    graphs += last.graphs;
    barriers += last.barriers;
    h2d += last.hostToDeviceBytes;
    d2h += last.deviceToHostBytes;
    residualMax = std::max(residualMax, last.residual);
    pieceResidual.push_back(last.pieceResidual);
    unconverged += last.converged ? 0 : 1;
    if (f + 1 == atMotion && setting.cuts < 0)
      motionError = positionError(sim.state().x, mesh, setting.reference, motionPositions);
    // What the app adds to a frame: bringing the visualization surface up to date (done
    // inside the frame already when the body is in pieces: its inverted-piece count reads it).
    sim.surface();
    const SurfaceUpdateStats& st = sim.lastSurfaceUpdate();
    msSurface.push_back(st.msTopology + st.msPositions);
  }
  std::sort(ms.begin(), ms.end());
  const double median = ms[ms.size() / 2];
  const double p95 = ms[std::min(ms.size() - 1, static_cast<size_t>(0.95 * ms.size()))];
  std::sort(msSurface.begin(), msSurface.end());
  nlohmann::json r;
  r["tets"] = mesh.numTets();
  describeSetting(setting, r);
  r["backend"] = sim.backendName();
  r["threads"] = threadCount();
  if (!sim.backendFallback().empty()) r["backend_note"] = sim.backendFallback();
  for (const std::string& note : sim.notes()) {
    if (note.find("running on the CPU") != std::string::npos) r["backend_note"] = note;
  }
  r["frames"] = frames;
  r["settle_frames"] = settle;
  r["ms_per_frame"] = median;
  r["fps"] = 1000.0 / median;
  r["ms_p95"] = p95;
  // Where a frame's time goes (medians of each part on its own, so they need not add up).
  auto medianOf = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  r["ms_elements"] = medianOf(msElements);
  r["ms_solve"] = medianOf(msSolve);
  r["ms_fracture"] = medianOf(msFracture);
  r["ms_other"] = medianOf(msOther);
  r["newton_iters_mean"] = newton / frames;
  r["launches"] = launches / frames;
  r["syncs"] = syncs / frames;
  r["graphs"] = graphs / frames;
  r["barriers"] = barriers / frames;
  r["h2d_bytes"] = h2d / frames;
  r["d2h_bytes"] = d2h / frames;
  r["cg_iters_mean"] = cg / frames;
  // What a Newton iteration costs, apart from how many a motion takes (the mean frame over the
  // mean iterations).
  r["ms_per_newton"] = newton > 0.0 ? msSum / newton : 0.0;
  r["residual_max"] = residualMax;
  // The worst piece's own residual (more than 10 vertices; the body's while fewer than two
  // are): what the body's residual does not show of a body in pieces. Frames whose worst piece
  // is above the tolerance are counted, not called unconverged: convergence is the body's.
  r["piece_residual_max"] = *std::max_element(pieceResidual.begin(), pieceResidual.end());
  r["piece_residual_median"] = medianOf(pieceResidual);
  const double tolerance = setting.solver.residualTolerance;  // (as `residual_tolerance`)
  r["piece_unconverged_frames"] =
      std::count_if(pieceResidual.begin(), pieceResidual.end(),
                    [&](double residual) { return residual > tolerance; });
  r["unconverged_frames"] = unconverged;
  r["motion_frame"] = atMotion;
  r["ms_surface"] = msSurface[msSurface.size() / 2];
  r["ms_surface_max"] = msSurface.back();
  r["volume_change_pct"] = last.volumeChangePct;
  r["warnings"] = last.warnings;
  r["damaged_edges"] = last.damagedEdges;
  r["pieces"] = last.pieces;
  r["debris_pieces"] = last.debrisPieces;
  r["debris_volume_pct"] = last.debrisVolumePct;
  if (setting.sceneCuts > 0) r["scene_cuts"] = setting.sceneCuts;
  if (setting.cuts >= 0) {
    r["cuts"] = setting.cuts;
    r["ms_surface_cut"] = msCut.empty() ? 0.0 : msCut[msCut.size() / 2];
    r["ms_surface_cut_max"] = msCut.empty() ? 0.0 : msCut.back();
  }
  if (setting.cuts >= 0) {
    for (const char* key : {"rel_position_error", "rel_position_error_motion",
                            "rel_position_error_rms", "rel_position_error_motion_rms"})
      r[key] = nullptr;  // cost against cracks: no reference run
  } else {
    const PositionError atEnd =
        positionError(sim.state().x, mesh, setting.reference, referencePositions);
    r["rel_position_error_motion"] = motionError.largest;
    r["rel_position_error_motion_rms"] = motionError.rms;
    r["rel_position_error"] = atEnd.largest;
    r["rel_position_error_rms"] = atEnd.rms;
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  r["peak_rss_mb"] = usage.ru_maxrss / 1024.0;
  return r;
}

// A run of one setting: its cuts (with --cracks), then for each count in `settles` (ascending,
// at least `frames` apart) untimed frames up to that count and a measured window of `frames`
// (the frames of one window count as settled for the next). One result per window. With several
// windows one run reads the cost at several settled states: a body in many pieces settles
// chaotically, and one window is one sample of where its pieces came to lie.
nlohmann::json measure(const SceneDescription& baseScene, const TetMesh& mesh,
                       const Setting& setting, int frames, const std::vector<int>& settles,
                       const fs::path& referencePositions) {
  Simulation sim(sceneWithSetting(baseScene, setting), mesh);
  // The surface is built when the scene opens and brought up to date after each cut, as the app
  // does: what a cut costs the surface is measured here, what a frame costs it below.
  sim.surface();
  std::vector<double> msCut;
  const int cuts = setting.cuts > 0 ? setting.cuts : setting.sceneCuts;
  if (cuts > 0) {
    applyRandomCuts(sim, cuts, [&] {
      sim.surface();
      const SurfaceUpdateStats& st = sim.lastSurfaceUpdate();
      msCut.push_back(st.msTopology + st.msPositions);
    });
  }
  std::sort(msCut.begin(), msCut.end());
  nlohmann::json windows = nlohmann::json::array();
  int done = 0;
  for (const int settle : settles) {
    for (; done < settle; ++done) {
      throwIfStopRequested();
      sim.advance();
    }
    if (settle > 0) sim.surface();
    nlohmann::json r = measureWindow(sim, mesh, setting, frames, settle, msCut, referencePositions);
    r["debris"] = debrisRuleName(baseScene.fracture.debris);
    windows.push_back(r);
    done += frames;
  }
  return windows;
}

// Runs `measure` in a child process; returns its windows' results (or one "error" entry).
nlohmann::json measureInChild(const SceneDescription& scene, const TetMesh& mesh,
                              const Setting& setting, int frames, const std::vector<int>& settles,
                              const fs::path& referencePositions, const fs::path& scratch) {
  const fs::path resultFile = scratch / "result.json";
  std::error_code ec;
  fs::remove(resultFile, ec);
  // Output still buffered in the parent would be written a second time by the child. The parent
  // must not have run a parallel loop before forking: oneTBB's worker threads do not survive
  // fork, and the child's first parallel loop could wait for them forever.
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    int code = 0;
    try {
      const nlohmann::json r = measure(scene, mesh, setting, frames, settles, referencePositions);
      std::ofstream(resultFile) << r.dump();
    } catch (const std::exception& e) {
      std::ofstream(resultFile)
          << nlohmann::json::array({nlohmann::json{{"error", e.what()}}}).dump();
      code = 1;
    }
    detail::WaitSites::instance().report();
    std::fflush(nullptr);
    _exit(code);
  }
  int status = 0;
  // A stop asked of bench (Ctrl-C reaches both, SIGTERM may reach this process alone) is
  // passed on to the measurement, which ends between two frames.
  bool forwarded = false;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (stopRequested() && !forwarded) {
      kill(pid, stopSignal());
      forwarded = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  throwIfStopRequested();
  std::ifstream in(resultFile);
  if (!in)
    return nlohmann::json::array({nlohmann::json{
        {"error", "the measurement process died (status " + std::to_string(status) + ")"}}});
  return nlohmann::json::parse(in);
}

// --preset: every scene read again with that solver preset in place of its own (its other
// solver keys still override the preset's defaults, as in the scene file).
std::optional<SolverPreset> presetOption(const CliArgs& args) {
  return namedOption(args, "--preset", enumFromName<SolverPreset>, "converged or paper");
}

// --debris: every run's debris rule instead of the scene's.
std::optional<DebrisRule> debrisOption(const CliArgs& args) {
  return namedOption(args, "--debris", debrisRuleFromName, "keep or remove");
}

// The scenes asked for: by name, the quick pair, the sphere for --cracks, or all of them.
std::vector<BenchScene> benchScenes(const BenchOptions& o) {
  std::vector<BenchScene> scenes;
  if (!o.scenes.empty()) {
    // Those scenes, in the order given.
    for (const std::string& name : o.scenes) {
      const size_t before = scenes.size();
      for (const BenchScene& s : kScenes) {
        if (name == s.name) scenes.push_back(s);
      }
      if (scenes.size() == before)
        throw UsageError("--scene: unknown scene '" + name + "'" +
                         didYouMean(name, benchSceneNames()) + " (" + sceneNames() + ")");
    }
    for (const BenchScene& s : scenes)
      if (s.cuts > 0 && o.cracks)
        throw UsageError(std::string("--cracks makes its own cuts: not with ") + s.name);
  } else if (o.quick || o.cracks) {
    scenes = o.cracks ? std::vector<BenchScene>{kScenes[0]}
                      : std::vector<BenchScene>{kScenes[0], kScenes[1]};
  } else {
    scenes.assign(std::begin(kScenes), std::end(kScenes));
  }
  return scenes;
}

// The reference, the paper's setting (one linearized step, one V-cycle, 3 sweeps, 20 coarse CG
// iterations on the scene's grid), the converged default on the scene's grid (so that every
// scene shows the old setting beside the new default, also one whose own preset is the paper's)
// and the scene's own setting when it differs from both; with `cracks`
// the scene's own solver after 0, 10 and 100 random knife cuts; with `sweep` the grid of
// paper-like settings.
std::vector<Setting> benchSettings(const SceneDescription& scene, bool cracks, bool sweep) {
  Setting reference;
  reference.reference = true;
  Setting paper;
  paper.solver = solverPreset(SolverPreset::Paper);
  paper.solver.grid = scene.solver.grid;
  Setting converged;
  converged.solver = solverPreset(SolverPreset::Converged);
  converged.solver.grid = scene.solver.grid;
  Setting own;
  own.solver = scene.solver;
  std::vector<Setting> settings = {reference, paper, converged};
  auto same = [&](const Setting& s) {
    SolverOptions a = s.solver, b = own.solver;
    a.backend = b.backend;  // the backend is --backend's, not part of the setting
    return a == b;
  };
  if (!same(paper) && !same(converged)) settings.push_back(own);
  if (cracks) {
    settings.clear();
    for (int cuts : {0, 10, 100}) {
      Setting cut = own;
      cut.cuts = cuts;
      settings.push_back(cut);
    }
  }
  if (sweep) {
    for (const char* grid : {"50/all", "200/all", "50/1000/all"}) {
      for (int sweeps : {1, 3, 10, 30}) {
        for (int coarse : {5, 20, 200}) {
          if (std::string(grid) == scene.solver.grid && sweeps == 3 && coarse == 20) continue;
          settings.push_back(paperSetting(grid, sweeps, coarse));
        }
      }
    }
  }
  return settings;
}

// --settle N[,N...]: where each measured window starts, in frames after the cuts: ascending, each
// window (`frames` long) ended before the next starts. Several only with --cracks: the other
// rows compare each window with a reference run that has one.
void checkSettles(const std::vector<int>& settles, int frames, bool cracks) {
  if (settles.empty()) throw UsageError("--settle names no frame count");
  for (const int settle : settles)
    if (settle < 0 || settle > 100000)
      throw UsageError("--settle expects counts in [0, 100000], got " + std::to_string(settle));
  if (settles.size() > 1 && !cracks)
    throw UsageError("--settle takes several counts only with --cracks");
  for (size_t k = 1; k < settles.size(); ++k) {
    if (settles[k] < settles[k - 1] + frames)
      throw UsageError("--settle: window " + std::to_string(k + 1) + " starts at frame " +
                       std::to_string(settles[k]) + ", before window " + std::to_string(k) + " (" +
                       std::to_string(settles[k - 1]) + " + " + std::to_string(frames) +
                       " frames) has ended");
  }
}

}  // namespace

std::vector<std::string> benchSceneNames() {
  std::vector<std::string> names;
  for (const BenchScene& s : kScenes) names.push_back(s.name);
  return names;
}

nlohmann::json runBench(const BenchOptions& o, std::ostream& out, std::ostream& err) {
  SolverOverrides solver = o.solver;
  const std::optional<DebrisRule> debris = o.debris;
  if (o.preset) solver.insert(solver.begin(), {"preset", enumName(*o.preset)});
  if (o.frames < 0 || o.frames > 100000)
    throw UsageError("--frames expects an integer in [1, 100000], got " + std::to_string(o.frames));
  const int frames = o.frames != 0 ? o.frames : o.quick ? 20 : 60;
  const std::vector<int>& settles = o.settles;
  checkSettles(settles, frames, o.cracks);
  const std::vector<BenchScene> scenes = benchScenes(o);
  const std::optional<std::string>& referenceDir = o.referenceDir;
  if (referenceDir) fs::create_directories(*referenceDir);
  std::string pattern = (fs::temp_directory_path() / "galsculpt-bench-XXXXXX").string();
  if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder");
  const fs::path scratch = pattern;

  // Progress on standard error: measurements done of all, the time elapsed and left.
  auto settingsOf = [&](const SceneDescription& scene, const BenchScene& bs) {
    return benchSettings(scene, o.cracks, o.sweep && std::string(bs.name) == "sphere");
  };
  int measurements = 0, measured = 0;
  for (const BenchScene& bs : scenes) {
    measurements += static_cast<int>(
        settingsOf(
            withSolverOverrides(loadScene(fs::path(assetDirectory()) / "scenes" / bs.file), solver),
            bs)
            .size());
  }
  const auto started = std::chrono::steady_clock::now();
  auto sayProgress = [&](const char* scene) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    err << "bench: " << measured << '/' << measurements << " measurement(s) done (" << scene
        << "), " << paceText(measured, measurements, elapsed) << '\n'
        << std::flush;
  };

  nlohmann::json results = nlohmann::json::array();
  out << benchHeader() << '\n';
  for (const BenchScene& bs : scenes) {
    SceneDescription scene = loadScene(fs::path(assetDirectory()) / "scenes" / bs.file);
    scene = withSolverOverrides(scene, solver);
    if (debris) scene.fracture.debris = *debris;
    TetMesh mesh;
    try {
      mesh = loadSceneMesh(scene, [&err](const std::string& line) { err << line << '\n'; });
    } catch (const InputError& e) {
      err << "skipping " << bs.name << ": " << e.what() << '\n';
      measurements -= static_cast<int>(settingsOf(scene, bs).size());
      continue;
    }
    const std::vector<Setting> settings = settingsOf(scene, bs);
    const fs::path refFile = scratch / (std::string(bs.name) + ".ref");
    std::vector<int> sceneSettles = settles;
    for (int& settle : sceneSettles) settle += bs.startFrame;
    std::map<int, double> uncutMs;  // per window start: the uncut frame (--cracks)
    const size_t sceneFirst = results.size();
    const std::optional<ReferenceCache> cache =
        referenceDir
            ? std::optional<ReferenceCache>(ReferenceCache(
                  *referenceDir, bs.name, referenceKey(scene, mesh, frames, sceneSettles, bs.cuts)))
            : std::nullopt;
    for (Setting s : settings) {
      s.sceneCuts = bs.cuts;
      nlohmann::json rows;
      if (s.reference && cache && cache->load(refFile, rows)) {
        for (nlohmann::json& r : rows) r["reference_cached"] = true;
      } else {
        rows = measureInChild(scene, mesh, s, frames, sceneSettles, refFile, scratch);
        if (s.reference && cache) cache->store(refFile, rows);
      }
      for (nlohmann::json r : rows) {
        r["scene"] = bs.name;
        if (s.cuts >= 0 && !r.contains("error")) {
          const int at = r["settle_frames"].get<int>();
          if (s.cuts == 0) uncutMs[at] = r["ms_per_frame"].get<double>();
          if (s.cuts > 0 && uncutMs.count(at))
            r["times_uncut"] = r["ms_per_frame"].get<double>() / uncutMs[at];
        }
        out << benchRow(r) << '\n' << std::flush;
        results.push_back(r);
      }
      ++measured;
      sayProgress(bs.name);
    }
    if (sceneSettles.size() > 1)
      printWindowSummary(std::vector<nlohmann::json>(results.begin() + sceneFirst, results.end()),
                         out);
  }
  fs::remove_all(scratch);
  const nlohmann::json doc{
      {"machine", {{"cores", static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN))}}},
      {"frames", frames},
      {"settle_frames", settles.front()},
      {"settle_windows", settles},
      {"results", results}};
  if (o.json) {
    writeFileAtomically(*o.json, [&](std::ostream& file) { file << doc.dump(2) << '\n'; });
    out << "wrote " << *o.json << '\n';
  }
  return doc;
}

int benchCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  const CliArgs a(args, commandSpec("bench"));
  applyThreadsOption(a);
  BenchOptions o;
  if (const auto list = a.value("--scene")) {
    std::stringstream names(*list);
    for (std::string name; std::getline(names, name, ',');) o.scenes.push_back(name);
    if (o.scenes.empty()) throw UsageError("--scene names no scene");
  }
  o.quick = a.has("--quick");
  o.sweep = a.has("--sweep");
  o.cracks = a.has("--cracks");
  o.frames = a.intValue("--frames", 0, 1, 100000);
  o.settles = a.intListValue("--settle", {0}, 0, 100000);
  o.preset = presetOption(a);
  o.debris = debrisOption(a);
  o.solver = solverOverrides(a);
  o.referenceDir = a.value("--reference-dir");
  o.json = a.value("--json");
  runBench(o, out, err);
  return kExitOk;
}

}  // namespace galsculpt
