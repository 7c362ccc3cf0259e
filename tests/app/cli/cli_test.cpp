#include "app/cli/cli.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/surface/surface_io.h"
#include "gpu/cuda_step_backend.h"
#include "solver/mesh/shape_generators.h"
#include "tests/app/cli/cli_run.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
CliRun run(const std::vector<std::string>& args) {
  return test::runCliCapture(args);
}

TEST(Cli, HelpAndVersion) {
  EXPECT_EQ(run({"--help"}).code, kExitOk);
  EXPECT_NE(run({"help"}).out.find("mesh import SURFACE OUT --tets N"), std::string::npos);
  EXPECT_NE(run({"--version"}).out.find("galsculpt "), std::string::npos);
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run({"frobnicate"}).code, kExitUsage);
  EXPECT_EQ(run({"mesh"}).code, kExitUsage);
  EXPECT_EQ(run({"mesh", "info"}).code, kExitUsage);
  EXPECT_EQ(run({"mesh", "info", "a.node", "--bogus"}).code, kExitUsage);
  const CliRun r = run({"mesh", "import", "a.obj", "b.node"});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_NE(r.err.find("needs --tets N"), std::string::npos);
  EXPECT_EQ(run({"mesh", "import", "a.obj", "b.node", "--tets", "ten"}).code, kExitUsage);
  EXPECT_EQ(run({"mesh", "convert", "a.node", "b.docx"}).code, kExitUsage);
}

TEST(Cli, BadInputExitsThreeWithFileAndLine) {
  const fs::path broken = fs::path(GALSCULPT_TEST_DATA) / "broken" / "nan_coordinate.node";
  const CliRun r = run({"mesh", "info", broken.string()});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("nan_coordinate.node:3: coordinate is not finite"), std::string::npos)
      << r.err;
  EXPECT_EQ(run({"mesh", "info", "/nonexistent/x.obj"}).code, kExitBadInput);
}

TEST(Cli, InfoOfTetMeshAndSurface) {
  test::TempDir dir;
  writeSurface(dir / "s.ply", makeIcosphere(1.0, 2));
  const CliRun surface = run({"mesh", "info", (dir / "s.ply").string()});
  ASSERT_EQ(surface.code, kExitOk) << surface.err;
  EXPECT_NE(surface.out.find("kind: surface"), std::string::npos);
  EXPECT_NE(surface.out.find("faces: 320"), std::string::npos);
  EXPECT_NE(surface.out.find("watertight: yes"), std::string::npos);
  EXPECT_NE(surface.out.find("pieces: 1"), std::string::npos);

  const fs::path tricky = fs::path(GALSCULPT_TEST_DATA) / "valid" / "tricky.node";
  const CliRun tet = run({"mesh", "info", tricky.string(), "--json"});
  ASSERT_EQ(tet.code, kExitOk) << tet.err;
  const auto j = nlohmann::json::parse(tet.out);
  EXPECT_EQ(j["tets"], 2);
  EXPECT_EQ(j["reoriented_tets"], 1);
  EXPECT_EQ(j["pieces"], 1);
  EXPECT_EQ(j["quality_histogram"].size(), 10u);
}

TEST(Cli, ConvertBetweenFormats) {
  test::TempDir dir;
  const CliRun gen = run({"mesh", "generate", "sphere", (dir / "s.node").string(), "--tets", "2000",
                          "--radius", "0.5"});
  ASSERT_EQ(gen.code, kExitOk) << gen.err;
  for (const char* out : {"s.msh", "s.vtk", "s.obj", "s.stl", "s.glb"}) {
    const CliRun r = run({"mesh", "convert", (dir / "s.node").string(), (dir / out).string()});
    EXPECT_EQ(r.code, kExitOk) << out << ": " << r.err;
    EXPECT_TRUE(fs::exists(dir / out)) << out;
  }
  const CliRun back = run({"mesh", "convert", (dir / "s.msh").string(), (dir / "t.node").string()});
  ASSERT_EQ(back.code, kExitOk) << back.err;
  // The same tets; each set carries its own stamp (its last line).
  auto withoutStamp = [](std::string text) {
    return text.substr(0, text.rfind("# galsculpt set"));
  };
  EXPECT_EQ(withoutStamp(test::readText(dir / "t.ele")),
            withoutStamp(test::readText(dir / "s.ele")));
  const CliRun surf = run({"mesh", "convert", (dir / "s.obj").string(), (dir / "s2.ply").string()});
  EXPECT_EQ(surf.code, kExitOk) << surf.err;
  const CliRun vol = run({"mesh", "convert", (dir / "s.obj").string(), (dir / "s3.node").string()});
  EXPECT_EQ(vol.code, kExitUsage) << "surface to tets needs --tets";
}

TEST(Cli, ImportRejectsAnOpenSurfaceWithExitThree) {
  test::TempDir dir;
  TriMesh open = makeIcosphere(1.0, 2);
  open.faces.resize(open.faces.size() - 4);
  writeSurface(dir / "open.obj", open);
  const CliRun r = run(
      {"mesh", "import", (dir / "open.obj").string(), (dir / "o.node").string(), "--tets", "500"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("the surface is open"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "o.node"));
}

TEST(Cli, RunWritesMetricsAndSurfaces) {
  test::TempDir dir;
  const fs::path scene = fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json";
  const CliRun r = run({"run", scene.string(), "--frames", "4", "--out", (dir / "out").string(),
                        "--metrics", (dir / "m.csv").string(), "--export-every", "2"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_TRUE(fs::exists(dir / "out" / "final.obj"));
  EXPECT_TRUE(fs::exists(dir / "out" / "frame_00002.obj"));
  EXPECT_TRUE(fs::exists(dir / "out" / "frame_00004.obj"));
  std::istringstream csv(test::readText(dir / "m.csv"));
  std::string line;
  int rows = 0;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("frame,time_s,ms_total,", 0), 0u);
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 4);
  EXPECT_EQ(run({"run", scene.string(), "--frames", "2"}).code, kExitUsage) << "--out is required";
  EXPECT_EQ(run({"run", scene.string(), "--out", "x", "--frames", "0"}).code, kExitUsage);
}

TEST(Cli, PlayRunsAScriptHeadlessAndWritesTheFinalSurface) {
  test::TempDir dir;
  const fs::path script = fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scripts" / "sphere_cut.json";
  const CliRun r =
      run({"play", script.string(), "--out", (dir / "out").string(), "--export-every", "30"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("2 piece(s)"), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("left a piece above"), std::string::npos) << "both halves solved: " << r.err;
  EXPECT_TRUE(fs::exists(dir / "out" / "final.obj"));
  EXPECT_TRUE(fs::exists(dir / "out" / "frame_00060.obj"));
  EXPECT_TRUE(fs::exists(dir / "out" / "metrics.csv"));
  EXPECT_EQ(run({"play", script.string()}).code, kExitUsage) << "--out is required";
  EXPECT_EQ(
      run({"play", script.string(), "--out", (dir / "o3").string(), "--export-format", "fbx"}).code,
      kExitUsage);

  // Other formats and the tet mesh with its damage.
  const CliRun formats =
      run({"play", script.string(), "--out", (dir / "glb").string(), "--export-every", "60",
           "--export-format", "glb", "--export-tets", "--png-every", "30", "--size", "160x100"});
  ASSERT_EQ(formats.code, kExitOk) << formats.err;
  for (const char* name :
       {"final.obj", "final.glb", "frame_00060.glb", "final.node", "final.ele", "final.face",
        "final.damage", "final.vtk", "frame_00030.png", "frame_00060.png", "final.png"}) {
    EXPECT_TRUE(fs::exists(dir / "glb" / name)) << name;
  }
  test::writeText(dir / "bad.json", "{\"frames\": 2}");
  const CliRun bad = run({"play", (dir / "bad.json").string(), "--out", (dir / "o2").string()});
  EXPECT_EQ(bad.code, kExitBadInput);
  EXPECT_NE(bad.err.find("$.scene"), std::string::npos) << bad.err;
}

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  return fields;
}

// Ten knife strokes through the clay ball (dozens of pieces), 30 frames, played from `scene`;
// the metrics' rows as columns by name.
struct CutBallRun {
  CliRun cli;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  double at(size_t row, const std::string& name) const {
    return std::stod(rows[row][std::find(header.begin(), header.end(), name) - header.begin()]);
  }
};

CutBallRun playTenStrokesThroughTheClayBall(const test::TempDir& dir, const fs::path& scene) {
  nlohmann::json events = nlohmann::json::array();
  int frame = 2;
  for (double at : {-0.06, -0.03, 0.0, 0.03, 0.06}) {
    events.push_back({{"frame", frame},
                      {"tool", "knife"},
                      {"duration", 2},
                      {"from", {{-0.2, 0.2, at}, {0.2, 0.2, at}}},
                      {"to", {{-0.2, -0.2, at}, {0.2, -0.2, at}}}});
    events.push_back({{"frame", frame + 1},
                      {"tool", "knife"},
                      {"duration", 2},
                      {"from", {{at, 0.2, -0.2}, {at, 0.2, 0.2}}},
                      {"to", {{at, -0.2, -0.2}, {at, -0.2, 0.2}}}});
    frame += 3;
  }
  const nlohmann::json script = {{"scene", scene.string()}, {"frames", 30}, {"events", events}};
  test::writeText(dir / "cuts.json", script.dump());
  CutBallRun played;
  played.cli = run({"play", (dir / "cuts.json").string(), "--out", (dir / "out").string()});
  std::ifstream csv(dir / "out" / "metrics.csv");
  std::string line;
  std::getline(csv, line);
  played.header = splitCsv(line);
  while (std::getline(csv, line)) played.rows.push_back(splitCsv(line));
  return played;
}

const fs::path kClayBall = fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json";

// With the body's residual alone deciding (solver.converge_pieces false), some frames of the cut
// ball leave a piece above the residual tolerance of its own loads while the body's residual is
// within it (docs/physics.md). The run says how many, as the metrics' piece_residual column
// counts them.
TEST(Cli, PlaySaysWhichFramesLeftAPieceAboveTheTolerance) {
  test::TempDir dir;
  nlohmann::json scene = nlohmann::json::parse(test::readText(kClayBall));
  scene["mesh"]["file"] = (kClayBall.parent_path() / "../meshes/sphere_small.node").string();
  scene["solver"]["converge_pieces"] = false;
  test::writeText(dir / "ball.json", scene.dump());
  const CutBallRun r = playTenStrokesThroughTheClayBall(dir, dir / "ball.json");
  ASSERT_EQ(r.cli.code, kExitOk) << r.cli.err;
  int above = 0;
  for (size_t i = 0; i < r.rows.size(); ++i) {
    EXPECT_LE(r.at(i, "residual"), 0.01) << i;
    EXPECT_EQ(r.at(i, "converged"), 1.0) << i;
    if (r.at(i, "pieces") > 1 && r.at(i, "piece_residual") > 0.01) ++above;
  }
  ASSERT_GT(above, 0) << "the cut ball leaves some piece unsolved: nothing to say";
  EXPECT_NE(r.cli.err.find("note: " + std::to_string(above) + " frame(s) left a piece above"),
            std::string::npos)
      << r.cli.err;
}

// The scenes' default solves every piece: each frame of the same cuts converges with every piece
// within the tolerance of its own loads, so the run has nothing to note.
TEST(Cli, PlaySolvesEveryPieceOfACutBall) {
  test::TempDir dir;
  const CutBallRun r = playTenStrokesThroughTheClayBall(dir, kClayBall);
  ASSERT_EQ(r.cli.code, kExitOk) << r.cli.err;
  ASSERT_EQ(r.rows.size(), 30u);
  EXPECT_GT(r.at(29, "pieces"), 10.0) << "dozens of pieces";
  for (size_t i = 0; i < r.rows.size(); ++i) {
    EXPECT_EQ(r.at(i, "converged"), 1.0) << i;
    EXPECT_LE(r.at(i, "piece_residual"), 0.01) << i;
  }
  EXPECT_EQ(r.cli.err.find("left a piece above"), std::string::npos) << r.cli.err;
}

// The reference solves to Newton's step test, with no residual tolerance: its run says nothing
// of pieces above one (it once counted every frame whose pieces had any residual at all).
TEST(Cli, ReferencePlayNotesNoPieceAboveATolerance) {
  test::TempDir dir;
  const nlohmann::json script = {{"scene", kClayBall.string()},
                                 {"frames", 4},
                                 {"events",
                                  {{{"frame", 1},
                                    {"tool", "knife"},
                                    {"duration", 1},
                                    {"from", {{-0.2, 0.2, 0.02}, {0.2, 0.2, 0.02}}},
                                    {"to", {{-0.2, -0.2, 0.02}, {0.2, -0.2, 0.02}}}}}}};
  test::writeText(dir / "cut.json", script.dump());
  const CliRun r = run({"play", (dir / "cut.json").string(), "--out", (dir / "out").string(),
                        "--solver", "reference"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  std::ifstream csv(dir / "out" / "metrics.csv");
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = splitCsv(line);
  const auto at = [&](const std::vector<std::string>& row, const std::string& name) {
    return std::stod(row[std::find(header.begin(), header.end(), name) - header.begin()]);
  };
  std::vector<std::string> row;
  while (std::getline(csv, line)) row = splitCsv(line);
  ASSERT_GT(at(row, "pieces"), 1.0) << "the knife cut the ball through";
  ASSERT_GT(at(row, "piece_residual"), 0.0);
  EXPECT_EQ(r.err.find("left a piece above"), std::string::npos) << r.err;
}

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
  EXPECT_EQ(run({"bench", "--scene", "moon"}).code, kExitUsage);
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

// --backend on run (and play, bench, open): cpu runs without a note; cuda runs on the GPU or
// says why not; anything else is a usage error.
TEST(Cli, BackendFlag) {
  test::TempDir dir;
  const fs::path scene = fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json";
  const CliRun cpu = run(
      {"run", scene.string(), "--frames", "1", "--out", (dir / "a").string(), "--backend", "cpu"});
  ASSERT_EQ(cpu.code, kExitOk) << cpu.err;
  EXPECT_EQ(cpu.err.find("running on the CPU"), std::string::npos) << cpu.err;
  const CliRun cuda = run(
      {"run", scene.string(), "--frames", "1", "--out", (dir / "b").string(), "--backend", "cuda"});
  ASSERT_EQ(cuda.code, kExitOk) << cuda.err;
  std::string reason;
  const SimModel probe = buildSimModel(test::gridBar(1, 1, 1, 0.1), MaterialParams{});
  StepSettings multigrid;
  multigrid.multigrid = true;
  if (!gpu::makeCudaStepBackend(probe, multigrid, reason)) {
    EXPECT_NE(cuda.err.find("note: the CUDA backend is not available (" + reason + ")"),
              std::string::npos)
        << cuda.err;
  }
  const fs::path script = fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scripts" / "sphere_cut.json";
  const std::vector<std::vector<std::string>> bad = {
      {"run", scene.string(), "--frames", "1", "--out", (dir / "c").string()},
      {"play", script.string(), "--out", (dir / "c").string()},
      {"bench"},
      {"open", scene.string(), "--headless", "--out", (dir / "c").string()}};
  for (std::vector<std::string> args : bad) {
    args.insert(args.end(), {"--backend", "gpu"});
    const CliRun r = run(args);
    EXPECT_EQ(r.code, kExitUsage) << args[0];
    EXPECT_NE(r.err.find("--backend must be auto, cpu or cuda"), std::string::npos)
        << args[0] << ": " << r.err;
  }
}

// --solver-option sets the scene's solver keys (run, play, bench, open): the frames take them;
// an unknown key or a malformed list is a usage error naming the keys, a value out of range an
// input error naming the option.
TEST(Cli, SolverOptionFlag) {
  test::TempDir dir;
  const fs::path scene = fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json";
  const CliRun one = run({"run", scene.string(), "--frames", "3", "--out", (dir / "a").string(),
                          "--solver-option", "newton_iters=1,pcg_tolerance=0", "--backend", "cpu"});
  ASSERT_EQ(one.code, kExitOk) << one.err;
  std::istringstream csv(test::readText(dir / "a" / "metrics.csv"));
  std::string header, line;
  std::getline(csv, header);
  std::vector<std::string> names;
  for (std::istringstream h(header); std::getline(h, line, ',');) names.push_back(line);
  const size_t column = std::find(names.begin(), names.end(), "newton_iterations") - names.begin();
  ASSERT_LT(column, names.size());
  int rows = 0;
  while (std::getline(csv, line)) {
    std::vector<std::string> cells;
    for (std::istringstream r(line); std::getline(r, header, ',');) cells.push_back(header);
    ASSERT_EQ(cells.size(), names.size());
    EXPECT_EQ(cells[column], "1") << "newton_iters=1: one Newton iteration a frame";
    ++rows;
  }
  EXPECT_EQ(rows, 3);
  const fs::path script = fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scripts" / "sphere_cut.json";
  const std::vector<std::vector<std::string>> commands = {
      {"run", scene.string(), "--frames", "1", "--out", (dir / "c").string()},
      {"play", script.string(), "--out", (dir / "c").string()},
      {"bench"},
      {"open", scene.string(), "--headless", "--out", (dir / "c").string()}};
  for (std::vector<std::string> args : commands) {
    args.insert(args.end(), {"--solver-option", "newton_iters=2,sweeps=3"});
    const CliRun r = run(args);
    EXPECT_EQ(r.code, kExitUsage) << args[0];
    EXPECT_NE(r.err.find("--solver-option: unknown solver option 'sweeps' (options: preset, "),
              std::string::npos)
        << args[0] << ": " << r.err;
  }
  const CliRun malformed = run({"run", scene.string(), "--frames", "1", "--out",
                                (dir / "d").string(), "--solver-option", "newton_iters"});
  EXPECT_EQ(malformed.code, kExitUsage);
  EXPECT_NE(malformed.err.find("'newton_iters' is not KEY=VALUE"), std::string::npos)
      << malformed.err;
  const CliRun outOfRange = run({"run", scene.string(), "--frames", "1", "--out",
                                 (dir / "e").string(), "--solver-option=newton_iters=500"});
  EXPECT_EQ(outOfRange.code, kExitBadInput);
  EXPECT_NE(outOfRange.err.find("solver options newton_iters=500: "), std::string::npos)
      << outOfRange.err;
  EXPECT_NE(outOfRange.err.find("$.solver.newton_iters"), std::string::npos) << outOfRange.err;
}

TEST(Cli, SceneCheck) {
  const fs::path scene = fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json";
  const CliRun r = run({"scene", "check", scene.string(), "--load-mesh"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("material: clay"), std::string::npos);
  EXPECT_NE(r.out.find("tets\n"), std::string::npos);
}

}  // namespace
}  // namespace galsculpt
