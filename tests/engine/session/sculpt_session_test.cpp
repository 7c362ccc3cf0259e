#include "engine/session/sculpt_session.h"

#include <gtest/gtest.h>

#include "engine/session/project_file.h"
#include "tests/engine/session/clay_ball.h"

namespace galsculpt {
namespace {

using namespace galsculpt::test;
namespace fs = std::filesystem;

// What `play` leaves of a script: the state at its last frame.
SimulationSnapshot playedToTheEnd(const PlaybackScript& script) {
  Simulation sim(script.scene, clayBall().mesh);
  Playback playback(script, sim);
  while (!playback.finished()) playback.advance();
  return sim.snapshot();
}

TEST(SculptSession, UndoAndRedoReturnTheExactStates) {
  SculptSession s(clayBall().scene, clayBall().mesh);
  for (int f = 0; f < 3; ++f) s.step();
  const SimulationSnapshot a = s.simulation().snapshot();
  s.beginAction("knife");
  cutThrough(s, 0.02);
  for (int f = 0; f < 3; ++f) s.step();
  const SimulationSnapshot b = s.simulation().snapshot();
  ASSERT_GT(std::count_if(b.crossing.begin(), b.crossing.end(), hasCrossing), 0)
      << "the knife recorded where it crossed";
  const size_t recordedB = s.recording().size();
  s.beginAction("push");
  s.beginStroke(brushAt(Tool::Push, Vec3(-0.02, 0.098, 0.0), Vec3::UnitY(), 0.03, 0.2));
  for (int f = 0; f < 4; ++f) s.step();
  s.endStroke();
  s.step();
  const SimulationSnapshot c = s.simulation().snapshot();
  const size_t recordedC = s.recording().size();
  EXPECT_EQ(s.undoLabel(), "push");

  ASSERT_TRUE(s.undo());
  expectSameState(s.simulation().snapshot(), b);
  EXPECT_EQ(s.recording().size(), recordedB) << "the undone stroke leaves the recording";
  ASSERT_TRUE(s.undo());
  expectSameState(s.simulation().snapshot(), a);
  EXPECT_TRUE(s.recording().empty());
  EXPECT_FALSE(s.undo());
  ASSERT_TRUE(s.redo());
  expectSameState(s.simulation().snapshot(), b);
  ASSERT_TRUE(s.redo());
  expectSameState(s.simulation().snapshot(), c);
  EXPECT_EQ(s.recording().size(), recordedC);
  EXPECT_FALSE(s.redo());
  // The surface follows an undo of damage.
  s.undo();
  s.undo();
  EXPECT_EQ(
      s.simulation().surface().mesh.numFaces(),
      SculptSession(clayBall().scene, clayBall().mesh).simulation().surface().mesh.numFaces());
  // A new action drops the redo steps.
  s.beginAction("paint");
  s.paint(Vec3(0.1, 0.0, 0.0), 0.02, -1, false, {});
  EXPECT_FALSE(s.canRedo());
  // Reset is undoable too.
  s.step();
  const SimulationSnapshot beforeReset = s.simulation().snapshot();
  s.reset();
  EXPECT_EQ(s.simulation().frame(), 0);
  EXPECT_TRUE(s.recording().empty());
  ASSERT_TRUE(s.undo());
  expectSameState(s.simulation().snapshot(), beforeReset);
}

TEST(SculptSession, HistoryStaysWithinItsMemoryBudget) {
  SculptSession s(clayBall().scene, clayBall().mesh);
  const size_t one = s.simulation().snapshot().bytes();
  s.setHistoryBudget(3 * one + one / 2);
  for (int i = 0; i < 8; ++i) {
    s.beginAction("paint");
    s.paint(Vec3(0.1, 0.0, 0.0), 0.01 + 0.002 * i, -1, false, {});
  }
  EXPECT_LE(s.historyBytes(), 3 * one + one / 2 + one / 10);
  int undone = 0;
  while (s.undo()) ++undone;
  EXPECT_GE(undone, 2);
  EXPECT_LT(undone, 8) << "the oldest steps were forgotten";
}

// Everything a user does is recorded; the script replays to the same state, bit for bit.
TEST(SculptSession, ARecordedSessionReplaysExactly) {
  test::TempDir dir;
  SculptSession s(clayBall().scene, clayBall().mesh);
  const Symmetry mirrorX{0, 0.0};
  s.setCamera({Vec3(0, 0, 0), 0.5, 0.3, 0.2});
  s.step();
  s.beginAction("knife");
  s.knife(Vec3(0.05, 0.2, -0.2), Vec3(0.05, 0.2, 0.2), Vec3(0.05, 0.05, -0.2),
          Vec3(0.05, 0.05, 0.2), mirrorX);
  s.step();
  s.beginAction("grab");
  BrushStroke grab = brushAt(Tool::Grab, Vec3(0.0, 0.1, 0.0), Vec3::UnitY(), 0.03);
  s.beginStroke(grab);
  for (int f = 1; f <= 4; ++f) {
    s.moveStroke(grab.center + f * Vec3(0.003, 0.002, 0.0), Vec3::UnitY());
    s.step();
  }
  s.endStroke();
  s.beginAction("inflate");
  BrushStroke inflate = brushAt(Tool::Inflate, Vec3(0.0, 0.0, 0.1), Vec3::UnitZ(), 0.03, 0.2);
  inflate.symmetry = mirrorX;
  s.beginStroke(inflate);
  s.step();
  s.moveStroke(Vec3(0.02, 0.0, 0.098), Vec3::UnitZ());
  s.step();
  s.endStroke();
  s.beginAction("undone pinch");
  s.beginStroke(brushAt(Tool::Pinch, Vec3(0.0, 0.0, -0.1), -Vec3::UnitZ(), 0.03, 0.2));
  s.step();
  s.undo();
  s.beginAction("paint");
  s.paint(Vec3(0.1, 0.0, 0.0), 0.02, -1, false, {});
  s.paint(Vec3(0.1, 0.0, 0.0), 0.01, -1, true, {});
  s.setCamera({Vec3(0, 0.01, 0), 0.4, 0.5, 0.1});
  for (int f = 0; f < 3; ++f) s.step();
  s.saveRecording(dir / "session.json");

  const PlaybackScript script = loadPlaybackScript(dir / "session.json");
  EXPECT_EQ(script.frames, s.simulation().frame());
  Simulation replay(script.scene, clayBall().mesh);
  Playback playback(script, replay);
  while (!playback.finished()) playback.advance();
  expectSameState(replay.snapshot(), s.simulation().snapshot());
  ASSERT_TRUE(playback.camera().has_value());
  EXPECT_EQ(playback.camera()->distance, 0.4);
}

// The state a session's saved recording replays to through `play`'s Playback.
SimulationSnapshot replayOf(const SculptSession& session, const fs::path& file) {
  session.saveRecording(file);
  return playedToTheEnd(loadPlaybackScript(file));
}

// A script's events given to the session (the Python module's apply) act from the next frame as
// the script would and are recorded, so that the saved recording replays to the same state,
// also after an undo.
TEST(SculptSession, AppliedScriptEventsActAsInAScriptAndReplay) {
  test::TempDir dir;
  SculptSession s(clayBall().scene, clayBall().mesh);
  s.step();
  ToolEvent drag =
      parseToolEvent(nlohmann::json::parse(R"({"frame": 1, "tool": "brush", "center": [0, 0.1, 0],
                                "radius": 0.03, "offset": [0, 0.02, 0], "duration": 4})"),
                     "event", "test");
  const std::vector<Vec3> before = s.simulation().state().x;
  const int top = s.simulation().nearestVertex(Vec3(0, 0.1, 0));
  s.apply(drag);
  EXPECT_EQ(s.simulation().state().x, before) << "nothing moves before the next step";
  EXPECT_EQ(s.undoLabel(), "apply");
  ToolEvent knife =
      parseToolEvent(nlohmann::json::parse(R"({"frame": 1, "tool": "knife", "duration": 2,
          "from": [[-0.2, 0.2, 0.02], [0.2, 0.2, 0.02]], "to": [[-0.2, -0.2, 0.02], [0.2, -0.2, 0.02]]})"),
                     "event", "test");
  s.apply(knife);
  for (int f = 0; f < 6; ++f) s.step();
  const SimulationSnapshot after = s.simulation().snapshot();
  EXPECT_GT(std::count(after.damaged.begin(), after.damaged.end(), 1), 0);
  EXPECT_EQ(s.recording().size(), 2u);
  expectSameState(replayOf(s, dir / "applied.json"), after);
  // Undo returns to before the knife: the knife no longer acts, the drag (applied before it,
  // not begun yet) still does, and the session stays what its recording replays to.
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(s.recording().size(), 1u);
  for (int f = 0; f < 6; ++f) s.step();
  const SimulationSnapshot undone = s.simulation().snapshot();
  EXPECT_EQ(std::count(undone.damaged.begin(), undone.damaged.end(), 1), 0);
  EXPECT_GT(undone.x[top].y() - before[top].y(), 0.002) << "the drag acted";
  expectSameState(replayOf(s, dir / "undone.json"), undone);
}

// The session after an undo to the middle of a script brush's drag, and a project saved there
// and reopened, go on as the recording replays: the drag lets go at its end (its release is in
// the state, not in the tool applier an undo or a reopening starts afresh), and a named anchor
// added before is still found by its name. An anchor event is recorded at the frame where it
// acted, whatever frame it was given with.
TEST(SculptSession, ABrushDragUnderWayAtAnUndoOrInAProjectLetsGoAtItsEnd) {
  test::TempDir dir;
  SculptSession s(clayBall().scene, clayBall().mesh);
  const auto event = [](const char* json) {
    return parseToolEvent(nlohmann::json::parse(json), "event", "test");
  };
  s.apply(event(R"({"frame": 0, "tool": "anchor", "name": "side",
                    "anchor": {"sphere": {"center": [0.1, 0, 0], "radius": 0.03}}})"));
  s.apply(event(R"({"frame": 0, "tool": "brush", "center": [0, 0.1, 0], "radius": 0.03,
                    "offset": [0, 0.02, 0], "duration": 4})"));
  for (int f = 0; f < 2; ++f) s.step();
  const std::size_t anchorsDuringTheDrag = s.simulation().state().anchors.size();
  writeProject(dir / "mid.gsproj", s, std::nullopt);
  s.apply(event(R"({"frame": 2, "tool": "knife", "from": [[-0.2, 0.2, 0.02], [0.2, 0.2, 0.02]],
                    "to": [[-0.2, -0.2, 0.02], [0.2, -0.2, 0.02]]})"));
  s.step();
  ASSERT_TRUE(s.undo());  // back to frame 2, the drag half done
  ASSERT_EQ(s.simulation().frame(), 2);
  const auto goOn = [&](SculptSession& session) {
    for (int f = 0; f < 3; ++f) session.step();
    session.apply(event(R"({"frame": 0, "tool": "anchor", "action": "remove", "name": "side"})"));
    for (int f = 0; f < 2; ++f) session.step();
  };
  goOn(s);
  EXPECT_LT(s.simulation().state().anchors.size(), anchorsDuringTheDrag - 1)
      << "the drag let go and the named anchor was removed";
  ASSERT_EQ(s.simulation().frame(), 7);
  {
    SCOPED_TRACE("the recording replayed");
    expectSameState(replayOf(s, dir / "undone.json"), s.simulation().snapshot());
  }
  // Reopened at frame 2 and given the same later event, the project ends in the same state.
  std::unique_ptr<SculptSession> reopened =
      sessionFromProject(readProject(dir / "mid.gsproj"), dir / "mid.gsproj");
  ASSERT_EQ(reopened->simulation().frame(), 2);
  goOn(*reopened);
  SCOPED_TRACE("the project reopened");
  expectSameState(reopened->simulation().snapshot(), s.simulation().snapshot());
}

// A script replayed into a session (opening it in the app) reaches the state `play` reaches,
// keeps its events - hand-written anchor events too - and saves them back replayable.
TEST(SculptSession, AReplayedScriptContinuesAndSavesBackExactly) {
  test::TempDir dir;
  test::writeText(dir / "s.json", "{\"scene\": \"" +
                                      (kAssets / "scenes" / "default.json").string() +
                                      R"(", "frames": 6, "events": [
      {"frame": 1, "tool": "anchor", "name": "side", "anchor": {"sphere": {"center": [0.1, 0, 0], "radius": 0.03}}},
      {"frame": 2, "tool": "knife", "from": [[0.03, 0.3, -0.3], [0.03, 0.3, 0.3]],
       "to": [[0.03, -0.3, -0.3], [0.03, -0.3, 0.3]]},
      {"frame": 4, "tool": "anchor", "action": "remove", "name": "side"}]})");
  const PlaybackScript script = loadPlaybackScript(dir / "s.json");
  SculptSession s(script.scene, clayBall().mesh);
  int reported = 0;
  s.replay(script, [&](int, int) { ++reported; });
  EXPECT_EQ(reported, 6);
  expectSameState(s.simulation().snapshot(), playedToTheEnd(script));
  // Sculpt on, save, replay the saved recording from scratch.
  s.beginAction("paint");
  s.paint(Vec3(-0.1, 0.0, 0.0), 0.02, -1, false, {});
  s.step();
  expectSameState(replayOf(s, dir / "continued.json"), s.simulation().snapshot());
}

// A script whose grab and knife reach past its last frame, opened as a session and sculpted on:
// the grab keeps moving and the knife keeps cutting as its recording replays them (they stopped
// acting at the script's end while the saved recording replayed them to their ends).
TEST(SculptSession, StrokesReachingPastAScriptsEndActOnAsItsRecordingReplays) {
  test::TempDir dir;
  test::writeText(dir / "s.json", "{\"scene\": \"" +
                                      (kAssets / "scenes" / "default.json").string() +
                                      R"(", "frames": 6, "events": [
      {"frame": 2, "tool": "grab", "center": [0, -0.1, 0.02], "radius": 0.03, "end": 16,
       "moves": [{"frame": 4, "center": [0, -0.11, 0.02]}, {"frame": 9, "center": [0, -0.12, 0.02]},
                 {"frame": 14, "center": [0, -0.13, 0.02]}]},
      {"frame": 5, "tool": "knife", "duration": 5, "from": [[0.03, 0.3, -0.3], [0.03, 0.3, 0.3]],
       "to": [[0.03, -0.3, -0.3], [0.03, -0.3, 0.3]]}]})");
  const PlaybackScript script = loadPlaybackScript(dir / "s.json");
  SculptSession s(script.scene, clayBall().mesh);
  s.replay(script);
  for (int f = 0; f < 14; ++f) s.step();
  EXPECT_EQ(s.simulation().frame(), 20);
  expectSameState(replayOf(s, dir / "continued.json"), s.simulation().snapshot());
}

}  // namespace
}  // namespace galsculpt

namespace galsculpt {
namespace {

// A cut made after the last frame (the user cuts, then saves without playing on) is in the
// saved state and at the recording's last frame: `play`, and a replay into a session, must
// apply it too (the app's recording replayed without the final cut before).
TEST(SculptSession, ACutAfterTheLastFrameReplays) {
  test::TempDir dir;
  SculptSession s(clayBall().scene, clayBall().mesh);
  for (int f = 0; f < 3; ++f) s.step();
  s.beginAction("knife");
  ASSERT_GT(s.knife(Vec3(0.03, 0.3, -0.3), Vec3(0.03, 0.3, 0.3), Vec3(0.03, -0.3, -0.3),
                    Vec3(0.03, -0.3, 0.3), {}),
            0);
  s.saveRecording(dir / "session.json");
  const PlaybackScript script = loadPlaybackScript(dir / "session.json");
  ASSERT_EQ(script.frames, 3);
  expectSameState(playedToTheEnd(script), s.simulation().snapshot());
  SculptSession reopened(script.scene, clayBall().mesh);
  reopened.replay(script);
  expectSameState(reopened.simulation().snapshot(), s.simulation().snapshot());
}

}  // namespace
}  // namespace galsculpt
