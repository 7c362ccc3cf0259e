#include "app/cli/cli.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/app/cli/cli_run.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::run;

TEST(Cli, RunWritesMetricsAndSurfaces) {
  test::TempDir dir;
  const fs::path scene = test::kDefaultSceneFile;
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
  EXPECT_NE(r.out.find("final surface: 2 piece(s), closed"), std::string::npos) << r.out;

  // The export is whole by the project's own check, one shell a piece, and imports again.
  for (const char* name : {"final.obj", "frame_00060.obj"}) {
    const CliRun info = run({"mesh", "info", (dir / "out" / name).string()});
    ASSERT_EQ(info.code, kExitOk) << info.err;
    for (const char* line : {"watertight: yes", "self_intersections: 0", "shells: 2", "pieces: 2",
                             "inward_shells: 0", "contact: none"})
      EXPECT_NE(info.out.find(line), std::string::npos) << name << ": " << line << '\n' << info.out;
  }
  const CliRun again = run({"mesh", "import", (dir / "out" / "final.obj").string(),
                            (dir / "again.node").string(), "--tets", "10000"});
  ASSERT_EQ(again.code, kExitOk) << again.err;
  // Each step of the import says the time since it began; TetGen's attempts, how many there
  // may be.
  EXPECT_NE(again.err.find("s] tetgen attempt 1 of at most 30 ("), std::string::npos) << again.err;
  // Too few tets for the surface: refused, naming a count that works.
  const CliRun few = run({"mesh", "import", (dir / "out" / "final.obj").string(),
                          (dir / "few.node").string(), "--tets", "300"});
  EXPECT_EQ(few.code, kExitFailure) << few.err;
  const size_t hint = few.err.find("(--tets ");
  ASSERT_NE(hint, std::string::npos) << few.err;
  const std::string works = few.err.substr(hint + 8, few.err.find(' ', hint + 8) - hint - 8);
  EXPECT_NE(few.err.find(" or more would do)", hint), std::string::npos) << few.err;
  const CliRun suggested = run({"mesh", "import", (dir / "out" / "final.obj").string(),
                                (dir / "few.node").string(), "--tets", works});
  EXPECT_EQ(suggested.code, kExitOk) << "the suggested " << works << " tets: " << suggested.err;
  const CliRun againInfo = run({"mesh", "info", (dir / "again.node").string()});
  EXPECT_NE(againInfo.out.find("pieces: 2"), std::string::npos) << againInfo.out;

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
  for (const char* name : {"final.glb", "frame_00060.glb"}) {
    const CliRun info = run({"mesh", "info", (dir / "glb" / name).string()});
    EXPECT_NE(info.out.find("watertight: yes"), std::string::npos) << name << '\n' << info.out;
    EXPECT_NE(info.out.find("shells: 2"), std::string::npos) << name << '\n' << info.out;
  }
  // The tets reopen cracked: mesh info counts the pieces through the damage.
  const CliRun tets = run({"mesh", "info", (dir / "glb" / "final.node").string()});
  EXPECT_NE(tets.out.find("pieces: 2\nmesh_pieces: 1"), std::string::npos) << tets.out;
  // A second run into the same folder owns it: the first one's pictures, glTF files and tets
  // are gone, its own listed.
  test::writeText(dir / "glb" / "mine.txt", "kept");
  const CliRun second = run({"play", script.string(), "--out", (dir / "glb").string()});
  ASSERT_EQ(second.code, kExitOk) << second.err;
  EXPECT_NE(second.err.find("note: removed"), std::string::npos) << second.err;
  EXPECT_NE(second.out.find("files in " + (dir / "glb").string() + ": final.obj, metrics.csv\n"),
            std::string::npos)
      << second.out;
  for (const auto& entry : fs::directory_iterator(dir / "glb")) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name == "final.obj" || name == "metrics.csv" || name == "mine.txt" ||
                name == ".galsculpt-writer")
        << name << " left beside the second run's files";
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

const fs::path kClayBall = test::kDefaultSceneFile;

// With the body's residual alone deciding (solver.converge_pieces false), some frames of the cut
// ball leave a piece above the residual tolerance of its own loads while the body's residual is
// within it (docs/physics.md). The run says how many, as the metrics' piece_residual column
// counts them.
TEST(Cli, PlayWarnsOfToolsThatActOnNothing) {
  // A knife above the ball, a brush, a push and an anchor paint in empty space: each said with
  // its frame, its event and how far it passed; a push on the ball says nothing.
  test::TempDir dir;
  const fs::path script = dir / "idle.json";
  test::writeText(script, std::string(R"({"scene": ")") + test::kDefaultSceneFile.string() + R"(",
    "frames": 6, "events": [
    {"frame": 1, "tool": "knife", "duration": 2, "from": [[-0.2, 0.5, 0.02], [0.2, 0.5, 0.02]],
     "to": [[-0.2, 0.4, 0.02], [0.2, 0.4, 0.02]]},
    {"frame": 1, "tool": "push", "center": [0, 0.3, 0], "radius": 0.01, "end": 3},
    {"frame": 2, "tool": "brush", "center": [0, 0.3, 0], "radius": 0.01, "offset": [0, 0.01, 0]},
    {"frame": 2, "tool": "anchor_paint", "center": [0, 0.3, 0], "radius": 0.01},
    {"frame": 4, "tool": "push", "center": [0, 0.1, 0], "radius": 0.03, "end": 5}]})");
  const CliRun r = run({"play", script.string(), "--out", (dir / "o").string()});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  // The metrics count them in the row of the frame computed after they acted (an event of
  // frame k acts before frame k + 1): the knife ending at frame 2, the brush and the paint in
  // row 3, the push in empty space letting go at frame 3 in row 4.
  std::ifstream csv(dir / "o" / "metrics.csv");
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = splitCsv(line);
  const auto column = std::find(header.begin(), header.end(), "idle_tools") - header.begin();
  ASSERT_LT(column, static_cast<long>(header.size())) << line;
  std::vector<std::string> idle;
  while (std::getline(csv, line)) idle.push_back(splitCsv(line)[column]);
  EXPECT_EQ(idle, (std::vector<std::string>{"0", "0", "3", "1", "0", "0"}));
  const std::string w = "warning: " + script.string() + ": ";
  EXPECT_NE(r.err.find(w + "frame 2: knife ($.events[0]) crossed no edge: its blade passed 0.3"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(w + "frame 3: push ($.events[1]) reached no vertex: the nearest is 0.2"),
            std::string::npos);
  EXPECT_NE(r.err.find(w + "frame 2: brush ($.events[2]) reached no vertex"), std::string::npos);
  EXPECT_NE(r.err.find(w + "frame 2: anchor_paint ($.events[3]) anchored no vertex"),
            std::string::npos);
  EXPECT_EQ(r.err.find("$.events[4]"), std::string::npos) << "the push on the ball acted";
  EXPECT_NE(r.out.find("4 warning(s)"), std::string::npos) << r.out;
}

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

}  // namespace
}  // namespace galsculpt
