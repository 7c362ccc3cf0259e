#include "engine/scene/scene.h"

#include <gtest/gtest.h>

#include "engine/scene/scene_mesh.h"
#include "solver/fem/material_table.h"
#include "solver/io/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

const fs::path kScenes = fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes";

TEST(Scene, EveryShippedSceneValidates) {
  int count = 0;
  for (const char* name : {"default", "hanging_sphere", "human", "armadillo", "steak", "charpy"}) {
    SCOPED_TRACE(name);
    const SceneDescription s = loadScene(kScenes / (std::string(name) + ".json"));
    EXPECT_FALSE(s.name.empty());
    EXPECT_GT(s.material.youngsModulus, 0.0);
    ++count;
  }
  EXPECT_EQ(count, 6);
}

TEST(Scene, HangingSphereHasThePaperParameters) {
  const SceneDescription s = loadScene(kScenes / "hanging_sphere.json");
  EXPECT_EQ(s.mesh.kind, MeshSource::Kind::Generate);
  EXPECT_EQ(s.mesh.generator, Generator::Sphere);
  EXPECT_EQ(s.mesh.tets, 35000);
  EXPECT_DOUBLE_EQ(s.mesh.radius, 0.1);
  EXPECT_DOUBLE_EQ(s.material.youngsModulus, 8000.0);
  EXPECT_DOUBLE_EQ(s.material.poissonRatio, 0.48);
  EXPECT_DOUBLE_EQ(s.material.density, 1000.0);
  EXPECT_EQ(s.material.model, MaterialModel::StableNeoHookean);
  EXPECT_NEAR(s.timeStep, 1.0 / 60.0, 1e-6);
  EXPECT_DOUBLE_EQ(s.dampingMass, 0.1);
  EXPECT_DOUBLE_EQ(s.dampingStiffness, 0.01);
  ASSERT_EQ(s.anchors.size(), 1u);
  EXPECT_DOUBLE_EQ(s.anchors[0].min.y(), 0.08);
  EXPECT_EQ(s.solver.grid, "50/all");
  EXPECT_FALSE(s.fracture.enabled);
}

TEST(Scene, CharpyHasAPendulumAndFracture) {
  const SceneDescription s = loadScene(kScenes / "charpy.json");
  EXPECT_TRUE(s.fracture.enabled);
  EXPECT_EQ(s.material.preset, "brittle_steel");
  EXPECT_DOUBLE_EQ(s.fracture.threshold, 2.0e9);
  EXPECT_DOUBLE_EQ(s.fracture.compressiveThreshold, 4.0e9);
  // The preset's fracture energy on a local stress: a kernel made the peak load mesh-dependent
  // (docs/physics.md, fracture item 7).
  EXPECT_DOUBLE_EQ(s.fracture.energy, 1.2e4);
  EXPECT_EQ(s.fracture.kernelRadius, 0.0);
  ASSERT_EQ(s.colliders.size(), 4u);
  EXPECT_EQ(s.colliders[3].motion.type, ColliderMotion::Type::Pendulum);
  // A test machine's radii (ISO 148-1): anvils rounded 1 mm, the 2 mm striker.
  EXPECT_DOUBLE_EQ(s.colliders[1].cornerRadius, 0.001);
  EXPECT_DOUBLE_EQ(s.colliders[2].cornerRadius, 0.001);
  EXPECT_DOUBLE_EQ(s.colliders[3].cornerRadius, 0.002);
}

// A scene of a 500-tet sphere with the given sections (`"key": value, ...`), written to `name`
// in `dir` and loaded.
SceneDescription sphereSceneWith(const test::TempDir& dir, const std::string& name,
                                 const std::string& sections) {
  test::writeText(dir / name, R"({"mesh": {"generate": "sphere", "tets": 500}, )" + sections + "}");
  return loadScene(dir / name);
}

// Brittle and ductile presets carry their own break stress; a scene may leave it out.
TEST(Scene, FractureThresholdDefaultsToTheMaterialPreset) {
  test::TempDir dir;
  const SceneDescription steel = sphereSceneWith(
      dir, "steel.json", R"("material": {"preset": "steel"}, "fracture": {"enabled": true})");
  const SceneDescription flesh =
      sphereSceneWith(dir, "flesh.json", R"("material": {"preset": "flesh"},
                  "fracture": {"enabled": true, "threshold": 1234}, "solver": {"split_aggregates": false})");
  EXPECT_DOUBLE_EQ(steel.fracture.threshold, materialPreset("steel").fractureThreshold);
  EXPECT_GT(materialPreset("steel").fractureThreshold, 1e8);
  EXPECT_GT(materialPreset("flesh").yieldStress, 0.0) << "ductile: plastic before it breaks";
  EXPECT_LT(materialPreset("flesh").yieldStress, materialPreset("flesh").fractureThreshold);
  EXPECT_DOUBLE_EQ(flesh.fracture.threshold, 1234.0);
  EXPECT_DOUBLE_EQ(steel.fracture.debrisFraction, 0.01) << "debris: under 1 % of the body";
  EXPECT_TRUE(steel.fracture.partCrackedSections) << "sections cracked through part by default";
  const SceneDescription paper = sphereSceneWith(
      dir, "paper.json", R"("fracture": {"enabled": true, "part_cracked_sections": false})");
  EXPECT_FALSE(paper.fracture.partCrackedSections);
  EXPECT_TRUE(steel.solver.splitAggregates);
  EXPECT_FALSE(flesh.solver.splitAggregates);
}

// The two steel presets (docs/scenes.md): one cleavage stress crushing at twice it, the ductile
// one yielding well below its break; the fracture section takes both thresholds from the
// material unless it gives its own; the debris rule is kept unless a scene asks for removal.
TEST(Scene, SteelPresetsCarryTheirBreakingAndCrushingStresses) {
  test::TempDir dir;
  const SceneDescription brittle = sphereSceneWith(
      dir, "b.json", R"("material": {"preset": "brittle_steel"}, "fracture": {"enabled": true})");
  const SceneDescription ductile =
      sphereSceneWith(dir, "d.json", R"("material": {"preset": "ductile_steel"},
                  "fracture": {"enabled": true, "compressive_threshold": 0, "debris": "remove"})");
  EXPECT_EQ(brittle.material.yieldStress, 0.0) << "elastic up to its break";
  EXPECT_DOUBLE_EQ(brittle.fracture.threshold, 2.0e9);
  EXPECT_DOUBLE_EQ(brittle.fracture.compressiveThreshold, 4.0e9);
  EXPECT_DOUBLE_EQ(brittle.fracture.energy, 1.2e4) << "the preset's fracture energy";
  EXPECT_EQ(brittle.fracture.debris, DebrisRule::Keep) << "the default";
  EXPECT_DOUBLE_EQ(ductile.material.yieldStress, 3.55e8);
  EXPECT_LT(3.0 * ductile.material.yieldStress, ductile.fracture.threshold)
      << "the ductile steel yields long before the triaxial stress under a notch breaks it";
  EXPECT_EQ(ductile.fracture.compressiveThreshold, 0.0) << "the scene's own: never crushes";
  EXPECT_EQ(ductile.fracture.debris, DebrisRule::Remove);
  EXPECT_EQ(ductile.fracture.energy, 0.0) << "not measured with one (docs/physics.md)";
  EXPECT_EQ(loadScene(kScenes / "charpy.json").material.preset, "brittle_steel");
  EXPECT_EQ(loadScene(kScenes / "charpy_ductile.json").material.preset, "ductile_steel");
  try {
    sphereSceneWith(dir, "bad.json", R"("fracture": {"debris": "merge"})");
    ADD_FAILURE() << "an unknown debris rule is refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("$.fracture.debris"), std::string::npos) << e.what();
  }
}

// The fracture criterion: stress by default (the paper); strain takes its limit from the scene
// or the material's fracture_strain; stress_or_strain both. A key the criterion does not use is
// refused, not ignored.
TEST(Scene, FractureCriterionTakesItsLimitsAndRefusesUnusedKeys) {
  test::TempDir dir;
  const SceneDescription stress =
      sphereSceneWith(dir, "a.json", R"("fracture": {"enabled": true})");
  EXPECT_EQ(stress.fracture.criterion, FractureCriterion::Stress);
  EXPECT_EQ(stress.fracture.strain, 0.0);
  const SceneDescription strain =
      sphereSceneWith(dir, "b.json", R"("material": {"preset": "flesh", "fracture_strain": 0.7},
                  "fracture": {"criterion": "strain"})");
  EXPECT_EQ(strain.fracture.criterion, FractureCriterion::Strain);
  EXPECT_DOUBLE_EQ(strain.fracture.strain, 0.7) << "the material's";
  EXPECT_EQ(strain.fracture.compressiveThreshold, 0.0) << "no stress, no crushing";
  const SceneDescription both = sphereSceneWith(dir, "c.json", R"("material": {"preset": "flesh"},
                  "fracture": {"criterion": "stress_or_strain", "strain": 0.4})");
  EXPECT_DOUBLE_EQ(both.fracture.strain, 0.4);
  EXPECT_DOUBLE_EQ(both.fracture.threshold, materialPreset("flesh").fractureThreshold);
  EXPECT_THROW_WITH(
      sphereSceneWith(dir, "d.json", R"("fracture": {"criterion": "strain", "threshold": 1e4,
                      "strain": 0.5})"),
      InputError, "$.fracture.threshold: the strain criterion uses no stress");
  EXPECT_THROW_WITH(
      sphereSceneWith(dir, "e.json", R"("fracture": {"criterion": "strain", "strain": 0.5,
                      "kernel_radius": 0.01})"),
      InputError, "$.fracture.kernel_radius: the strain criterion uses no stress");
  EXPECT_THROW_WITH(sphereSceneWith(dir, "f.json", R"("fracture": {"strain": 0.5})"), InputError,
                    "$.fracture.strain: the stress criterion uses no strain");
  EXPECT_THROW_WITH(sphereSceneWith(dir, "g.json", R"("fracture": {"criterion": "strain"})"),
                    InputError, "$.fracture.strain: must be positive when the criterion uses");
  EXPECT_THROW_WITH(sphereSceneWith(dir, "h.json", R"("fracture": {"criterion": "plastic"})"),
                    InputError,
                    "$.fracture.criterion: unknown value 'plastic' (expected one of: stress, "
                    "strain, stress_or_strain)");
}

TEST(Scene, MeasureProbesAreReadAndChecked) {
  const SceneDescription charpy = loadScene(kScenes / "charpy.json");
  ASSERT_EQ(charpy.measure.opening.size(), 2u);
  EXPECT_EQ(charpy.measure.loadCollider, 3);
  test::TempDir dir;
  test::writeText(dir / "bad.json", R"({"mesh": {"generate": "sphere", "tets": 500},
                  "measure": {"load_collider": 2}})");
  try {
    loadScene(dir / "bad.json");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("$.measure.load_collider: names no collider"),
              std::string::npos)
        << e.what();
  }
}

TEST(Scene, DefaultSceneMeshIsCommittedAndLoads) {
  const SceneDescription s = loadScene(kScenes / "default.json");
  const TetMesh mesh = loadSceneMesh(s);
  EXPECT_GT(mesh.numTets(), 1000);
  EXPECT_LT(mesh.numTets(), 20000) << "the committed mesh stays small";
}

struct BadScene {
  std::string json, message;
};

void PrintTo(const BadScene& b, std::ostream* os) {
  *os << "'" << b.message << "'";
}

class SceneErrors : public ::testing::TestWithParam<BadScene> {};

TEST_P(SceneErrors, NameTheJsonPath) {
  test::TempDir dir;
  test::writeText(dir / "s.json", GetParam().json);
  EXPECT_THROW_WITH(loadScene(dir / "s.json"), InputError, GetParam().message);
}

const char* kMesh = R"("mesh": {"generate": "sphere", "tets": 1000})";

INSTANTIATE_TEST_SUITE_P(
    Cases, SceneErrors,
    ::testing::Values(
        BadScene{"{}", "s.json: $.mesh: is required"},
        BadScene{"[1, 2]", "s.json: $: expected an object"},
        BadScene{"{\"mesh\": {}}", "$.mesh: give exactly one of 'file', 'generate' or 'import'"},
        BadScene{"{\"mesh\": {\"generate\": \"cube\", \"tets\": 10}}",
                 "$.mesh.generate: unknown value 'cube'"},
        BadScene{"{\"mesh\": {\"generate\": \"sphere\"}}", "$.mesh.tets: is required"},
        BadScene{std::string("{") + kMesh + R"(, "material": {"poisson_ratio": 0.5}})",
                 "$.material.poisson_ratio: must be at most 0.4999"},
        BadScene{std::string("{") + kMesh + R"(, "material": {"preset": "jelly"}})",
                 "$.material.preset: unknown value 'jelly'"},
        BadScene{std::string("{") + kMesh + R"(, "anchors": [{"box": {"min": [0, 0]}}]})",
                 "$.anchors[0].box.min: expected an array of 3 numbers"},
        BadScene{std::string("{") + kMesh +
                     R"(, "anchors": [{"sphere": {"radius": 1}, "path": [{"t": 1}, {"t": 0.5}]}]})",
                 "$.anchors[0].path[1].t: path times must increase"},
        BadScene{
            std::string("{") + kMesh + R"(, "colliders": [{"type": "box", "center": [0, 0, 0]}]})",
            "$.colliders[0].half_extents: is required for a box"},
        BadScene{std::string("{") + kMesh +
                     R"(, "colliders": [{"type": "box", "half_extents": [1, 0.2, 1],
                     "corner_radius": 0.3}]})",
                 "$.colliders[0].corner_radius: must not exceed the least half extent"},
        BadScene{std::string("{") + kMesh +
                     R"(, "colliders": [{"type": "box", "half_extents": [1, 1, 1],
                     "corner_radius": -0.1}]})",
                 "$.colliders[0].corner_radius: must be at least 0"},
        BadScene{std::string("{") + kMesh +
                     R"(, "colliders": [{"type": "sphere", "radius": 0.1, "center": [0, 0, 0],
                     "motion": {"type": "pendulum", "pivot": [0, 0, 1], "axis": [0, 0, 1],
                     "angular_velocity": 1, "mass": 5}}]})",
                 "$.colliders[0].motion: a rigid pendulum's centre must lie off its axis"},
        BadScene{std::string("{") + kMesh +
                     R"(, "colliders": [{"type": "plane", "motion": {"type": "pendulum",
                     "pivot": [0, 0, 1], "axis": [1, 0, 0], "angular_velocity": 1, "mass": 5}}]})",
                 "$.colliders[0].motion: a plane cannot be a rigid pendulum"},
        BadScene{std::string("{") + kMesh +
                     R"(, "colliders": [{"type": "sphere", "radius": 0.1, "motion": {"type":
                     "pendulum", "axis": [1, 0, 0], "angular_velocity": 1, "mass": -5}}]})",
                 "$.colliders[0].motion.mass: must be at least 0"},
        BadScene{std::string("{") + kMesh + R"(, "solver": {"grid": "1000/50/all"}})",
                 "$.solver.grid: grid levels must be positive and increase"},
        BadScene{std::string("{") + kMesh + R"(, "solver": {"grid": "50"}})",
                 "$.solver.grid: grid '50' must list"},
        BadScene{std::string("{") + kMesh +
                     R"(, "material": {"fracture_threshold": 0}, "fracture": {"enabled": true}})",
                 "$.fracture.threshold: must be positive when fracture is enabled"},
        BadScene{std::string("{") + kMesh + R"(, "fracture": {"debris_fraction": 1.5}})",
                 "$.fracture.debris_fraction: must be at most 1"},
        BadScene{std::string("{") + kMesh + R"(, "fracture": {"part_cracked_sections": 1}})",
                 "$.fracture.part_cracked_sections: expected true or false, got number"},
        BadScene{std::string("{") + kMesh + R"(, "time_step": "fast"})",
                 "$.time_step: expected a number, got string"},
        BadScene{std::string("{") + kMesh + R"(, "gravty": [0, -9.81, 0]})",
                 "$.gravty: unknown key"},
        BadScene{std::string("{") + kMesh + ",\n\"substeps\": 0}",
                 "$.substeps: must be at least 1"},
        BadScene{std::string("{") + kMesh + R"(, "material": {"model": "neo"}})",
                 "$.material.model: unknown value 'neo' (expected one of: corotational, stvk, "
                 "stable_neo_hookean, fixed_corotated, hencky)"},
        BadScene{
            std::string("{") + kMesh + R"(, "solver": {"smoother": "sor"}})",
            "$.solver.smoother: unknown value 'sor' (expected one of: auto, gauss_seidel, jacobi)"},
        BadScene{std::string("{") + kMesh + R"(, "solver": {"backend": "gpu"}})",
                 "$.solver.backend: unknown value 'gpu' (expected one of: auto, cpu, cuda, "
                 "device-like)"},
        BadScene{std::string("{") + kMesh + R"(, "solver": {"energy_guard": "local"}})",
                 "$.solver.energy_guard: unknown value 'local' (expected one of: vertex, body)"},
        BadScene{std::string("{") + kMesh + R"(, "initial_velocity": {"linear": [1, 0]}})",
                 "$.initial_velocity.linear: expected an array of 3 numbers"},
        BadScene{std::string("{") + kMesh + R"(, "initial_velocity": {"spin": [0, 0, 1]}})",
                 "$.initial_velocity.spin: unknown key"},
        BadScene{"{\n\"mesh\": {\n\"file\": \"x.node\",\n}\n}", "s.json:4: JSON syntax error"}));

// Every model of the solver's table (solver/fem/material_table.h) is a scene's by its name.
TEST(Scene, EveryMaterialModelOfTheTableReadsByItsName) {
  test::TempDir dir;
  for (const MaterialInfo& row : kMaterialModels) {
    test::writeText(dir / "s.json",
                    std::string("{") + kMesh + R"(, "material": {"model": ")" + row.name + "\"}}");
    const SceneDescription s = loadScene(dir / "s.json");
    EXPECT_EQ(s.material.model, row.model) << row.name;
    EXPECT_STREQ(materialModelName(row.model), row.name);
  }
}

// Settings are parsed once into enums; their names come back as written.
TEST(Scene, SolverChoicesAreTypedAndKeepTheirNames) {
  test::TempDir dir;
  test::writeText(dir / "s.json", std::string("{") + kMesh + R"(, "material": {"model": "stvk"},
      "solver": {"type": "reference", "smoother": "jacobi", "coarse_solver": "cholesky",
                 "backend": "cpu", "energy_guard": "vertex", "accelerated_start": false}})");
  const SceneDescription s = loadScene(dir / "s.json");
  EXPECT_FALSE(s.solver.acceleratedStart);
  EXPECT_TRUE(solverPreset(SolverPreset::Converged).acceleratedStart);
  EXPECT_FALSE(solverPreset(SolverPreset::Paper).acceleratedStart);
  EXPECT_EQ(s.material.model, MaterialModel::StVK);
  EXPECT_EQ(s.solver.type, SolverType::Reference);
  EXPECT_EQ(s.solver.smoother, Smoother::Jacobi);
  EXPECT_EQ(s.solver.coarseSolver, CoarseSolver::Cholesky);
  EXPECT_EQ(s.solver.backend, BackendRequest::Cpu);
  EXPECT_EQ(s.solver.energyGuard, EnergyGuard::Vertex);
  EXPECT_STREQ(enumName(EnergyGuard::Body), "body");
  EXPECT_EQ(solverPreset(SolverPreset::Converged).energyGuard, EnergyGuard::Body);
  EXPECT_EQ(solverPreset(SolverPreset::Paper).energyGuard, EnergyGuard::Body);
  EXPECT_EQ(solverPreset(SolverPreset::Converged).stiffnessTolerance, 1e-3);
  EXPECT_EQ(solverPreset(SolverPreset::Paper).stiffnessTolerance, 0.0);
  EXPECT_STREQ(materialModelName(s.material.model), "stvk");
  EXPECT_STREQ(enumName(s.solver.type), "reference");
  EXPECT_STREQ(enumName(s.solver.smoother), "jacobi");
  EXPECT_STREQ(enumName(s.solver.coarseSolver), "cholesky");
  EXPECT_STREQ(enumName(s.solver.backend), "cpu");
  EXPECT_EQ(enumFromName<BackendRequest>("cuda"), BackendRequest::Cuda);
  EXPECT_FALSE(enumFromName<BackendRequest>("gpu").has_value());
  EXPECT_EQ(enumFromName<SolverPreset>("paper"), SolverPreset::Paper);
  EXPECT_EQ(enumFromName<SolverPreset>(enumName(SolverPreset::Converged)), SolverPreset::Converged);
  EXPECT_FALSE(enumFromName<SolverPreset>("fast").has_value());
}

TEST(Scene, AnInitialVelocityIsATranslationAndASpin) {
  test::TempDir dir;
  test::writeText(dir / "s.json", std::string("{") + kMesh + R"(, "initial_velocity":
      {"linear": [1, 2, 3], "angular": [0, 0, 5], "center": [0.1, 0, 0]}})");
  const SceneDescription s = loadScene(dir / "s.json");
  EXPECT_EQ(s.initialVelocity.linear, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(s.initialVelocity.angular, Eigen::Vector3d(0, 0, 5));
  ASSERT_TRUE(s.initialVelocity.center.has_value());
  EXPECT_EQ(*s.initialVelocity.center, Eigen::Vector3d(0.1, 0, 0));
  test::writeText(dir / "s.json", std::string("{") + kMesh + "}");
  EXPECT_TRUE(loadScene(dir / "s.json").initialVelocity.linear.isZero());
  EXPECT_FALSE(loadScene(dir / "s.json").initialVelocity.center.has_value());
}

TEST(Scene, MissingMeshFileIsReportedWhenLoading) {
  test::TempDir dir;
  test::writeText(dir / "s.json", R"({"mesh": {"file": "nothing.node"}})");
  const SceneDescription s = loadScene(dir / "s.json");
  EXPECT_THROW_WITH(loadSceneMesh(s), InputError, "s.json: $.mesh.file:");
  EXPECT_THROW_WITH(loadSceneMesh(s), InputError, "nothing.node does not exist");
}

TEST(Scene, MissingCgalDataSaysHowToGetIt) {
  test::TempDir dir;
  setenv("GALSCULPT_CACHE_DIR", dir.path().c_str(), 1);
  const SceneDescription s = loadScene(kScenes / "armadillo.json");
  EXPECT_THROW_WITH(loadSceneMesh(s), InputError, "scripts/fetch-cgal-meshes.sh");
  unsetenv("GALSCULPT_CACHE_DIR");
}

TEST(Scene, GeneratedMeshesAreCached) {
  test::TempDir dir;
  setenv("GALSCULPT_CACHE_DIR", dir.path().c_str(), 1);
  test::writeText(dir / "s.json", R"({"mesh": {"generate": "charpy", "tets": 1500}})");
  const SceneDescription s = loadScene(dir / "s.json");
  int progressLines = 0;
  const TetMesh first = loadSceneMesh(s, [&](const std::string&) { ++progressLines; });
  EXPECT_GT(progressLines, 0);
  int secondLines = 0;
  const TetMesh second = loadSceneMesh(s, [&](const std::string&) { ++secondLines; });
  EXPECT_EQ(secondLines, 0) << "the second load comes from the cache";
  EXPECT_EQ(first.tets, second.tets);
  EXPECT_NEAR(first.numTets(), 1500, 225);
  unsetenv("GALSCULPT_CACHE_DIR");
}

}  // namespace
}  // namespace galsculpt
