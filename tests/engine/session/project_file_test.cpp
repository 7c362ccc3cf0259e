#include "engine/session/project_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

#include "engine/scene/scene_mesh.h"
#include "solver/io/input_error.h"
#include "tests/project_bytes.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

// A push brush of radius 3 cm at `center`.
BrushStroke pushAt(const Vec3& center, double strength = BrushStroke{}.strength) {
  BrushStroke push;
  push.kind = Tool::Push;
  push.center = center;
  push.radius = 0.03;
  push.strength = strength;
  return push;
}

struct SculptedBall {
  SceneDescription scene =
      loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json");
  SculptSession session{scene, loadSceneMesh(scene)};
  SculptedBall() {
    session.step();
    session.knife(Vec3(0.05, 0.2, -0.2), Vec3(0.05, 0.2, 0.2), Vec3(0.05, 0.0, -0.2),
                  Vec3(0.05, 0.0, 0.2), {});
    session.beginStroke(pushAt(Vec3(-0.02, 0.098, 0.0), 0.2));
    for (int f = 0; f < 3; ++f) session.step();
    session.endStroke();
    session.paint(Vec3(0.1, 0.0, 0.0), 0.02, -1, false, {});
    session.step();
  }
};

// The bytes a version 2 build wrote for the same session: no solver carry.
std::string asVersion2(const std::string& version3) {
  std::size_t carry = 0;
  std::string s = test::withProjectHeader(version3, [&](nlohmann::json& h) {
    carry = h["solver_carry"].get<std::size_t>();
    h.erase("solver_carry");
  });
  s.erase(s.size() - 8 * carry);
  s.replace(s.find("PROJECT 3\n"), 10, "PROJECT 2\n");
  return s;
}

TEST(ProjectFile, RoundTripRestoresTheSessionExactlyAndItRunsOnIdentically) {
  test::TempDir dir;
  SculptedBall ball;
  const CameraPose pose{Vec3(0.01, 0.02, 0.03), 0.7, 0.4, 0.2};
  writeProject(dir / "ball.gsproj", ball.session, pose);
  EXPECT_TRUE(looksLikeProject(dir / "ball.gsproj"));
  EXPECT_FALSE(
      looksLikeProject(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json"));

  const Project p = readProject(dir / "ball.gsproj");
  ASSERT_TRUE(p.camera.has_value());
  EXPECT_EQ(p.camera->target, pose.target);
  EXPECT_EQ(p.camera->distance, pose.distance);
  EXPECT_EQ(p.mesh.vertices, ball.session.simulation().model().mesh.vertices);
  EXPECT_EQ(p.recording.size(), ball.session.recording().size());
  std::unique_ptr<SculptSession> reopened = sessionFromProject(p, dir / "ball.gsproj");
  const SimulationSnapshot a = ball.session.simulation().snapshot();
  const SimulationSnapshot b = reopened->simulation().snapshot();
  EXPECT_EQ(a.frame, b.frame);
  EXPECT_TRUE(a.x == b.x && a.v == b.v && a.damaged == b.damaged);
  EXPECT_EQ(a.crossing, b.crossing);
  EXPECT_GT(std::count_if(a.crossing.begin(), a.crossing.end(), hasCrossing), 0)
      << "the knife's crossings are saved";
  EXPECT_TRUE(a.plasticStrain == b.plasticStrain);
  ASSERT_FALSE(a.plasticInverse.empty()) << "the clay ball has a plastic state to save";
  for (size_t t = 0; t < a.plasticInverse.size(); ++t)
    ASSERT_TRUE(a.plasticInverse[t] == b.plasticInverse[t]);
  EXPECT_EQ(a.anchorTags, b.anchorTags);
  EXPECT_EQ(reopened->simulation().anchors().heldVertices(),
            ball.session.simulation().anchors().heldVertices());
  for (int f = 0; f < 3; ++f) {
    ball.session.step();
    reopened->step();
  }
  EXPECT_TRUE(ball.session.simulation().state().x == reopened->simulation().state().x)
      << "the reopened project runs on exactly like the original";
  // Its recording still replays from the scene's start.
  reopened->saveRecording(dir / "replay.json");
  const PlaybackScript script = loadPlaybackScript(dir / "replay.json");
  EXPECT_EQ(script.frames, reopened->simulation().frame());
}

// Saved between a stroke's end and the next frame, a project keeps that the brush let go
// (SimState::letGo): the reopened session's next frame starts where the original's does, and
// both run on identically.
TEST(ProjectFile, ABrushLetGoBeforeTheNextFrameIsSaved) {
  test::TempDir dir;
  SculptedBall ball;
  ball.session.beginStroke(pushAt(Vec3(0.02, 0.098, 0.0), 0.2));
  for (int f = 0; f < 2; ++f) ball.session.step();
  ball.session.endStroke();
  ASSERT_TRUE(ball.session.simulation().state().letGo);
  writeProject(dir / "ball.gsproj", ball.session, std::nullopt);
  const Project p = readProject(dir / "ball.gsproj");
  EXPECT_TRUE(p.state.letGo);
  std::unique_ptr<SculptSession> reopened = sessionFromProject(p, dir / "ball.gsproj");
  EXPECT_TRUE(reopened->simulation().snapshot().letGo);
  for (int f = 0; f < 2; ++f) {
    ball.session.step();
    reopened->step();
  }
  EXPECT_FALSE(reopened->simulation().state().letGo) << "taken by the next frame";
  EXPECT_TRUE(ball.session.simulation().state().x == reopened->simulation().state().x);
  // A project without the key (written before it, or with nothing let go) reads false.
  writeProject(dir / "after.gsproj", ball.session, std::nullopt);
  EXPECT_FALSE(readProject(dir / "after.gsproj").state.letGo);
}

// The rigid pendulum's angle and speed are state: saved mid-strike, the reopened Charpy runs on
// as the original does; a state that does not fit the scene's colliders is refused.
TEST(ProjectFile, ARigidPendulumsStateIsSavedAndReopened) {
  test::TempDir dir;
  // The project keeps the scene's text: the pendulum's mass must be written in it.
  nlohmann::json text = nlohmann::json::parse(
      test::readText(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "charpy.json"));
  text["mesh"]["tets"] = 2000;
  text["colliders"][3]["motion"]["mass"] = 22.0;
  text["solver"]["preset"] = "paper";  // quick: the round trip is the question
  test::writeText(dir / "charpy.json", text.dump());
  const SceneDescription scene = loadScene(dir / "charpy.json");
  SculptSession session(scene, loadSceneMesh(scene));
  for (int f = 0; f < 40; ++f) session.step();
  const ColliderState hammer = session.simulation().state().colliders[3];
  ASSERT_LT(hammer.angularVelocity, 6.5) << "saved mid-strike: the bar has slowed the hammer";
  writeProject(dir / "charpy.gsproj", session, std::nullopt);
  const Project p = readProject(dir / "charpy.gsproj");
  ASSERT_EQ(p.state.colliders.size(), 4u);
  EXPECT_EQ(p.state.colliders[3].angle, hammer.angle);
  EXPECT_EQ(p.state.colliders[3].angularVelocity, hammer.angularVelocity);
  std::unique_ptr<SculptSession> reopened = sessionFromProject(p, dir / "charpy.gsproj");
  for (int f = 0; f < 3; ++f) {
    session.step();
    reopened->step();
  }
  EXPECT_TRUE(session.simulation().state().x == reopened->simulation().state().x);
  EXPECT_EQ(session.simulation().state().colliders[3].angularVelocity,
            reopened->simulation().state().colliders[3].angularVelocity);

  const std::string good = test::readText(dir / "charpy.gsproj");
  auto errorOf = [&](const std::function<void(nlohmann::json&)>& edit) {
    test::writeText(dir / "bad.gsproj", test::withProjectHeader(good, edit));
    try {
      readProject(dir / "bad.gsproj");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(errorOf([](nlohmann::json& h) {
              h["colliders"].erase(0);
            }).find("$.colliders: holds 3 states; the scene has 4 colliders"),
            std::string::npos);
  EXPECT_NE(errorOf([](nlohmann::json& h) {
              h["colliders"][3]["angle"] = "up";
            }).find("$.colliders[3].angle"),
            std::string::npos);
  EXPECT_NE(errorOf([](nlohmann::json& h) {
              h["colliders"][3]["spin"] = 1;
            }).find("$.colliders[3].spin: unknown key"),
            std::string::npos);
  // Written before pendulums had a state: the colliders start as the scene gives them.
  test::writeText(dir / "old.gsproj",
                  test::withProjectHeader(good, [](nlohmann::json& h) { h.erase("colliders"); }));
  EXPECT_EQ(readProject(dir / "old.gsproj").state.colliders[3].angularVelocity, 6.5);
}

TEST(ProjectFile, MalformedProjectsGetClearErrors) {
  test::TempDir dir;
  SculptedBall ball;
  writeProject(dir / "good.gsproj", ball.session, std::nullopt);
  const std::string good = test::readText(dir / "good.gsproj");
  auto errorOf = [&](const std::string& bytes) {
    test::writeText(dir / "bad.gsproj", bytes);
    try {
      readProject(dir / "bad.gsproj");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  };
  EXPECT_NE(errorOf("hello").find("bad.gsproj:1: not a Galsculpt project"), std::string::npos);
  EXPECT_NE(errorOf(replaced("PROJECT 3", "PROJECT 7")).find("made by a newer Galsculpt"),
            std::string::npos);
  EXPECT_NE(errorOf(good.substr(0, good.size() - 100)).find("truncated"), std::string::npos);
  EXPECT_NE(errorOf(good.substr(0, 40)).find("truncated"), std::string::npos);
  EXPECT_NE(errorOf(good + "x").find("unexpected data after byte"), std::string::npos);
  // The header edited (its length line follows it).
  auto withHeader = [&](const std::function<void(nlohmann::json&)>& edit) {
    return test::withProjectHeader(good, edit);
  };
  EXPECT_NE(errorOf(withHeader([](nlohmann::json& h) {
              h["anchors"][0]["vertices"][0] = 1 << 30;
            })).find("$.anchors[0].vertices: holds 1073741824, not a vertex of the mesh"),
            std::string::npos);
  EXPECT_NE(errorOf(withHeader([](nlohmann::json& h) { h["frxme"] = 1; })).find("$.frxme"),
            std::string::npos);
  EXPECT_NE(errorOf(withHeader([](nlohmann::json& h) {
              h["scene"]["material"]["preset"] = "cheese";
            })).find("$.material.preset"),
            std::string::npos);
  const std::string fewerEdges =
      errorOf(withHeader([](nlohmann::json& h) { h["edges"] = h["edges"].get<int>() - 1; }));
  EXPECT_TRUE(fewerEdges.find("unexpected data") != std::string::npos ||
              fewerEdges.find("blade crossing of edge") != std::string::npos)
      << fewerEdges;
  const SimModel& model = ball.session.simulation().model();
  // Arrays from the end: the solver carry, plastic state (10 doubles a tet), crossings (a float
  // an edge), damage.
  size_t carry = 0;
  test::withProjectHeader(good, [&](nlohmann::json& h) { carry = h["solver_carry"]; });
  const size_t crossingEnd =
      good.size() - 8 * carry - 10 * static_cast<size_t>(model.numTets()) * 8;
  const size_t damageEnd = crossingEnd - 4 * static_cast<size_t>(model.numEdges());
  std::string damaged = good;
  damaged[damageEnd - 1] = 5;
  EXPECT_NE(errorOf(damaged).find("must be 0 or 1"), std::string::npos) << errorOf(damaged);
  // A crossing out of range, and one on an undamaged edge.
  const SimulationSnapshot state = ball.session.simulation().snapshot();
  auto withCrossing = [&](int edge, float value) {
    std::string s = good;
    std::memcpy(&s[damageEnd + 4 * static_cast<size_t>(edge)], &value, sizeof(float));
    return s;
  };
  const int cutEdge =
      static_cast<int>(std::find_if(state.crossing.begin(), state.crossing.end(), hasCrossing) -
                       state.crossing.begin());
  const int intactEdge = static_cast<int>(std::find(state.damaged.begin(), state.damaged.end(), 0) -
                                          state.damaged.begin());
  EXPECT_NE(errorOf(withCrossing(cutEdge, 1.5f)).find("blade crossing of edge"), std::string::npos);
  EXPECT_NE(errorOf(withCrossing(cutEdge, std::nanf(""))).find("blade crossing of edge"),
            std::string::npos);
  EXPECT_NE(errorOf(withCrossing(intactEdge, 0.5f)).find("on an undamaged edge"),
            std::string::npos);
  // A solver carry that is not finite, or longer than the file.
  ASSERT_GT(carry, 0u) << "the sculpted ball keeps a factorization";
  std::string nan = good;
  const double bad = std::nan("");
  std::memcpy(&nan[good.size() - 8], &bad, sizeof(double));
  EXPECT_NE(errorOf(nan).find("solver carry"), std::string::npos) << errorOf(nan);
  EXPECT_NE(errorOf(withHeader([&](nlohmann::json& h) {
              h["solver_carry"] = carry + 1;
            })).find("solver carry needs"),
            std::string::npos);
  // The version is a whole number and nothing else.
  for (const char* version : {"1garbage", "1.9", "", "-2", "2 ", "99999999999"}) {
    EXPECT_NE(errorOf(replaced("PROJECT 3\n", std::string("PROJECT ") + version + "\n"))
                  .find("bad.gsproj:1: the format version is not a whole number"),
              std::string::npos)
        << version;
  }
}

// Version 1 files (before blade crossings were saved) still open: their cuts have no crossings.
TEST(ProjectFile, Version1ProjectsStillOpen) {
  test::TempDir dir;
  SculptedBall ball;
  writeProject(dir / "new.gsproj", ball.session, std::nullopt);
  std::string bytes = asVersion2(test::readText(dir / "new.gsproj"));
  const SimModel& model = ball.session.simulation().model();
  const size_t crossingEnd = bytes.size() - 10 * static_cast<size_t>(model.numTets()) * 8;
  const size_t crossingBytes = 4 * static_cast<size_t>(model.numEdges());
  bytes.erase(crossingEnd - crossingBytes, crossingBytes);
  bytes.replace(bytes.find("PROJECT 2\n"), 10, "PROJECT 1\n");
  test::writeText(dir / "old.gsproj", bytes);
  const Project p = readProject(dir / "old.gsproj");
  EXPECT_EQ(p.state.damaged, ball.session.simulation().state().damaged);
  EXPECT_EQ(p.state.crossing, std::vector<float>(model.numEdges(), kNoCrossing));
  std::unique_ptr<SculptSession> reopened = sessionFromProject(p, dir / "old.gsproj");
  EXPECT_EQ(reopened->simulation().state().x, ball.session.simulation().state().x);
}

// Continuity: what the solver carries from frame to frame beyond the state (the coarsest matrix
// whose factorization the multigrid keeps while its matrix stays close) is saved with it, so
// the session that saved and the reopened one run on to the same bits, frame after frame and
// under the same tools; a version 2 file (no carry) still opens and runs.
TEST(ProjectFile, AReopenedProjectRunsOnToTheSameBitsAsTheSessionThatSavedIt) {
  test::TempDir dir;
  struct Untouched {
    SceneDescription scene =
        loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json");
    SculptSession session{scene, loadSceneMesh(scene)};
  } ball;  // at rest, where the coarsest factorization is kept from frame to frame
  for (int f = 0; f < 10; ++f) ball.session.step();
  writeProject(dir / "ball.gsproj", ball.session, std::nullopt);
  const Project project = readProject(dir / "ball.gsproj");
  EXPECT_FALSE(project.state.solverCarry.empty()) << "the ball at rest keeps its factorization";
  std::unique_ptr<SculptSession> reopened = sessionFromProject(project, dir / "ball.gsproj");
  auto same = [&](const char* when) {
    const SimState& a = ball.session.simulation().state();
    const SimState& b = reopened->simulation().state();
    ASSERT_EQ(ball.session.simulation().frame(), reopened->simulation().frame());
    EXPECT_TRUE(a.x == b.x && a.v == b.v) << when << ", frame " << reopened->simulation().frame();
  };
  for (int f = 0; f < 30; ++f) {
    ball.session.step();
    reopened->step();
    same("untouched");
  }
  BrushStroke pull;
  pull.kind = Tool::Pull;
  pull.center = Vec3(0.0, -0.098, 0.02);
  pull.radius = 0.03;
  pull.strength = 0.2;
  for (SculptSession* s : {&ball.session, reopened.get()}) s->beginStroke(pull);
  for (int f = 0; f < 8; ++f) {
    for (SculptSession* s : {&ball.session, reopened.get()}) {
      s->moveStroke(Vec3(0.0, -0.098 - 0.002 * f, 0.02), Vec3(0.0, -1.0, 0.0));
      s->step();
    }
    same("under a stroke");
  }
  for (SculptSession* s : {&ball.session, reopened.get()}) s->endStroke();
  for (int f = 0; f < 10; ++f) {
    ball.session.step();
    reopened->step();
    same("after the stroke");
  }

  // Saved by a version 2 build: no carry; it opens where it was left and runs.
  test::writeText(dir / "v2.gsproj", asVersion2(test::readText(dir / "ball.gsproj")));
  const Project old = readProject(dir / "v2.gsproj");
  EXPECT_TRUE(old.state.solverCarry.empty());
  EXPECT_EQ(old.state.x, project.state.x);
  std::unique_ptr<SculptSession> oldSession = sessionFromProject(old, dir / "v2.gsproj");
  EXPECT_TRUE(oldSession->step().converged);

  // A carry of another pattern (saved under other damage) is dropped, not misread.
  SimulationSnapshot odd = reopened->simulation().snapshot();
  odd.solverCarry.resize(odd.solverCarry.size() / 2 + 1, 1.0);
  reopened->simulation().restore(odd);
  EXPECT_TRUE(reopened->step().converged);
}

// Saved while a brush is still held: the file records the stroke as ending there (it once wrote
// an end frame no reader accepts).
TEST(ProjectFile, SavingDuringAStrokeWritesAReadableProject) {
  test::TempDir dir;
  SculptedBall ball;
  BrushStroke grab;
  grab.center = Vec3(0.0, 0.1, 0.0);
  grab.radius = 0.02;
  ball.session.beginStroke(grab);
  ball.session.moveStroke(Vec3(0.0, 0.11, 0.0), Vec3::UnitY());
  ball.session.step();
  writeProject(dir / "held.gsproj", ball.session, std::nullopt);
  const Project p = readProject(dir / "held.gsproj");
  ASSERT_FALSE(p.recording.empty());
  EXPECT_EQ(p.recording.back().end, ball.session.simulation().frame());
  ball.session.saveRecording(dir / "held.json");
  EXPECT_EQ(loadPlaybackScript(dir / "held.json").events.back().end,
            ball.session.simulation().frame());
}

// A push under way holds by springs (soft anchors): the project keeps their weights, and a
// weight out of [0, 1] is an error naming its key.
TEST(ProjectFile, APushUnderWayKeepsItsSpringsAndBadWeightsAreRefused) {
  test::TempDir dir;
  SculptedBall ball;
  ball.session.beginStroke(pushAt(Vec3(0.0, 0.1, 0.0)));
  ball.session.step();
  const SimulationSnapshot held = ball.session.simulation().snapshot();
  bool soft = false;
  for (const AnchorConstraint& a : held.anchors) soft = soft || !a.springWeights.empty();
  ASSERT_TRUE(soft) << "the push holds by springs";
  writeProject(dir / "push.gsproj", ball.session, std::nullopt);
  const SimulationSnapshot read = readProject(dir / "push.gsproj").state;
  ASSERT_EQ(read.anchors.size(), held.anchors.size());
  for (size_t i = 0; i < held.anchors.size(); ++i)
    EXPECT_EQ(read.anchors[i].springWeights, held.anchors[i].springWeights) << "anchor " << i;
  const std::string good = test::readText(dir / "push.gsproj");
  int soft_anchor = -1;
  for (size_t i = 0; i < held.anchors.size(); ++i)
    if (!held.anchors[i].springWeights.empty()) soft_anchor = static_cast<int>(i);
  test::writeText(dir / "bad.gsproj", test::withProjectHeader(good, [&](nlohmann::json& h) {
                    h["anchors"][soft_anchor]["spring_weights"][0] = 1.5;
                  }));
  EXPECT_THROW_WITH(readProject(dir / "bad.gsproj"), InputError,
                    "$.anchors[" + std::to_string(soft_anchor) + "].spring_weights: holds 1.5");
}

}  // namespace
}  // namespace galsculpt
