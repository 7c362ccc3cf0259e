// The application under Xvfb: the real window, driven by synthetic input through the same
// handlers as the mouse and keys (app/window/input_script.h). Each test starts `galsculpt open` on
// the default clay ball, applies a tool, lets the app save the project when it closes and checks
// the effect on the mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include <signal.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "engine/scene/scene_mesh.h"
#include "engine/session/playback.h"
#include "engine/session/project_file.h"
#include "engine/surface/surface_io.h"
#include "solver/mesh/surface_checks.h"
#include "solver/model/sim_model.h"
#include "tests/test_util.h"

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

const fs::path kDefaultScene =
    fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json";

struct UiRun {
  int exitCode = -1;
  std::string log;
  Project project;
  fs::path recording;
};

// Runs the app with `steps` (the "steps" list of an input script) and reads what it saved.
UiRun runApp(const test::TempDir& dir, const std::string& steps,
             const fs::path& scene = kDefaultScene, bool realtime = false, bool paused = true) {
  test::writeText(dir / "steps.json", std::string("{\"realtime\": ") +
                                          (realtime ? "true" : "false") + ", \"steps\": [" + steps +
                                          "]}");
  const fs::path log = dir / "log.txt";
  const std::string command = "GALSCULPT_RECOVERY_DIR='" + (dir / "recovery").string() +
                              "' xvfb-run -a -s '-screen 0 1280x800x24' '" +
                              std::string(GALSCULPT_BINARY) + "' open '" + scene.string() + "' " +
                              (paused ? "--paused " : "") +
                              "--no-recovery --autosave 0 --size 1280x800 --input-script '" +
                              (dir / "steps.json").string() + "' --save-project '" +
                              (dir / "out.gsproj").string() + "' --save-recording '" +
                              (dir / "recording.json").string() + "' > '" + log.string() + "' 2>&1";
  UiRun run;
  const int status = std::system(command.c_str());
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.log = test::readText(log);
  if (fs::exists(dir / "out.gsproj")) run.project = readProject(dir / "out.gsproj");
  run.recording = dir / "recording.json";
  return run;
}

// The rest positions of the ball, and which vertices moved by more than `at` least.
double largestMotion(const Project& p) {
  double m = 0.0;
  for (size_t v = 0; v < p.mesh.vertices.size(); ++v)
    m = std::max(m, (p.state.x[v] - p.mesh.vertices[v]).norm());
  return m;
}

int pieces(const Project& p) {
  const SimModel model = buildSimModel(p.mesh, MaterialParams{});
  SimState state = initialState(model);
  state.damaged = p.state.damaged;
  return countDamagePieces(model, state);
}

int damagedEdges(const Project& p) {
  int n = 0;
  for (std::uint8_t d : p.state.damaged) n += d;
  return n;
}

const char* kSteps = R"({"command": "step"}, {"wait": 1}, {"command": "step"}, {"wait": 1})";

TEST(AppUi, KnifeStrokeAcrossTheBallCutsItInTwo) {
  test::TempDir dir;
  const UiRun run = runApp(dir, std::string(
                                    R"({"key": "K"}, {"move": [0.2, 0.52]}, {"press": "left"},
      {"move": [[0.3, 0.52], [0.4, 0.52], [0.5, 0.52], [0.6, 0.52], [0.7, 0.52], [0.8, 0.52]]},
      {"release": "left"}, )") + kSteps);
  ASSERT_EQ(run.exitCode, 0) << run.log;
  EXPECT_GT(damagedEdges(run.project), 50);
  EXPECT_EQ(pieces(run.project), 2) << "a stroke across the whole ball cuts through it";
}

TEST(AppUi, GrabDragsTheSurfaceAndThePhysicsFollows) {
  test::TempDir dir;
  const UiRun run =
      runApp(dir, std::string(R"({"key": "G"}, {"move": [0.5, 0.45]}, {"press": "left"},
      {"move": [[0.52, 0.42], [0.56, 0.38]]}, )") +
                      kSteps + R"(, {"release": "left"})");
  ASSERT_EQ(run.exitCode, 0) << run.log;
  EXPECT_GT(largestMotion(run.project), 0.01) << "the grabbed region followed the cursor";
  EXPECT_EQ(run.project.state.frame, 2);
}

// Push, pull, inflate and pinch at the centre of the view: the vertices under the brush move
// in, out, outwards and towards the brush axis.
TEST(AppUi, ShapingBrushesMoveTheSurfaceTheirWay) {
  struct Case {
    const char* key;
    const char* name;
  };
  for (const Case c :
       {Case{"B", "push"}, Case{"U", "pull"}, Case{"I", "inflate"}, Case{"P", "pinch"}}) {
    test::TempDir dir;
    const UiRun run = runApp(dir, std::string(R"({"key": ")") + c.key +
                                      R"("}, {"command": "strength", "argument": "0.6"},
        {"move": [0.5, 0.5]}, {"press": "left"}, )" +
                                      kSteps + R"(, {"release": "left"})");
    ASSERT_EQ(run.exitCode, 0) << c.name << "\n" << run.log;
    const Project& p = run.project;
    // The brush centre: the surface vertex that moved most.
    int center = 0;
    for (size_t v = 0; v < p.mesh.vertices.size(); ++v)
      if ((p.state.x[v] - p.mesh.vertices[v]).norm() >
          (p.state.x[center] - p.mesh.vertices[center]).norm())
        center = static_cast<int>(v);
    const Vec3 at = p.mesh.vertices[center];
    const Vec3 moved = p.state.x[center] - at;
    const Vec3 outward = at.normalized();
    EXPECT_GT(moved.norm(), 0.004) << c.name;
    const std::string name = c.name;
    if (name == "push") {
      EXPECT_LT(moved.dot(outward), -0.8 * moved.norm()) << "push goes in";
    } else if (name == "pull") {
      EXPECT_GT(moved.dot(outward), 0.8 * moved.norm()) << "pull comes out";
    } else if (name == "inflate") {
      EXPECT_GT(moved.dot(outward), 0.0) << "inflate goes out";
    }
    if (name == "pinch") {
      // Vertices around the centre draw towards it (sideways, along the surface).
      double before = 0.0, after = 0.0;
      for (size_t v = 0; v < p.mesh.vertices.size(); ++v) {
        const double d = (p.mesh.vertices[v] - at).norm();
        if (d < 0.005 || d > 0.015) continue;
        before += d;
        after += (p.state.x[v] - p.state.x[center]).norm();
      }
      EXPECT_LT(after, before) << "pinch draws the surface together";
    }
  }
}

TEST(AppUi, AnchorPaintHoldsVerticesAndEraseFreesThem) {
  test::TempDir dir;
  const UiRun painted = runApp(dir, R"({"key": "A"}, {"move": [0.45, 0.5]}, {"press": "left"},
      {"move": [[0.5, 0.5], [0.55, 0.5]]}, {"release": "left"})");
  ASSERT_EQ(painted.exitCode, 0) << painted.log;
  size_t sceneAnchored = 0, paintedAnchored = 0;
  {
    test::TempDir plain;
    const UiRun none = runApp(plain, R"({"wait": 1})");
    for (const AnchorConstraint& a : none.project.state.anchors) sceneAnchored += a.vertices.size();
  }
  for (const AnchorConstraint& a : painted.project.state.anchors)
    paintedAnchored += a.vertices.size();
  EXPECT_GT(paintedAnchored, sceneAnchored + 5) << "the stroke painted anchors";

  test::TempDir dir2;
  const UiRun erased = runApp(dir2, R"({"key": "A"}, {"move": [0.5, 0.5]}, {"press": "left"},
      {"release": "left"}, {"key": "E"}, {"command": "radius", "argument": "0.5"},
      {"press": "left"}, {"release": "left"})");
  ASSERT_EQ(erased.exitCode, 0) << erased.log;
  size_t left = 0;
  for (const AnchorConstraint& a : erased.project.state.anchors) left += a.vertices.size();
  EXPECT_EQ(left, 0u) << "a wide erase frees every anchor, the scene's too";
}

TEST(AppUi, SymmetryMirrorsAnchorPaintAcrossTheXPlane) {
  test::TempDir dir;
  const UiRun run = runApp(dir, R"({"key": "A"}, {"key": "X"}, {"key": "1"},
      {"move": [0.58, 0.5]}, {"press": "left"}, {"release": "left"})");
  ASSERT_EQ(run.exitCode, 0) << run.log;
  int right = 0, left = 0;
  for (const AnchorConstraint& a : run.project.state.anchors) {
    for (int v : a.vertices) {
      const Vec3& p = run.project.mesh.vertices[v];
      if (p.y() < -0.07) continue;  // the scene's anchor at the bottom
      (p.x() > 0.0 ? right : left) += 1;
    }
  }
  EXPECT_GT(right, 2);
  EXPECT_GT(left, 2) << "the mirrored dab anchors the other side";
}

TEST(AppUi, CtrlZUndoesAStrokeExactly) {
  test::TempDir dir;
  const UiRun run =
      runApp(dir, std::string(R"({"key": "K"}, {"move": [0.2, 0.52]}, {"press": "left"},
      {"move": [[0.5, 0.52], [0.8, 0.52]]}, {"release": "left"}, {"key": "Z", "ctrl": true})"));
  ASSERT_EQ(run.exitCode, 0) << run.log;
  EXPECT_EQ(damagedEdges(run.project), 0) << "the cut is undone";
  test::TempDir dir2;
  const UiRun redo =
      runApp(dir2, std::string(R"({"key": "K"}, {"move": [0.2, 0.52]}, {"press": "left"},
      {"move": [[0.5, 0.52], [0.8, 0.52]]}, {"release": "left"}, {"key": "Z", "ctrl": true},
      {"key": "Z", "ctrl": true, "shift": true})"));
  EXPECT_GT(damagedEdges(redo.project), 50) << "and redone";
}

// Bad files get a clear message and the app keeps working.
TEST(AppUi, BadFilesGetClearErrorsAndTheAppKeepsRunning) {
  test::TempDir dir;
  test::writeText(dir / "bad_scene.json", "{\"mesh\": {\"file\": \"x.node\"}, \"gravity\": 3}");
  test::writeText(dir / "bad.gsproj", "GALSCULPT PROJECT 99\n2\n{}");
  const UiRun run =
      runApp(dir, "{\"command\": \"open\", \"argument\": \"" + (dir / "bad_scene.json").string() +
                      "\"}, {\"wait\": 2}, " + "{\"command\": \"open\", \"argument\": \"" +
                      (dir / "bad.gsproj").string() + "\"}, {\"wait\": 2}, " +
                      R"({"key": "G"}, {"move": [0.5, 0.45]}, {"press": "left"},
      {"move": [0.56, 0.38]}, {"command": "step"}, {"wait": 1}, {"release": "left"})");
  ASSERT_EQ(run.exitCode, 0) << run.log;
  EXPECT_NE(run.log.find("bad_scene.json: $.gravity"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("made by a newer Galsculpt"), std::string::npos) << run.log;
  EXPECT_GT(largestMotion(run.project), 0.005) << "the ball is still there and still sculpts";
}

// What the app recorded replays headless to exactly the state the app saved.
TEST(AppUi, TheAppsRecordingReplaysToTheSavedState) {
  test::TempDir dir;
  const UiRun run = runApp(
      dir, std::string(R"({"key": "G"}, {"move": [0.5, 0.45]}, {"press": "left"},
      {"move": [[0.52, 0.42], [0.56, 0.38]]}, )") +
               kSteps + R"(, {"release": "left"},
      {"key": "K"}, {"move": [0.2, 0.6]}, {"press": "left"}, {"move": [[0.5, 0.62], [0.8, 0.64]]},
      {"release": "left"}, {"key": "B"}, {"move": [0.5, 0.3]}, {"press": "left"},
      {"move": [0.52, 0.32]}, )" +
               kSteps + R"(, {"release": "left"}, )" +
               R"({"press": "right"}, {"move": [0.6, 0.3]}, {"release": "right"}, )" + kSteps);
  ASSERT_EQ(run.exitCode, 0) << run.log;
  const PlaybackScript script = loadPlaybackScript(run.recording);
  Simulation sim(script.scene, loadSceneMesh(script.scene));
  Playback playback(script, sim);
  while (!playback.finished()) playback.advance();
  EXPECT_EQ(sim.frame(), run.project.state.frame);
  double worst = 0.0;
  for (size_t v = 0; v < sim.state().x.size(); ++v)
    worst = std::max(worst, (sim.state().x[v] - run.project.state.x[v]).norm());
  EXPECT_TRUE(sim.state().x == run.project.state.x)
      << "positions replay bit for bit; largest difference " << worst << " m\n"
      << test::readText(run.recording);
  EXPECT_TRUE(sim.state().damaged == run.project.state.damaged);
  ASSERT_TRUE(playback.camera().has_value());
  EXPECT_EQ(playback.camera()->yaw, run.project.camera->yaw) << "the orbit was recorded";
}

// The Scene settings panel: a bad value is refused with its JSON path and the session stays;
// a good one restarts the simulation with it, and the recording brings the edited scene along.
TEST(AppUi, SceneSettingsRestartTheSimulationAndTravelWithTheRecording) {
  test::TempDir dir;
  const UiRun run = runApp(dir, std::string(R"({"command": "preset", "argument": "rubber"},
      {"command": "grid", "argument": "all/50"}, {"key": "G"}, {"move": [0.5, 0.45]},
      {"press": "left"}, {"move": [0.56, 0.38]}, )") +
                                    kSteps + R"(, {"release": "left"})");
  ASSERT_EQ(run.exitCode, 0) << run.log;
  EXPECT_NE(run.log.find("$.solver.grid"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("restarted with the new settings"), std::string::npos) << run.log;
  EXPECT_EQ(run.project.scene.material.preset, "rubber");
  ASSERT_TRUE(fs::exists(dir / "recording.scene.json"));
  const PlaybackScript script = loadPlaybackScript(run.recording);
  EXPECT_EQ(script.scene.material.preset, "rubber");
  Simulation sim(script.scene, run.project.mesh);
  Playback playback(script, sim);
  while (!playback.finished()) playback.advance();
  EXPECT_TRUE(sim.state().x == run.project.state.x) << "the edited scene replays exactly";
}

// A playback script opens in the window: replayed to its end, then sculpted on; a bad one is
// reported and the app keeps running.
TEST(AppUi, OpensAPlaybackScriptReplayedAndRefusesABadOne) {
  test::TempDir dir;
  const fs::path cut = fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scripts" / "sphere_cut.json";
  test::writeText(dir / "bad_script.json",
                  "{\"scene\": \"" + kDefaultScene.string() +
                      "\", \"frames\": 5, \"events\": [{\"tool\": \"saw\"}]}");
  const UiRun run = runApp(dir,
                           "{\"command\": \"open\", \"argument\": \"" +
                               (dir / "bad_script.json").string() + "\"}, {\"wait\": 2}",
                           cut);
  ASSERT_EQ(run.exitCode, 0) << run.log;
  EXPECT_NE(run.log.find("bad_script.json: $.events[0].tool"), std::string::npos) << run.log;
  const PlaybackScript script = loadPlaybackScript(cut);
  EXPECT_EQ(run.project.state.frame, script.frames) << "the script ran to its end";
  EXPECT_EQ(pieces(run.project), 2) << "its knife cut the ball in two";
  ASSERT_GE(run.project.recording.size(), script.events.size()) << "its events start the recording";
  EXPECT_TRUE(std::any_of(run.project.recording.begin(),
                          run.project.recording.begin() + script.events.size(),
                          [](const ToolEvent& e) { return e.kind == ToolEvent::Kind::Knife; }))
      << "the script's knife is among them";
}

TEST(AppUi, ExportsFromTheMenuCommandsAreWritten) {
  test::TempDir dir;
  const UiRun run = runApp(dir, R"({"key": "K"}, {"move": [0.2, 0.52]}, {"press": "left"},
      {"move": [[0.5, 0.52], [0.8, 0.52]]}, {"release": "left"}, {"command": "step"}, {"wait": 1},
      {"command": "export", "argument": ")" +
                                    (dir / "cut.glb").string() + R"("},
      {"command": "export_tets", "argument": ")" +
                                    (dir / "cut").string() + R"("})");
  ASSERT_EQ(run.exitCode, 0) << run.log;
  EXPECT_TRUE(fs::exists(dir / "cut.glb"));
  // The export is the closed one, and the window says what it holds.
  EXPECT_NE(run.log.find("piece(s), closed"), std::string::npos) << run.log;
  const TriMesh exported = readSurface(dir / "cut.glb");
  EXPECT_TRUE(analyzeSurface(exported).closedManifold());
  EXPECT_TRUE(findSelfIntersections(exported, 1).empty());
  for (const char* ext : {".node", ".ele", ".face", ".damage", ".vtk"})
    EXPECT_TRUE(fs::exists(dir / (std::string("cut") + ext))) << ext;
}

// A file left in the recovery folder by a crashed run comes back as it was autosaved.
TEST(AppUi, RecoversTheAutosaveOfACrashedRun) {
  test::TempDir dir;
  {
    const SceneDescription scene = loadScene(kDefaultScene);
    SculptSession crashed(scene, loadSceneMesh(scene));
    for (int f = 0; f < 4; ++f) crashed.step();
    crashed.knife(Vec3(0.02, 0.3, -0.3), Vec3(0.02, 0.3, 0.3), Vec3(0.02, -0.3, -0.3),
                  Vec3(0.02, -0.3, 0.3), {});
    crashed.step();
    long dead = 4000000;
    while (kill(static_cast<pid_t>(dead), 0) == 0 || errno == EPERM) ++dead;
    fs::create_directories(dir / "recovery");
    writeProject(dir / "recovery" / ("recovery-" + std::to_string(dead) + ".gsproj"), crashed,
                 std::nullopt);
  }
  const UiRun run = runApp(dir, R"({"command": "recover"}, {"wait": 3})");
  ASSERT_EQ(run.exitCode, 0) << run.log;
  EXPECT_EQ(run.project.state.frame, 5);
  EXPECT_EQ(pieces(run.project), 2);
}

// As a user works: the simulation plays on its worker thread while the window draws and takes
// input; tools wait for the frame in flight and act between frames, so the recording still
// replays to exactly the saved state.
TEST(AppUi, RealtimeSessionWithTheSolverOnItsThreadStillReplaysExactly) {
  test::TempDir dir;
  const UiRun run = runApp(dir, R"({"command": "play"}, {"wait": 10},
      {"press": "right"}, {"move": [0.55, 0.5]}, {"release": "right"}, {"scroll": 1},
      {"key": "G"}, {"move": [0.5, 0.45]}, {"press": "left"}, {"move": [0.53, 0.42]},
      {"wait": 5}, {"move": [0.56, 0.4]}, {"wait": 5}, {"release": "left"},
      {"key": "K"}, {"move": [0.2, 0.6]}, {"press": "left"}, {"move": [0.5, 0.6]},
      {"move": [0.8, 0.6]}, {"release": "left"}, {"wait": 10}, {"command": "pause"})",
                           kDefaultScene, true);
  ASSERT_EQ(run.exitCode, 0) << run.log;
  EXPECT_GT(run.project.state.frame, 0);
  EXPECT_GT(damagedEdges(run.project), 0);
  const PlaybackScript script = loadPlaybackScript(run.recording);
  Simulation sim(script.scene, run.project.mesh);
  Playback playback(script, sim);
  while (!playback.finished()) playback.advance();
  EXPECT_EQ(sim.frame(), run.project.state.frame);
  EXPECT_TRUE(sim.state().x == run.project.state.x) << "positions replay bit for bit";
  EXPECT_TRUE(sim.state().damaged == run.project.state.damaged);
}

// The overlay stays on the screen however long its text: a scene with a long name (and, on a
// machine without a GPU, the backend's long note) once widened it past the window's right edge.
// The viewport's background is a vertical gradient, the same along a row: right of the overlay
// the screenshot must show that background, and the overlay must be there left of it.
TEST(AppUi, TheOverlayStaysOnTheScreen) {
  test::TempDir dir;
  test::writeText(
      dir / "long.json",
      "{\"name\": \"" + std::string(60, 'x') + " a scene whose name runs on and on " +
          std::string(60, 'y') + "\", \"mesh\": {\"file\": \"" +
          (kDefaultScene.parent_path().parent_path() / "meshes" / "sphere_small.node").string() +
          "\"}}");
  const fs::path shot = dir / "shot.png";
  const UiRun run = runApp(dir,
                           R"({"wait": 3}, {"command": "screenshot", "argument": ")" +
                               shot.string() + R"("}, {"wait": 1})",
                           dir / "long.json");
  ASSERT_EQ(run.exitCode, 0) << run.log;
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels = stbi_load(shot.c_str(), &w, &h, &channels, 3);
  ASSERT_NE(pixels, nullptr) << shot;
  auto at = [&](int x, int y) {
    const unsigned char* p = pixels + 3 * (static_cast<size_t>(y) * w + x);
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  auto close = [](const std::array<int, 3>& a, const std::array<int, 3>& b) {
    return std::abs(a[0] - b[0]) <= 3 && std::abs(a[1] - b[1]) <= 3 && std::abs(a[2] - b[2]) <= 3;
  };
  int overlayRows = 0;
  for (int y = 35; y < 60; ++y) {
    const std::array<int, 3> background = at(w / 2 + 40, y);
    EXPECT_TRUE(close(at(w - 3, y), background)) << "row " << y << ": the overlay reaches the edge";
    overlayRows += !close(at(w - 150, y), background);
  }
  EXPECT_GT(overlayRows, 15) << "the overlay is drawn at the top right";
  stbi_image_free(pixels);
}

// --- The real-time path, as a user runs it: the app opens playing, frames run on the worker
// and the window draws what they give; screenshots are the window's own pixels.

struct Shot {
  int w = 0, h = 0;
  std::vector<unsigned char> rgb;
  std::array<int, 3> at(int x, int y) const {
    const unsigned char* p = rgb.data() + 3 * (static_cast<size_t>(y) * w + x);
    return {p[0], p[1], p[2]};
  }
};

Shot loadShot(const fs::path& file) {
  Shot s;
  int channels = 0;
  unsigned char* pixels = stbi_load(file.c_str(), &s.w, &s.h, &channels, 3);
  if (!pixels) return s;
  s.rgb.assign(pixels, pixels + 3 * static_cast<size_t>(s.w) * s.h);
  stbi_image_free(pixels);
  return s;
}

// The viewport between the panels: the empty background is a vertical gradient, the same
// along each row, so a drawn body is what makes a row uneven.
constexpr double kLeft = 0.33, kRight = 0.70, kTop = 0.08, kBottom = 0.95;

double bodyRows(const Shot& s) {
  int busy = 0, rows = 0;
  for (int y = static_cast<int>(kTop * s.h); y < kBottom * s.h; y += 2, ++rows) {
    int lo = 1 << 30, hi = -1;
    for (int x = static_cast<int>(kLeft * s.w); x < kRight * s.w; x += 2) {
      const std::array<int, 3> p = s.at(x, y);
      lo = std::min(lo, p[0] + p[1] + p[2]);
      hi = std::max(hi, p[0] + p[1] + p[2]);
    }
    busy += hi - lo > 45;
  }
  return rows ? static_cast<double>(busy) / rows : 0.0;
}

// The share of the viewport's pixels that differ between two shots.
double changed(const Shot& a, const Shot& b) {
  if (a.w != b.w || a.h != b.h || a.rgb.empty()) return 1.0;
  int n = 0, total = 0;
  for (int y = static_cast<int>(kTop * a.h); y < kBottom * a.h; y += 2) {
    for (int x = static_cast<int>(kLeft * a.w); x < kRight * a.w; x += 2, ++total) {
      const std::array<int, 3> p = a.at(x, y), q = b.at(x, y);
      n += std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]) > 30;
    }
  }
  return static_cast<double>(n) / total;
}

// Pixels of the crack faces' tint (red, kCrackColor shaded) in the viewport.
int crackPixels(const Shot& s) {
  int n = 0;
  for (int y = static_cast<int>(kTop * s.h); y < kBottom * s.h; ++y) {
    for (int x = static_cast<int>(kLeft * s.w); x < kRight * s.w; ++x) {
      const std::array<int, 3> p = s.at(x, y);
      n += p[0] > 60 && p[0] > 2 * p[1] && p[0] > 2 * p[2];
    }
  }
  return n;
}

std::string shot(const fs::path& file) {
  // The cursor off the body first (its brush circle is drawn where it is).
  return R"({"move": [0.5, 0.985]}, {"wait": 2}, {"command": "screenshot", "argument": ")" +
         file.string() + R"("}, {"wait": 1})";
}

// A screenshot while a stroke is held: moving the cursor away would drag the stroke with it.
std::string heldShot(const fs::path& file) {
  return R"({"command": "screenshot", "argument": ")" + file.string() + R"("})";
}

UiRun runLive(const test::TempDir& dir, const std::string& steps,
              const fs::path& scene = kDefaultScene) {
  return runApp(dir, steps, scene, true, false);
}

TEST(AppUiRealtime, TheBodyIsOnTheScreenAfterOpening) {
  for (const fs::path& scene :
       {kDefaultScene, kDefaultScene.parent_path() / "hanging_sphere.json"}) {
    test::TempDir dir;
    const UiRun run = runLive(dir, R"({"wait_frames": 3}, )" + shot(dir / "a.png"), scene);
    ASSERT_EQ(run.exitCode, 0) << run.log;
    const Shot a = loadShot(dir / "a.png");
    ASSERT_FALSE(a.rgb.empty()) << run.log;
    EXPECT_GT(bodyRows(a), 0.3) << scene << ": the body fills the middle of the viewport";
    EXPECT_GE(run.project.state.frame, 3) << "the simulation played";
    EXPECT_NE(run.log.find("window: "), std::string::npos) << run.log;
  }
}

TEST(AppUiRealtime, AGrabDragMovesTheBodysPixelsAndUndoPutsThemBack) {
  test::TempDir dir;
  const UiRun run =
      runLive(dir, R"({"wait_frames": 5}, )" + shot(dir / "a.png") + R"(,
      {"key": "G"}, {"move": [0.5, 0.4]}, {"press": "left"}, {"move": [0.53, 0.33]},
      {"wait_frames": 2}, {"move": [0.58, 0.25]}, {"wait_frames": 6}, )" +
                       heldShot(dir / "b.png") + R"(, {"release": "left"}, {"command": "pause"},
      {"key": "Z", "ctrl": true}, )" +
                       heldShot(dir / "c.png"));
  ASSERT_EQ(run.exitCode, 0) << run.log;
  const Shot a = loadShot(dir / "a.png"), b = loadShot(dir / "b.png"), c = loadShot(dir / "c.png");
  EXPECT_GT(changed(a, b), 0.01) << "the grab moved the ball on the screen";
  // The screenshot comes straight after undo: it waits for the undo, which waited for the
  // frame in flight.
  EXPECT_LT(changed(a, c), 0.2 * changed(a, b)) << "undo put the pixels back";
  // The latency from the grab's input to the first drawn frame that shows it was measured.
  const size_t at = run.log.find("input to screen: median ");
  ASSERT_NE(at, std::string::npos) << run.log;
  double ms = -1.0;
  int samples = 0;
  ASSERT_EQ(std::sscanf(run.log.c_str() + at, "input to screen: median %lf ms over %d samples", &ms,
                        &samples),
            2);
  EXPECT_GT(samples, 0);
  EXPECT_GT(ms, 0.0);
}

TEST(AppUiRealtime, AScreenshotShowsWhatTheStepsBeforeItDid) {
  // The hanging sphere's frames are slow: the view command waits for the frame in flight, and
  // the screenshot straight after it waits too, instead of showing the old view.
  test::TempDir dir;
  const UiRun run = runLive(dir,
                            R"({"wait_frames": 2}, )" + shot(dir / "a.png") + R"(,
      {"command": "view", "argument": "stress"}, )" +
                                heldShot(dir / "b.png"),
                            kDefaultScene.parent_path() / "hanging_sphere.json");
  ASSERT_EQ(run.exitCode, 0) << run.log;
  const Shot a = loadShot(dir / "a.png"), b = loadShot(dir / "b.png");
  EXPECT_GT(changed(a, b), 0.1) << "the stress colours are on the body";
}

TEST(AppUiRealtime, AKnifeStrokeLeavesAVisibleCut) {
  test::TempDir dir;
  const UiRun run = runLive(dir, R"({"wait_frames": 3}, )" + shot(dir / "a.png") + R"(,
      {"key": "K"}, {"move": [0.3, 0.45]}, {"press": "left"},
      {"move": [[0.4, 0.45], [0.5, 0.45], [0.6, 0.45], [0.7, 0.45]]}, {"release": "left"},
      {"wait_frames": 2}, {"key": "G"}, {"move": [0.5, 0.32]}, {"press": "left"},
      {"move": [0.52, 0.25]}, {"wait_frames": 3}, {"move": [0.56, 0.15]}, {"wait_frames": 15}, )" +
                                     heldShot(dir / "b.png") + R"(, {"release": "left"})");
  ASSERT_EQ(run.exitCode, 0) << run.log;
  const Shot a = loadShot(dir / "a.png"), b = loadShot(dir / "b.png");
  EXPECT_GT(damagedEdges(run.project), 50);
  EXPECT_EQ(pieces(run.project), 2);
  EXPECT_GT(changed(a, b), 0.02) << "the cap, cut off and pulled, moved on the screen";
  EXPECT_GT(crackPixels(b), crackPixels(a) + 2000) << "its crack faces are on the screen";
}

}  // namespace
}  // namespace galsculpt

namespace galsculpt {
namespace {

// The shell command that opens the default scene's window under Xvfb driven by DIR/steps.json,
// its output in `log`: `env` goes before it (VAR=value ...), `flags` after `open SCENE`.
std::string windowCommand(const test::TempDir& dir, const fs::path& log, const std::string& env,
                          const std::string& flags) {
  return env + " GALSCULPT_RECOVERY_DIR='" + (dir / "recovery").string() +
         "' xvfb-run -a -s '-screen 0 1280x800x24' '" + std::string(GALSCULPT_BINARY) + "' open '" +
         kDefaultScene.string() + "' --no-recovery --size 1280x800 " + flags + " --input-script '" +
         (dir / "steps.json").string() + "' > '" + log.string() + "' 2>&1";
}

// SIGTERM (a logout, a shutdown, a Ctrl-C in the terminal) closes the window as the close button
// does, but a session with changes is kept in the recovery folder, freshly saved, instead of
// being lost; the process then ends by the signal.
TEST(AppUiRealtime, SigtermClosesTheWindowAndKeepsTheSessionForRecovery) {
  test::TempDir dir;
  test::writeText(dir / "steps.json", R"({"realtime": true, "steps": [
      {"wait_frames": 2}, {"key": "G"}, {"move": [0.5, 0.4]}, {"press": "left"},
      {"move": [0.52, 0.36]}, {"wait_frames": 2}, {"release": "left"}, {"wait": 3000}]})");
  const fs::path recovery = dir / "recovery", log = dir / "log.txt";
  const std::string command = windowCommand(dir, log, "", "--autosave 1");
  FILE* app = popen(command.c_str(), "r");
  ASSERT_NE(app, nullptr);
  // The first autosave names the app's pid (recovery-PID.gsproj) and says the grab made changes.
  pid_t pid = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(90);
  while (pid == 0 && std::chrono::steady_clock::now() < deadline) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(recovery, ec)) {
      const std::string name = e.path().filename().string();
      if (name.rfind("recovery-", 0) == 0 && e.path().extension() == ".gsproj")
        pid = static_cast<pid_t>(std::stol(name.substr(9)));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_NE(pid, 0) << "no autosave: " << test::readText(log);
  const fs::path kept = recovery / ("recovery-" + std::to_string(pid) + ".gsproj");
  const int autosaved = readProject(kept).state.frame;
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const auto beforeSignal = fs::file_time_type::clock::now();
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  const auto signalled = std::chrono::steady_clock::now();
  const int status = pclose(app);
  EXPECT_LT(std::chrono::steady_clock::now() - signalled, std::chrono::seconds(10));
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGTERM)
      << "xvfb-run passes on the app's end by SIGTERM: status " << status;
  const std::string text = test::readText(log);
  EXPECT_NE(text.find("stopped by SIGTERM; the session is kept for recovery: " + kept.string()),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("window: "), std::string::npos) << "it closed as a window does: " << text;
  ASSERT_TRUE(fs::exists(kept));
  // Saved again as it closed (on a loaded machine the simulation may not have finished another
  // frame since the autosave: the file's time tells, not its frame). The kernel stamps files
  // from its coarse clock, up to a tick behind the clock read here: a 20 ms margin.
  EXPECT_GE(fs::last_write_time(kept), beforeSignal - std::chrono::milliseconds(20))
      << "saved again as it closed";
  EXPECT_GE(readProject(kept).state.frame, autosaved);
}

}  // namespace
}  // namespace galsculpt

namespace galsculpt {
namespace {

// On a software rasterizer the window redraws and shows only what changed. What the X server
// shows must still be the whole picture after every draw: a grab across the body, the brush
// circle over a panel's edge, a tool switch, the stress view, a camera orbit, undo.
TEST(AppUiRealtime, WhatTheWindowShowsIsTheWholePictureAfterEveryPartialDraw) {
  test::TempDir dir;
  test::writeText(dir / "steps.json", R"({"realtime": true, "steps": [
      {"wait_frames": 2}, {"key": "G"}, {"move": [0.5, 0.4]}, {"press": "left"},
      {"move": [0.55, 0.35]}, {"wait_frames": 2}, {"move": [0.7, 0.3]}, {"wait_frames": 2},
      {"move": [0.36, 0.5]}, {"wait_frames": 2}, {"release": "left"},
      {"key": "B"}, {"move": [0.5, 0.5]}, {"wait": 3},
      {"command": "view", "argument": "stress"}, {"wait_frames": 2},
      {"move": [0.5, 0.5]}, {"press": "right"}, {"move": [0.6, 0.5]}, {"wait": 2},
      {"release": "right"}, {"wait_frames": 1}, {"key": "Z", "ctrl": true}, {"wait_frames": 2}]})");
  const fs::path log = dir / "log.txt";
  const std::string command = windowCommand(dir, log, "GALSCULPT_CHECK_PRESENT=1", "--autosave 0");
  ASSERT_EQ(std::system(command.c_str()), 0) << test::readText(log);
  const std::string text = test::readText(log);
  int draws = -1;
  long differing = -1;
  const size_t at = text.find("present check: ");
  ASSERT_NE(at, std::string::npos) << "no partial presents here: " << text;
  ASSERT_EQ(std::sscanf(text.c_str() + at, "present check: %d partial draws, %ld pixels", &draws,
                        &differing),
            2)
      << text;
  EXPECT_GT(draws, 20);
  EXPECT_EQ(differing, 0) << "pixels on the screen unlike the picture, over " << draws << " draws";
}

}  // namespace
}  // namespace galsculpt
