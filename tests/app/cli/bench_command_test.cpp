#include "app/cli/cli.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "app/cli/bench_reference.h"
#include "tests/app/cli/cli_run.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

// The two error figures on a known case: one loose vertex 0.3 off among four, the reference's
// largest displacement 2: the largest is 0.15 of it, the root mean square half that.
TEST(PositionError, LargestAndRootMeanSquareOverTheReferencesLargestDisplacement) {
  const test::TempDir dir;
  TetMesh mesh;
  mesh.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  std::vector<Vec3> reference = mesh.vertices;
  reference[1] += Vec3(2, 0, 0);
  const fs::path file = dir / "positions.ref";
  const PositionError self = positionError(reference, mesh, /*reference=*/true, file);
  EXPECT_EQ(self.largest, 0.0);
  EXPECT_EQ(self.rms, 0.0);
  std::vector<Vec3> run = reference;
  run[3] += Vec3(0, 0.3, 0);
  const PositionError e = positionError(run, mesh, false, file);
  EXPECT_NEAR(e.largest, 0.15, 1e-12);
  EXPECT_NEAR(e.rms, 0.075, 1e-12);
  const PositionError missing = positionError(run, mesh, false, dir / "none.ref");
  EXPECT_EQ(missing.largest, -1.0) << "no reference: no figure";
  EXPECT_EQ(missing.rms, -1.0);
}

using test::CliRun;
using test::run;

// A private assets folder (GALSCULPT_ASSETS, unset by the caller) whose "sphere" scene uses the
// small committed mesh.
void useSmallSphereAssets(const test::TempDir& dir) {
  fs::create_directories(dir / "scenes");
  test::writeText(
      dir / "scenes" / "hanging_sphere.json",
      std::string(R"({"mesh": {"file": ")") + GALSCULPT_SOURCE_DIR +
          R"(/assets/meshes/sphere_small.node"}, "material": {"youngs_modulus": 8000, "poisson_ratio": 0.48,
                      "density": 1000}, "anchors": [{"box": {"min": [-1, 0.08, -1]}}]})");
  setenv("GALSCULPT_ASSETS", dir.path().c_str(), 1);
}

// --reference-dir: the first run computes the reference and keeps it, the second reads it (the
// same errors, the row marked cached); other frames are another reference.
TEST(Cli, BenchKeepsItsReferencesInAFolder) {
  test::TempDir dir;
  useSmallSphereAssets(dir);
  const std::string refs = (dir / "refs").string();
  auto bench = [&](const char* frames, const char* json) {
    return run({"bench", "--scene", "sphere", "--frames", frames, "--reference-dir", refs, "--json",
                (dir / json).string()});
  };
  const CliRun first = bench("2", "a.json");
  const CliRun second = bench("2", "b.json");
  const CliRun other = bench("3", "c.json");
  unsetenv("GALSCULPT_ASSETS");
  ASSERT_EQ(first.code, kExitOk) << first.err;
  ASSERT_EQ(second.code, kExitOk) << second.err;
  ASSERT_EQ(other.code, kExitOk) << other.err;
  const auto a = nlohmann::json::parse(test::readText(dir / "a.json"))["results"];
  const auto b = nlohmann::json::parse(test::readText(dir / "b.json"))["results"];
  const auto c = nlohmann::json::parse(test::readText(dir / "c.json"))["results"];
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), 3u);
  EXPECT_FALSE(a[0].contains("reference_cached"));
  EXPECT_EQ(b[0]["reference_cached"], true);
  EXPECT_FALSE(c[0].contains("reference_cached")) << "3 frames are another reference";
  EXPECT_EQ(b[0]["ms_per_frame"], a[0]["ms_per_frame"]) << "the kept row";
  for (int i : {1, 2}) {
    EXPECT_GT(a[i]["rel_position_error"].get<double>(), 0.0);
    EXPECT_EQ(b[i]["rel_position_error"], a[i]["rel_position_error"]);
    EXPECT_EQ(b[i]["rel_position_error_motion"], a[i]["rel_position_error_motion"]);
  }
  int kept = 0;
  for (const auto& entry : fs::directory_iterator(refs)) kept += entry.is_regular_file();
  EXPECT_EQ(kept, 6) << "rows and positions of two references";
}

// A kept reference is one of the same physics: a default that changed under a scene that did
// not (the crack faces' closing width, 0 before it became 0.01) is another reference, not the
// old one read back against the new law's runs.
TEST(Cli, BenchReferenceKeysFollowTheDefaultsAScenesPhysicsTakes) {
  SceneDescription scene;
  scene.source = nlohmann::json::parse(R"({"name": "s"})");
  const TetMesh mesh;
  const std::uint64_t key = referenceKey(scene, mesh, 20, {}, 0);
  EXPECT_EQ(referenceKey(scene, mesh, 20, {}, 0), key);
  SceneDescription hardLaw = scene;
  hardLaw.fracture.crackWidth = 0.0;
  ASSERT_NE(scene.fracture.crackWidth, 0.0);
  EXPECT_NE(referenceKey(hardLaw, mesh, 20, {}, 0), key);
}

TEST(Cli, BenchReportsSpeedBesideErrorAsJson) {
  test::TempDir dir;
  useSmallSphereAssets(dir);
  const CliRun r =
      run({"bench", "--scene", "sphere", "--frames", "3", "--json", (dir / "b.json").string()});
  const CliRun cracks =
      run({"bench", "--cracks", "--frames", "2", "--json", (dir / "c.json").string()});
  // --debris: the debris rule of every run instead of the scene's (here: keep, the default).
  const CliRun removing = run({"bench", "--cracks", "--frames", "2", "--debris", "remove", "--json",
                               (dir / "d.json").string()});
  const CliRun badDebris = run({"bench", "--cracks", "--debris", "merge"});
  const CliRun badScene = run({"bench", "--scene", "sphere,bowl"});
  // A scene whose own preset is the paper's still gets the converged default beside it.
  test::writeText(dir / "scenes" / "charpy.json",
                  std::string(R"({"mesh": {"file": ")") + GALSCULPT_SOURCE_DIR +
                      R"(/assets/meshes/sphere_small.node"}, "solver": {"preset": "paper"}})");
  const CliRun paperScene =
      run({"bench", "--scene", "charpy", "--frames", "2", "--json", (dir / "p.json").string()});
  // Several scenes, in the order named.
  const CliRun two = run(
      {"bench", "--scene", "charpy,sphere", "--frames", "1", "--json", (dir / "2.json").string()});
  // --settle: untimed frames first; one measured frame after three settling ones ends where four
  // measured frames do.
  const CliRun settled = run({"bench", "--scene", "sphere", "--frames", "1", "--settle", "3",
                              "--json", (dir / "s.json").string()});
  const CliRun four =
      run({"bench", "--scene", "sphere", "--frames", "4", "--json", (dir / "f.json").string()});
  unsetenv("GALSCULPT_ASSETS");
  ASSERT_EQ(settled.code, kExitOk) << settled.err;
  ASSERT_EQ(four.code, kExitOk) << four.err;
  const auto s = nlohmann::json::parse(test::readText(dir / "s.json"));
  const auto f = nlohmann::json::parse(test::readText(dir / "f.json"));
  EXPECT_EQ(s["settle_frames"], 3);
  EXPECT_EQ(s["results"][0]["settle_frames"], 3);
  EXPECT_EQ(f["settle_frames"], 0);
  EXPECT_NE(f["results"][0]["volume_change_pct"].get<double>(), 0.0);
  EXPECT_NEAR(s["results"][0]["volume_change_pct"].get<double>(),
              f["results"][0]["volume_change_pct"].get<double>(),
              1e-9 * std::fabs(f["results"][0]["volume_change_pct"].get<double>()))
      << "the reference ran the settling frames";
  ASSERT_EQ(two.code, kExitOk) << two.err;
  const auto both = nlohmann::json::parse(test::readText(dir / "2.json"))["results"];
  ASSERT_EQ(both.size(), 6u);
  EXPECT_EQ(both[0]["scene"], "charpy");
  // Progress on standard error: measurements done of all, time elapsed and left.
  EXPECT_NE(two.err.find("bench: 1/6 measurement(s) done (charpy), "), std::string::npos)
      << two.err;
  EXPECT_NE(two.err.find(" left\n"), std::string::npos) << two.err;
  EXPECT_NE(two.err.find("bench: 6/6 measurement(s) done (sphere), "), std::string::npos)
      << two.err;
  EXPECT_EQ(both[5]["scene"], "sphere");
  ASSERT_EQ(paperScene.code, kExitOk) << paperScene.err;
  const auto p = nlohmann::json::parse(test::readText(dir / "p.json"));
  ASSERT_EQ(p["results"].size(), 3u);
  EXPECT_EQ(p["results"][1]["preset"], "paper");
  EXPECT_EQ(p["results"][2]["preset"], "converged");
  ASSERT_EQ(cracks.code, kExitOk) << cracks.err;
  const auto c = nlohmann::json::parse(test::readText(dir / "c.json"));
  ASSERT_EQ(c["results"].size(), 3u);
  EXPECT_EQ(c["results"][0]["cuts"], 0);
  EXPECT_EQ(c["results"][2]["cuts"], 100);
  EXPECT_EQ(c["results"][0]["damaged_edges"], 0);
  EXPECT_GT(c["results"][2]["damaged_edges"].get<int>(),
            c["results"][1]["damaged_edges"].get<int>());
  EXPECT_GT(c["results"][1]["damaged_edges"].get<int>(), 0);
  EXPECT_TRUE(c["results"][2]["rel_position_error"].is_null());
  // The surface brought up to date after each cut: measured when there are cuts.
  EXPECT_EQ(c["results"][0]["ms_surface_cut"].get<double>(), 0.0);
  EXPECT_GT(c["results"][2]["ms_surface_cut"].get<double>(), 0.0);
  EXPECT_GE(c["results"][2]["ms_surface_cut_max"].get<double>(),
            c["results"][2]["ms_surface_cut"].get<double>());
  // A frame's surface update is measured also when the frame did it itself (a body in pieces).
  ASSERT_GT(c["results"][2]["pieces"].get<int>(), 1);
  EXPECT_GT(c["results"][2]["ms_surface"].get<double>(), 0.0);
  EXPECT_NE(cracks.out.find("ms surface per cut"), std::string::npos) << cracks.out;
  EXPECT_NE(cracks.out.find(" newton"), std::string::npos) << cracks.out;
  EXPECT_NE(cracks.out.find(" unconverged"), std::string::npos) << cracks.out;
  // The debris the cuts left, and the rule that ran: the same pieces and debris either way
  // (debris is a function of the damage), only what the solver does with it differs.
  EXPECT_NE(cracks.out.find(" % debris volume"), std::string::npos) << cracks.out;
  ASSERT_EQ(removing.code, kExitOk) << removing.err;
  const auto d = nlohmann::json::parse(test::readText(dir / "d.json"));
  ASSERT_EQ(d["results"].size(), 3u);
  EXPECT_EQ(c["results"][2]["debris"], "keep");
  EXPECT_EQ(d["results"][2]["debris"], "remove");
  EXPECT_GT(c["results"][2]["debris_pieces"].get<int>(), 0);
  EXPECT_GT(c["results"][2]["debris_volume_pct"].get<double>(), 0.0);
  EXPECT_EQ(d["results"][2]["debris_pieces"], c["results"][2]["debris_pieces"]);
  EXPECT_EQ(d["results"][2]["debris_volume_pct"], c["results"][2]["debris_volume_pct"]);
  EXPECT_EQ(c["results"][0]["debris_pieces"], 0);
  EXPECT_EQ(badScene.code, kExitUsage);
  EXPECT_NE(badScene.err.find("unknown scene 'bowl'"), std::string::npos) << badScene.err;
  EXPECT_EQ(badDebris.code, kExitUsage);
  EXPECT_NE(badDebris.err.find("--debris must be keep or remove"), std::string::npos)
      << badDebris.err;
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const auto j = nlohmann::json::parse(test::readText(dir / "b.json"));
  // The reference, the paper's setting and the scene's own (the converged default).
  ASSERT_EQ(j["results"].size(), 3u);
  for (const char* key : {"scene",
                          "tets",
                          "solver",
                          "grid",
                          "fine_sweeps",
                          "coarse_iters",
                          "frames",
                          "ms_per_frame",
                          "fps",
                          "peak_rss_mb",
                          "rel_position_error",
                          "volume_change_pct",
                          "preset",
                          "rel_position_error_motion",
                          "rel_position_error_rms",
                          "rel_position_error_motion_rms",
                          "motion_frame",
                          "ms_p95",
                          "newton_iters_mean",
                          "cg_iters_mean",
                          "residual_max",
                          "unconverged_frames"}) {
    EXPECT_TRUE(j["results"][1].contains(key)) << key;
    EXPECT_TRUE(j["results"][2].contains(key)) << key;
  }
  EXPECT_EQ(j["results"][0]["solver"], "reference");
  EXPECT_EQ(j["results"][1]["solver"], "multigrid");
  EXPECT_EQ(j["results"][1]["preset"], "paper");
  EXPECT_EQ(j["results"][2]["preset"], "converged");
  EXPECT_EQ(j["results"][1]["motion_frame"], 3) << "within the run";
  EXPECT_EQ(j["results"][1]["cg_iters_mean"], 0.0) << "the paper's setting has no CG";
  EXPECT_GT(j["results"][2]["cg_iters_mean"].get<double>(), 0.0);
  EXPECT_EQ(j["results"][2]["unconverged_frames"], 0);
  EXPECT_GT(j["results"][1]["rel_position_error"].get<double>(),
            j["results"][2]["rel_position_error"].get<double>())
      << "the converged frames are closer to the reference";
  EXPECT_EQ(j["results"][0]["backend"], "cpu") << "the reference always runs on the CPU";
  EXPECT_TRUE(j["results"][1]["backend"] == "cpu" || j["results"][1]["backend"] == "cuda");
  if (j["results"][1]["backend"] == "cpu") {
    EXPECT_TRUE(j["results"][1].contains("backend_note")) << "auto says why it is not on a GPU";
  }
  EXPECT_GT(j["results"][1]["rel_position_error"].get<double>(), 0.0);
  EXPECT_LT(j["results"][1]["rel_position_error"].get<double>(), 1.0);
  for (int i : {1, 2}) {
    const double rms = j["results"][i]["rel_position_error_rms"].get<double>();
    EXPECT_GT(rms, 0.0) << i;
    EXPECT_LE(rms, j["results"][i]["rel_position_error"].get<double>()) << i;
  }
  EXPECT_EQ(run({"bench", "--scene", "moon"}).code, kExitUsage);
}

// charpy_after_break: Charpy's scene measured from frame 40 on, in every run (the reference's
// too), --settle counted from there; named in the unknown-scene message.
TEST(Cli, BenchMeasuresCharpyAfterTheBreakFromItsStartFrame) {
  test::TempDir dir;
  useSmallSphereAssets(dir);
  test::writeText(dir / "scenes" / "charpy.json",
                  std::string(R"({"mesh": {"file": ")") + GALSCULPT_SOURCE_DIR +
                      R"(/assets/meshes/sphere_small.node"}, "material": {"youngs_modulus": 8000,
                      "poisson_ratio": 0.48, "density": 1000}})");
  const CliRun broken = run({"bench", "--scene", "charpy_after_break", "--frames", "1", "--json",
                             (dir / "b.json").string()});
  const CliRun settled = run({"bench", "--scene", "charpy", "--frames", "1", "--settle", "40",
                              "--json", (dir / "s.json").string()});
  const CliRun later = run({"bench", "--scene", "charpy_after_break", "--frames", "1", "--settle",
                            "2", "--json", (dir / "l.json").string()});
  const CliRun unknown = run({"bench", "--scene", "charpy_broken"});
  unsetenv("GALSCULPT_ASSETS");
  ASSERT_EQ(broken.code, kExitOk) << broken.err;
  ASSERT_EQ(settled.code, kExitOk) << settled.err;
  ASSERT_EQ(later.code, kExitOk) << later.err;
  const auto b = nlohmann::json::parse(test::readText(dir / "b.json"))["results"];
  const auto s = nlohmann::json::parse(test::readText(dir / "s.json"))["results"];
  const auto l = nlohmann::json::parse(test::readText(dir / "l.json"))["results"];
  ASSERT_EQ(b.size(), 3u) << "the reference, the paper's setting and the converged default";
  ASSERT_EQ(s.size(), 3u);
  ASSERT_EQ(l.size(), 3u);
  for (size_t i = 0; i < b.size(); ++i) {
    EXPECT_EQ(b[i]["scene"], "charpy_after_break") << i;
    EXPECT_EQ(b[i]["settle_frames"], 40) << i;
    EXPECT_EQ(l[i]["settle_frames"], 42) << i;
    // The frames are Charpy's from frame 40 on: the same state as --settle 40 reaches.
    EXPECT_EQ(b[i]["volume_change_pct"], s[i]["volume_change_pct"]) << i;
    EXPECT_NE(b[i]["volume_change_pct"], l[i]["volume_change_pct"]) << i;
  }
  EXPECT_EQ(b[0]["solver"], "reference");
  EXPECT_EQ(b[1]["rel_position_error"], s[1]["rel_position_error"]) << "the reference ran them too";
  EXPECT_EQ(unknown.code, kExitUsage);
  EXPECT_NE(unknown.err.find("charpy_after_break"), std::string::npos) << unknown.err;
}

// sphere_cut: the hanging sphere after --cracks's 100 cuts, measured as a scene: its reference is
// cut the same way, so its rows have errors; --cracks (its own cuts) does not take it.
TEST(Cli, BenchMeasuresTheCutSphereAgainstACutReference) {
  test::TempDir dir;
  useSmallSphereAssets(dir);
  const CliRun cut =
      run({"bench", "--scene", "sphere_cut", "--frames", "2", "--json", (dir / "c.json").string()});
  const CliRun cracks =
      run({"bench", "--cracks", "--frames", "2", "--json", (dir / "k.json").string()});
  const CliRun both = run({"bench", "--cracks", "--scene", "sphere_cut"});
  unsetenv("GALSCULPT_ASSETS");
  ASSERT_EQ(cut.code, kExitOk) << cut.err;
  ASSERT_EQ(cracks.code, kExitOk) << cracks.err;
  const auto c = nlohmann::json::parse(test::readText(dir / "c.json"))["results"];
  const auto k = nlohmann::json::parse(test::readText(dir / "k.json"))["results"];
  ASSERT_EQ(c.size(), 3u);
  ASSERT_EQ(k.size(), 3u);
  for (size_t i = 0; i < c.size(); ++i) {
    EXPECT_EQ(c[i]["scene"], "sphere_cut") << i;
    EXPECT_EQ(c[i]["scene_cuts"], 100) << i;
    EXPECT_FALSE(c[i].contains("cuts")) << i << ": a scene's row, not --cracks's";
    // The same cuts as --cracks's 100-cut row.
    EXPECT_EQ(c[i]["damaged_edges"], k[2]["damaged_edges"]) << i;
    EXPECT_EQ(c[i]["pieces"], k[2]["pieces"]) << i;
    EXPECT_TRUE(c[i]["rel_position_error_motion"].is_number()) << i;
  }
  EXPECT_EQ(c[0]["solver"], "reference");
  EXPECT_EQ(c[0]["rel_position_error"].get<double>(), 0.0);
  EXPECT_GT(c[1]["rel_position_error"].get<double>(), 0.0)
      << "the paper's setting off the reference";
  EXPECT_LT(c[2]["rel_position_error"].get<double>(), c[1]["rel_position_error"].get<double>());
  EXPECT_EQ(both.code, kExitUsage);
  EXPECT_NE(both.err.find("--cracks makes its own cuts"), std::string::npos) << both.err;
}

TEST(Cli, BenchRunsTheScenesWithTheSolverPresetAsked) {
  test::TempDir dir;
  useSmallSphereAssets(dir);
  // --preset paper: every cut count with the paper's fixed work (one Newton step, no CG).
  const CliRun paper = run({"bench", "--cracks", "--frames", "2", "--preset", "paper", "--json",
                            (dir / "p.json").string()});
  // A scene of the paper's preset whose own solver keys stay: --preset converged keeps its grid.
  test::writeText(
      dir / "scenes" / "hanging_sphere.json",
      std::string(R"({"mesh": {"file": ")") + GALSCULPT_SOURCE_DIR +
          R"(/assets/meshes/sphere_small.node"}, "anchors": [{"box": {"min": [-1, 0.08, -1]}}],
                      "solver": {"preset": "paper", "grid": "20/all"}})");
  const CliRun converged = run({"bench", "--cracks", "--frames", "2", "--preset", "converged",
                                "--json", (dir / "c.json").string()});
  const CliRun own =
      run({"bench", "--cracks", "--frames", "2", "--json", (dir / "o.json").string()});
  const CliRun bad = run({"bench", "--cracks", "--preset", "fast"});
  unsetenv("GALSCULPT_ASSETS");
  ASSERT_EQ(paper.code, kExitOk) << paper.err;
  ASSERT_EQ(converged.code, kExitOk) << converged.err;
  ASSERT_EQ(own.code, kExitOk) << own.err;
  const auto p = nlohmann::json::parse(test::readText(dir / "p.json"));
  const auto c = nlohmann::json::parse(test::readText(dir / "c.json"));
  const auto o = nlohmann::json::parse(test::readText(dir / "o.json"));
  ASSERT_EQ(p["results"].size(), 3u);
  ASSERT_EQ(c["results"].size(), 3u);
  ASSERT_EQ(o["results"].size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(p["results"][i]["preset"], "paper") << i;
    EXPECT_EQ(p["results"][i]["newton_iters"], 1) << i;
    EXPECT_EQ(p["results"][i]["newton_iters_mean"].get<double>(), 1.0) << i;
    EXPECT_EQ(p["results"][i]["cg_iters_mean"].get<double>(), 0.0) << i;
    EXPECT_EQ(o["results"][i]["preset"], "paper") << i << ": the scene's own";
    EXPECT_EQ(c["results"][i]["preset"], "converged") << i;
    EXPECT_EQ(c["results"][i]["newton_iters"], 40) << i;
    EXPECT_EQ(c["results"][i]["grid"], "20/all") << i << ": the scene's key stays";
  }
  EXPECT_GT(c["results"][2]["cg_iters_mean"].get<double>(), 0.0);
  EXPECT_EQ(bad.code, kExitUsage);
  EXPECT_NE(bad.err.find("--preset must be converged or paper"), std::string::npos) << bad.err;
}

TEST(Cli, BenchCracksMeasuresSeveralSettledWindowsInOneRun) {
  test::TempDir dir;
  useSmallSphereAssets(dir);
  const CliRun windows = run({"bench", "--cracks", "--frames", "2", "--settle", "0,3", "--json",
                              (dir / "w.json").string()});
  const CliRun single = run(
      {"bench", "--cracks", "--frames", "2", "--settle", "3", "--json", (dir / "s.json").string()});
  const CliRun overlapping = run({"bench", "--cracks", "--frames", "2", "--settle", "0,1"});
  const CliRun noCracks = run({"bench", "--scene", "sphere", "--settle", "0,30"});
  const CliRun notANumber = run({"bench", "--cracks", "--settle", "3,x"});
  unsetenv("GALSCULPT_ASSETS");
  ASSERT_EQ(windows.code, kExitOk) << windows.err;
  ASSERT_EQ(single.code, kExitOk) << single.err;
  const auto w = nlohmann::json::parse(test::readText(dir / "w.json"));
  const auto s = nlohmann::json::parse(test::readText(dir / "s.json"));
  EXPECT_EQ(w["settle_frames"], 0);
  EXPECT_EQ(w["settle_windows"], nlohmann::json::array({0, 3}));
  // Each setting's windows in order: 0, 10 and 100 cuts, each at 0 and 3 frames settled.
  ASSERT_EQ(w["results"].size(), 6u);
  ASSERT_EQ(s["results"].size(), 3u);
  for (int k = 0; k < 6; ++k) {
    const nlohmann::json& r = w["results"][k];
    EXPECT_EQ(r["settle_frames"], k % 2 == 0 ? 0 : 3) << k;
    EXPECT_GT(r["ms_per_newton"].get<double>(), 0.0) << k;
    const nlohmann::json& uncut = w["results"][k % 2];
    if (r["cuts"].get<int>() == 0) {
      EXPECT_FALSE(r.contains("times_uncut")) << k;
    } else {
      EXPECT_NEAR(r["times_uncut"].get<double>(),
                  r["ms_per_frame"].get<double>() / uncut["ms_per_frame"].get<double>(), 1e-12)
          << k;
    }
  }
  // The second window is the state a run settled for three frames measures: the measured frames
  // of the first count as settled.
  for (int c = 0; c < 3; ++c) {
    const nlohmann::json& a = w["results"][2 * c + 1];
    const nlohmann::json& b = s["results"][c];
    EXPECT_EQ(a["cuts"], b["cuts"]);
    EXPECT_EQ(a["damaged_edges"], b["damaged_edges"]);
    EXPECT_EQ(a["pieces"], b["pieces"]);
    EXPECT_EQ(a["newton_iters_mean"], b["newton_iters_mean"]) << c;
    EXPECT_NEAR(a["volume_change_pct"].get<double>(), b["volume_change_pct"].get<double>(),
                1e-9 * std::fabs(b["volume_change_pct"].get<double>()) + 1e-12)
        << c;
  }
  EXPECT_NE(windows.out.find("cuts 100: x uncut by window "), std::string::npos) << windows.out;
  EXPECT_NE(windows.out.find(" ms per newton"), std::string::npos) << windows.out;
  // The worst piece's own residual: the body's for the uncut sphere (one piece), measured piece
  // by piece for the cut ones.
  EXPECT_NE(windows.out.find(" piece resid"), std::string::npos) << windows.out;
  for (const nlohmann::json& r : w["results"]) {
    EXPECT_GE(r["piece_residual_median"].get<double>(), 0.0);
    EXPECT_LE(r["piece_residual_median"], r["piece_residual_max"]);
    if (r["cuts"] == 0) {
      EXPECT_EQ(r["piece_residual_max"], r["residual_max"]);
      EXPECT_EQ(r["piece_unconverged_frames"], r["unconverged_frames"]);
    }
    EXPECT_EQ(r["piece_unconverged_frames"].get<int>() > 0,
              r["piece_residual_max"].get<double>() > r["residual_tolerance"].get<double>());
  }
  EXPECT_GT(w["results"][4]["pieces"].get<int>(), 1);
  EXPECT_GT(w["results"][4]["piece_residual_max"].get<double>(), 0.0);
  EXPECT_EQ(single.out.find("x uncut by window"), std::string::npos) << "one window: no summary";
  EXPECT_EQ(overlapping.code, kExitUsage);
  EXPECT_NE(overlapping.err.find("before window 1 (0 + 2 frames) has ended"), std::string::npos)
      << overlapping.err;
  EXPECT_EQ(noCracks.code, kExitUsage);
  EXPECT_NE(noCracks.err.find("several counts only with --cracks"), std::string::npos)
      << noCracks.err;
  EXPECT_EQ(notANumber.code, kExitUsage);
  EXPECT_NE(notANumber.err.find("--settle expects an integer or a comma-separated list"),
            std::string::npos)
      << notANumber.err;
}

}  // namespace
}  // namespace galsculpt
