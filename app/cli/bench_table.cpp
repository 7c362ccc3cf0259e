// What `galsculpt bench` prints: its header, a row per measurement, the windows' summary.
#include "app/cli/bench_table.h"

#include <algorithm>
#include <iomanip>
#include <map>
#include <sstream>

#include "solver/model/solver_options.h"

namespace galsculpt {

namespace {

// The scene column's width: the longest name and a space.
constexpr int kSceneColumn = 19;

}  // namespace

std::string benchHeader() {
  return "scene" + std::string(kSceneColumn - 5, ' ') +
         "tets    solver    grid                     fine coarse  ms/frame      fps  "
         "peak MB  pos err %  vol chg %  surf ms    max  backend  motion err %   p95 ms  newton"
         "      cg  max resid  unconv threads  launches  syncs";
}

std::string benchRow(const nlohmann::json& r) {
  std::ostringstream s;
  if (r.contains("error")) return "  error: " + r["error"].get<std::string>();
  if (r.contains("cuts")) {
    s << std::left << std::setw(kSceneColumn) << r.value("scene", "") << std::setw(8)
      << r["tets"].get<int>() << "cuts " << std::right << std::setw(4) << r["cuts"].get<int>()
      << std::fixed << std::setprecision(2) << std::setw(10) << r["ms_per_frame"].get<double>()
      << " ms/frame" << std::setw(8) << std::setprecision(1) << r["fps"].get<double>() << " fps"
      << std::setw(8) << r["damaged_edges"].get<int>() << " damaged edges" << std::setw(6)
      << r["pieces"].get<int>() << " pieces" << std::setw(8) << std::setprecision(2)
      << r["ms_surface"].get<double>() << " ms surface" << std::setw(8)
      << r.value("ms_surface_cut", 0.0) << " ms surface per cut" << std::setw(7)
      << std::setprecision(1) << r["newton_iters_mean"].get<double>() << " newton" << std::setw(7)
      << r["cg_iters_mean"].get<double>() << " cg" << std::setw(5)
      << r["unconverged_frames"].get<int>() << " unconverged" << std::setw(6)
      << r["debris_pieces"].get<int>() << " debris" << std::setw(7) << std::setprecision(2)
      << r["debris_volume_pct"].get<double>() << " % debris volume" << std::setw(7)
      << r["settle_frames"].get<int>() << " settled" << std::setw(8) << std::setprecision(1)
      << r["ms_per_newton"].get<double>() << " ms per newton";
    if (r.contains("times_uncut"))
      s << std::setw(7) << std::setprecision(2) << r["times_uncut"].get<double>() << " x uncut";
    else
      s << std::string(15, ' ');
    s << std::setw(9) << std::setprecision(4) << r["piece_residual_median"].get<double>()
      << " piece resid" << std::setw(4) << r.value("threads", 0) << " threads";
    return s.str();
  }
  // The solver: its grid and preset, and what differs from the preset's defaults.
  std::string grid = r["grid"].get<std::string>();
  if (r.contains("preset")) {
    const std::string preset = r["preset"].get<std::string>();
    const SolverOptions d =
        solverPreset(preset == "paper" ? SolverPreset::Paper : SolverPreset::Converged);
    grid += " " + preset;
    if (r.value("newton_iters", 1) != d.newtonIterations)
      grid += " n" + std::to_string(r.value("newton_iters", 1));
    if (r.value("cycles", 1) != 1) grid += " c" + std::to_string(r.value("cycles", 1));
    if (r.value("coarse_solver", std::string("cg")) != enumName(d.coarseSolver))
      grid += " " + r.value("coarse_solver", std::string("cg"));
    if (r.value("energy_guard", std::string("body")) != enumName(d.energyGuard))
      grid += " guard:" + r.value("energy_guard", std::string("body"));
    if (r.value("stiffness_tolerance", 0.0) != d.stiffnessTolerance)
      grid += " keep:" + nlohmann::json(r.value("stiffness_tolerance", 0.0)).dump();
  }
  auto percent = [](const nlohmann::json& v) {
    return v.is_number() ? 100.0 * v.get<double>() : -1.0;
  };
  s << std::left << std::setw(kSceneColumn) << r.value("scene", "") << std::setw(8)
    << r["tets"].get<int>() << std::setw(10) << r["solver"].get<std::string>() << std::setw(24)
    << grid << std::right << std::setw(4) << r["fine_sweeps"].get<int>() << std::setw(6)
    << r["coarse_iters"].get<int>() << std::fixed << std::setprecision(2) << std::setw(10)
    << r["ms_per_frame"].get<double>() << std::setw(9) << std::setprecision(1)
    << r["fps"].get<double>() << std::setw(9) << std::setprecision(0)
    << r["peak_rss_mb"].get<double>() << std::setw(11) << std::setprecision(3)
    << percent(r["rel_position_error"]) << std::setw(10) << std::setprecision(3)
    << r["volume_change_pct"].get<double>() << std::setw(8) << std::setprecision(2)
    << r["ms_surface"].get<double>() << std::setw(8) << r["ms_surface_max"].get<double>() << "  "
    << std::left << std::setw(6) << r.value("backend", std::string("cpu")) << std::right
    << std::setw(12) << std::setprecision(3) << percent(r["rel_position_error_motion"])
    << std::setw(9) << std::setprecision(1) << r["ms_p95"].get<double>() << std::setw(8)
    << std::setprecision(1) << r["newton_iters_mean"].get<double>() << std::setw(8)
    << r["cg_iters_mean"].get<double>() << std::setw(11) << std::scientific << std::setprecision(1)
    << r["residual_max"].get<double>() << std::fixed << std::setw(8)
    << r["unconverged_frames"].get<int>() << std::setw(8) << r.value("threads", 0) << std::setw(10)
    << std::setprecision(0) << r.value("launches", 0.0) << std::setw(7) << std::setprecision(1)
    << r.value("syncs", 0.0);
  return s.str();
}

// With several windows, each cut count's cost against the uncut frame in every window, and the
// median of those ratios.
void printWindowSummary(const std::vector<nlohmann::json>& rows, std::ostream& out) {
  std::map<int, std::vector<double>> ratios;
  for (const nlohmann::json& r : rows)
    if (r.contains("times_uncut")) ratios[r["cuts"].get<int>()].push_back(r["times_uncut"]);
  for (auto& [cuts, x] : ratios) {
    out << "cuts " << cuts << ": x uncut by window";
    for (double v : x) out << ' ' << std::fixed << std::setprecision(2) << v;
    std::sort(x.begin(), x.end());
    const size_t m = x.size();
    const double median = m % 2 ? x[m / 2] : 0.5 * (x[m / 2 - 1] + x[m / 2]);
    out << ", median " << median << '\n';
  }
}

}  // namespace galsculpt
