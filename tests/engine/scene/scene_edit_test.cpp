#include "engine/scene/scene_edit.h"

#include <gtest/gtest.h>

#include "solver/io/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

TEST(SceneEdit, ReplacesTheSettingsAndKeepsTheMeshReachableFromAnywhere) {
  const SceneDescription base =
      loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json");
  SceneSettings s = sceneSettings(base);
  EXPECT_EQ(s.material.preset, "clay");
  s.material = materialPreset("rubber");
  s.material.youngsModulus = 12345.0;
  s.fracture = true;
  s.fractureThreshold = 5e4;
  s.solver.grid = "30/300/all";
  s.solver.smoother = Smoother::Jacobi;
  const SceneDescription edited = editScene(base, s);
  EXPECT_EQ(edited.material.preset, "rubber");
  EXPECT_EQ(edited.material.youngsModulus, 12345.0);
  EXPECT_TRUE(edited.fracture.enabled);
  EXPECT_EQ(edited.fracture.threshold, 5e4);
  EXPECT_EQ(edited.solver.grid, "30/300/all");
  EXPECT_EQ(edited.solver.smoother, Smoother::Jacobi);
  EXPECT_EQ(edited.anchors.size(), base.anchors.size()) << "the rest of the scene stays";
  EXPECT_EQ(edited.mesh.path, base.mesh.path);
  // Saved elsewhere and read back, the edited scene still finds its mesh.
  test::TempDir dir;
  test::writeText(dir / "moved.json", edited.source.dump());
  const SceneDescription moved = loadScene(dir / "moved.json");
  EXPECT_EQ(moved.mesh.path, base.mesh.path);
  EXPECT_TRUE(fs::exists(moved.mesh.path));
}

// The steak tears by strain: an edit keeps its criterion and writes no stress threshold, which
// that criterion would refuse; the material's fracture strain goes through.
TEST(SceneEdit, AStrainCriterionSceneStaysValid) {
  const SceneDescription base =
      loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "steak.json");
  ASSERT_EQ(base.fracture.criterion, FractureCriterion::Strain);
  SceneSettings s = sceneSettings(base);
  s.material.fractureStrain = 0.4;
  const SceneDescription edited = editScene(base, s);
  EXPECT_EQ(edited.fracture.criterion, FractureCriterion::Strain);
  EXPECT_FALSE(edited.source["fracture"].contains("threshold"));
  EXPECT_DOUBLE_EQ(edited.fracture.strain, 0.5) << "the scene's own strain stays";
  EXPECT_DOUBLE_EQ(edited.material.fractureStrain, 0.4);
}

TEST(SceneEdit, RefusesValuesNoSceneFileMayHold) {
  const SceneDescription base =
      loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json");
  SceneSettings s = sceneSettings(base);
  s.solver.grid = "all/50";
  EXPECT_THROW_WITH(editScene(base, s), InputError, "$.solver.grid");
  s = sceneSettings(base);
  s.material.poissonRatio = 0.5;
  EXPECT_THROW_WITH(editScene(base, s), InputError, "$.material.poisson_ratio");
}

}  // namespace
}  // namespace galsculpt
