#include "engine/session/session_loader.h"

#include <gtest/gtest.h>

#include "engine/session/project_file.h"
#include "solver/io/input_error.h"
#include "solver/io/tetgen_io.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

const fs::path kAssets = fs::path(GALSCULPT_SOURCE_DIR) / "assets";

TEST(SessionLoader, OpensScenesScriptsProjectsAndMeshes) {
  test::TempDir dir;
  const OpenedSession scene = openSession(kAssets / "scenes" / "default.json");
  ASSERT_TRUE(scene.session);
  EXPECT_EQ(scene.session->simulation().frame(), 0);
  EXPECT_FALSE(scene.camera.has_value());

  // A playback script is replayed to its end.
  test::writeText(dir / "cut.json",
                  "{\"scene\": \"" + (kAssets / "scenes" / "default.json").string() +
                      "\", \"frames\": 4, \"events\": [{\"frame\": 1, \"tool\": \"knife\", "
                      "\"from\": [[-0.2, 0.2, 0.02], [0.2, 0.2, 0.02]], "
                      "\"to\": [[-0.2, -0.2, 0.02], [0.2, -0.2, 0.02]]}]}");
  const OpenedSession script = openSession(dir / "cut.json");
  EXPECT_EQ(script.session->simulation().frame(), 4);
  EXPECT_EQ(script.session->recording().size(), 1u);

  // A project opens where it was saved, with its camera.
  const CameraPose pose{Vec3(0.1, 0, 0), 0.5, 0.2, 0.1};
  writeProject(dir / "p.gsproj", *script.session, pose);
  const OpenedSession project = openSession(dir / "p.gsproj");
  EXPECT_EQ(project.session->simulation().frame(), 4);
  ASSERT_TRUE(project.camera.has_value());
  EXPECT_EQ(project.camera->distance, 0.5);

  // A bare tet mesh: clay, no gravity, nothing anchored.
  writeTetGen(dir / "bar", test::gridBar(3, 2, 2, 0.1));
  const OpenedSession mesh = openSession(dir / "bar.node");
  EXPECT_EQ(mesh.session->scene().material.preset, "clay");
  EXPECT_TRUE(mesh.session->scene().gravity.isZero(0.0));
  EXPECT_TRUE(mesh.session->scene().anchors.empty());
  EXPECT_EQ(mesh.session->simulation().model().numTets(), test::gridBar(3, 2, 2, 0.1).numTets());
}

// Solver keys given on opening (--solver-option, --backend) hold for a scene, a script and a
// project alike, and a project saved afterwards keeps them.
TEST(SessionLoader, SolverOverridesHoldForEveryKindOfFile) {
  test::TempDir dir;
  const SolverOverrides overrides = {{"newton_iters", 3}, {"backend", "cpu"}};
  const OpenedSession scene =
      openSession(kAssets / "scenes" / "default.json", {}, 20000, overrides);
  EXPECT_EQ(scene.session->scene().solver.newtonIterations, 3);
  EXPECT_EQ(scene.session->simulation().settings().newtonIterations, 3);
  test::writeText(dir / "s.json", "{\"scene\": \"" +
                                      (kAssets / "scenes" / "default.json").string() +
                                      "\", \"frames\": 2, \"events\": []}");
  const OpenedSession script = openSession(dir / "s.json", {}, 20000, overrides);
  EXPECT_EQ(script.session->scene().solver.newtonIterations, 3);
  EXPECT_EQ(script.session->simulation().frame(), 2);
  writeProject(dir / "p.gsproj", *script.session, std::nullopt);
  const OpenedSession project = openSession(dir / "p.gsproj");
  EXPECT_EQ(project.session->scene().solver.newtonIterations, 3);
  const OpenedSession again = openSession(dir / "p.gsproj", {}, 20000, {{"newton_iters", 5}});
  EXPECT_EQ(again.session->scene().solver.newtonIterations, 5);
  EXPECT_EQ(again.session->simulation().frame(), 2);
  EXPECT_THROW_WITH(openSession(dir / "p.gsproj", {}, 20000, {{"newton_iters", "many"}}),
                    InputError, "solver options newton_iters=\"many\"");
}

TEST(SessionLoader, WhatCannotBeOpenedIsNamed) {
  test::TempDir dir;
  EXPECT_THROW_WITH(openSession(dir / "missing.json"), InputError, "missing.json: no such file");
  test::writeText(dir / "notes.txt", "hello");
  EXPECT_THROW_WITH(openSession(dir / "notes.txt"), InputError, "notes.txt: not a project");
  test::writeText(dir / "broken.gsproj", "GALSCULPT PROJECX 2\n");
  EXPECT_THROW_WITH(openSession(dir / "broken.gsproj"), InputError,
                    "broken.gsproj:1: not a Galsculpt project");
}

}  // namespace
}  // namespace galsculpt
