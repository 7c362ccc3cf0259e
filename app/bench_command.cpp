// `galsculpt bench`: speed against error on the paper's scenes, and a solver-setting sweep.
//
// Every measurement runs in a child process (fork) so that its peak memory is its own and a
// crash cannot take the benchmark down. The reference run (Newton + direct solve) of a scene
// writes its final positions; each multigrid run is compared with them.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli.h"
#include "app/cli_args.h"
#include "engine/scene_mesh.h"
#include "engine/simulation.h"
#include "solver/atomic_file.h"
#include "solver/input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

struct BenchScene {
  const char* name;
  const char* file;
};
const BenchScene kScenes[] = {{"sphere", "hanging_sphere.json"}, {"charpy", "charpy.json"}, {"human", "human.json"},
                              {"armadillo", "armadillo.json"},   {"steak", "steak.json"}};

struct Setting {
  bool reference = false;
  std::string grid;
  int fineSweeps = 3, coarseIters = 20;
};

nlohmann::json measure(const SceneDescription& baseScene, const TetMesh& mesh, const Setting& setting, int frames,
                       const fs::path& referencePositions) {
  SceneDescription scene = baseScene;
  scene.solver.type = setting.reference ? "reference" : "multigrid";
  scene.solver.grid = setting.grid;
  scene.solver.fineSweeps = setting.fineSweeps;
  scene.solver.coarseIterations = setting.coarseIters;
  Simulation sim(scene, mesh);
  std::vector<double> ms;
  FrameMetrics last;
  for (int f = 0; f < frames; ++f) {
    last = sim.advance();
    ms.push_back(last.msTotal);
  }
  std::sort(ms.begin(), ms.end());
  const double median = ms[ms.size() / 2];
  nlohmann::json r;
  r["tets"] = mesh.numTets();
  r["solver"] = setting.reference ? "reference" : "multigrid";
  r["grid"] = setting.reference ? "" : setting.grid;
  r["fine_sweeps"] = setting.reference ? 0 : setting.fineSweeps;
  r["coarse_iters"] = setting.reference ? 0 : setting.coarseIters;
  r["frames"] = frames;
  r["ms_per_frame"] = median;
  r["fps"] = 1000.0 / median;
  r["volume_change_pct"] = last.volumeChangePct;
  r["warnings"] = last.warnings;
  const std::vector<Vec3>& x = sim.state().x;
  if (setting.reference) {
    writeFileAtomically(referencePositions, [&](std::ostream& out) {
      out.write(reinterpret_cast<const char*>(x.data()), static_cast<std::streamsize>(x.size() * sizeof(Vec3)));
    });
    r["rel_position_error"] = 0.0;
  } else {
    std::vector<Vec3> ref(x.size());
    std::ifstream in(referencePositions, std::ios::binary);
    in.read(reinterpret_cast<char*>(ref.data()), static_cast<std::streamsize>(ref.size() * sizeof(Vec3)));
    // Largest position difference relative to the reference's largest displacement.
    double err = 0.0, disp = 0.0;
    for (size_t v = 0; v < x.size(); ++v) {
      err = std::max(err, (x[v] - ref[v]).norm());
      disp = std::max(disp, (ref[v] - mesh.vertices[v]).norm());
    }
    r["rel_position_error"] = in ? err / std::max(disp, 1e-300) : -1.0;
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  r["peak_rss_mb"] = usage.ru_maxrss / 1024.0;
  return r;
}

// Runs `measure` in a child process; returns its result (or an "error" entry).
nlohmann::json measureInChild(const SceneDescription& scene, const TetMesh& mesh, const Setting& setting, int frames,
                              const fs::path& referencePositions, const fs::path& scratch) {
  const fs::path resultFile = scratch / "result.json";
  std::error_code ec;
  fs::remove(resultFile, ec);
  const pid_t pid = fork();
  if (pid == 0) {
    int code = 0;
    try {
      const nlohmann::json r = measure(scene, mesh, setting, frames, referencePositions);
      std::ofstream(resultFile) << r.dump();
    } catch (const std::exception& e) {
      std::ofstream(resultFile) << nlohmann::json{{"error", e.what()}}.dump();
      code = 1;
    }
    std::fflush(nullptr);
    _exit(code);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  std::ifstream in(resultFile);
  if (!in) return nlohmann::json{{"error", "the measurement process died (status " + std::to_string(status) + ")"}};
  return nlohmann::json::parse(in);
}

std::string row(const nlohmann::json& r) {
  std::ostringstream s;
  if (r.contains("error")) return "  error: " + r["error"].get<std::string>();
  s << std::left << std::setw(10) << r.value("scene", "") << std::setw(8) << r["tets"].get<int>() << std::setw(10)
    << r["solver"].get<std::string>() << std::setw(13) << r["grid"].get<std::string>() << std::right << std::setw(4)
    << r["fine_sweeps"].get<int>() << std::setw(6) << r["coarse_iters"].get<int>() << std::fixed << std::setprecision(2)
    << std::setw(10) << r["ms_per_frame"].get<double>() << std::setw(9) << std::setprecision(1)
    << r["fps"].get<double>() << std::setw(9) << std::setprecision(0) << r["peak_rss_mb"].get<double>()
    << std::setw(11) << std::setprecision(3) << 100.0 * r["rel_position_error"].get<double>() << std::setw(10)
    << std::setprecision(3) << r["volume_change_pct"].get<double>();
  return s.str();
}

}  // namespace

int benchCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  const CliArgs a(args, {"--scene", "--json", "--frames"}, {"--quick", "--sweep"});
  a.expectPositional(0, 0, "galsculpt bench [--scene NAME] [--quick] [--sweep] [--frames N] [--json FILE]");
  const bool quick = a.has("--quick");
  const int frames = a.intValue("--frames", quick ? 20 : 60, 1, 100000);
  std::vector<BenchScene> scenes;
  if (auto name = a.value("--scene")) {
    for (const BenchScene& s : kScenes) {
      if (*name == s.name) scenes.push_back(s);
    }
    if (scenes.empty()) throw UsageError("unknown scene '" + *name + "' (sphere, charpy, human, armadillo, steak)");
  } else if (quick) {
    scenes = {kScenes[0], kScenes[1]};
  } else {
    scenes.assign(std::begin(kScenes), std::end(kScenes));
  }
  std::string pattern = (fs::temp_directory_path() / "galsculpt-bench-XXXXXX").string();
  if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder");
  const fs::path scratch = pattern;

  nlohmann::json results = nlohmann::json::array();
  out << "scene     tets    solver    grid          fine coarse  ms/frame      fps  peak MB  pos err %  vol chg %\n";
  for (const BenchScene& bs : scenes) {
    const SceneDescription scene = loadScene(fs::path(assetDirectory()) / "scenes" / bs.file);
    TetMesh mesh;
    try {
      mesh = loadSceneMesh(scene, [&err](const std::string& line) { err << line << '\n'; });
    } catch (const InputError& e) {
      err << "skipping " << bs.name << ": " << e.what() << '\n';
      continue;
    }
    std::vector<Setting> settings = {{true, "", 0, 0}, {false, scene.solver.grid, scene.solver.fineSweeps, scene.solver.coarseIterations}};
    if (a.has("--sweep") && std::string(bs.name) == "sphere") {
      for (const char* grid : {"50/all", "200/all", "50/1000/all"}) {
        for (int sweeps : {1, 3, 10, 30}) {
          for (int coarse : {5, 20, 200}) {
            if (std::string(grid) == scene.solver.grid && sweeps == scene.solver.fineSweeps &&
                coarse == scene.solver.coarseIterations) {
              continue;
            }
            settings.push_back({false, grid, sweeps, coarse});
          }
        }
      }
    }
    const fs::path refFile = scratch / (std::string(bs.name) + ".ref");
    for (const Setting& s : settings) {
      nlohmann::json r = measureInChild(scene, mesh, s, frames, refFile, scratch);
      r["scene"] = bs.name;
      out << row(r) << '\n' << std::flush;
      results.push_back(r);
    }
  }
  fs::remove_all(scratch);
  if (auto json = a.value("--json")) {
    const nlohmann::json doc{{"machine", {{"cores", static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN))}}},
                             {"frames", frames},
                             {"results", results}};
    writeFileAtomically(*json, [&](std::ostream& o) { o << doc.dump(2) << '\n'; });
    out << "wrote " << *json << '\n';
  }
  return kExitOk;
}

}  // namespace galsculpt
