#include "app/window/input_script.h"

#include <gtest/gtest.h>

#include "solver/io/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

TEST(InputScript, ReadsEveryKindOfStep) {
  test::TempDir dir;
  test::writeText(dir / "s.json", R"({"realtime": true, "steps": [
    {"wait": 3}, {"move": [0.5, 0.25]}, {"move": [[0.1, 0.2], [0.3, 0.4]]},
    {"press": "left", "shift": true}, {"release": "right"}, {"scroll": -2},
    {"key": "z", "ctrl": true}, {"key": "space"}, {"key": "escape"},
    {"command": "save_project", "argument": "out.gsproj"}]})");
  const std::vector<InputStep> s = loadInputScript(dir / "s.json").steps;
  ASSERT_EQ(s.size(), 10u);
  EXPECT_TRUE(loadInputScript(dir / "s.json").realtime);
  EXPECT_EQ(s[0].kind, InputStep::Kind::Wait);
  EXPECT_EQ(s[0].frames, 3);
  EXPECT_EQ(s[1].points.size(), 1u);
  EXPECT_EQ(s[1].points[0].second, 0.25);
  EXPECT_EQ(s[2].points.size(), 2u);
  EXPECT_EQ(s[3].kind, InputStep::Kind::Press);
  EXPECT_TRUE(s[3].shift);
  EXPECT_EQ(s[4].button, MouseButton::Right);
  EXPECT_EQ(s[5].scroll, -2.0);
  EXPECT_EQ(s[6].key, 'Z');
  EXPECT_TRUE(s[6].ctrl);
  EXPECT_EQ(s[7].key, ' ');
  EXPECT_EQ(s[8].key, kKeyEscape);
  EXPECT_EQ(s[9].command, AppCommand::SaveProject);
  EXPECT_EQ(s[9].argument, "out.gsproj");
}

TEST(InputScript, BadStepsNameTheirPath) {
  test::TempDir dir;
  auto errorOf = [&](const std::string& steps) {
    test::writeText(dir / "s.json", "{\"steps\": [" + steps + "]}");
    try {
      loadInputScript(dir / "s.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(errorOf(R"({"wait": 1}, {"move": [1]})").find("$.steps[1].move"), std::string::npos);
  EXPECT_NE(errorOf(R"({"press": "thumb"})").find("$.steps[0].press"), std::string::npos);
  EXPECT_NE(errorOf(R"({"key": "F12"})").find("$.steps[0].key"), std::string::npos);
  EXPECT_NE(errorOf(R"({"command": "format_disk"})").find("$.steps[0].command"), std::string::npos);
  EXPECT_NE(errorOf(R"({"jump": 1})").find("$.steps[0]"), std::string::npos);
  EXPECT_NE(errorOf(R"({"wait": 1, "colour": 2})").find("colour"), std::string::npos);
  test::writeText(dir / "t.json", "{\"step\": []}");
  EXPECT_THROW_WITH(loadInputScript(dir / "t.json"), InputError, "steps");
}

// The runner takes a step a window frame, holds through its waits, keeps a screenshot until
// what came before it is on the screen, and says when the script is done.
TEST(InputScriptRunner, HoldsThroughWaitsAndScreenshotsUntilShown) {
  test::TempDir dir;
  test::writeText(dir / "s.json", R"({"steps": [
    {"wait": 2}, {"move": [0.5, 0.5]}, {"wait_frames": 1},
    {"command": "screenshot", "argument": "a.png"}]})");
  InputScriptRunner runner;
  EXPECT_FALSE(runner.active());
  runner.load(loadInputScript(dir / "s.json"));
  ASSERT_TRUE(runner.active());
  EXPECT_FALSE(runner.realtime());
  using Kind = InputScriptRunner::Turn::Kind;
  std::vector<Kind> turns;
  const InputStep* acted = nullptr;
  for (int frame = 0; frame < 8; ++frame) {
    const InputScriptRunner::Turn t = runner.next(0, frame < 6);  // input shown from frame 6
    turns.push_back(t.kind);
    if (t.kind == Kind::Act && !acted) acted = t.step;
  }
  // wait 2: taken, then two frames held; the move; wait_frames 1 (window frames when not in
  // real time): taken, one held; the screenshot held until frame 6; then done.
  EXPECT_EQ(turns, (std::vector<Kind>{Kind::Hold, Kind::Hold, Kind::Hold, Kind::Act, Kind::Hold,
                                      Kind::Hold, Kind::Act, Kind::Done}));
  ASSERT_NE(acted, nullptr);
  EXPECT_EQ(acted->kind, InputStep::Kind::Move);
}

// In real time "wait_frames" waits for views of finished frames, however many window frames.
TEST(InputScriptRunner, RealTimeWaitFramesCountsViewsShown) {
  test::TempDir dir;
  test::writeText(dir / "s.json", R"({"realtime": true, "steps": [
    {"wait_frames": 2}, {"key": "space"}]})");
  InputScriptRunner runner;
  runner.load(loadInputScript(dir / "s.json"));
  EXPECT_TRUE(runner.realtime());
  using Kind = InputScriptRunner::Turn::Kind;
  EXPECT_EQ(runner.next(5, false).kind, Kind::Hold);  // taken: wait until 7 views
  for (int k = 0; k < 10; ++k) EXPECT_EQ(runner.next(6, false).kind, Kind::Hold);
  const InputScriptRunner::Turn t = runner.next(7, false);
  ASSERT_EQ(t.kind, Kind::Act);
  EXPECT_EQ(t.step->key, ' ');
  EXPECT_EQ(runner.next(7, false).kind, Kind::Done);
}

}  // namespace
}  // namespace galsculpt
