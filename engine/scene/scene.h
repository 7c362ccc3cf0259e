// Scene files: what to simulate (mesh, material, anchors, colliders, gravity, fracture, solver).
//
// A scene is JSON, documented in docs/scenes.md. Loading validates every value and names the
// JSON path of the first bad one. The description is plain data: the engine turns it into a
// solver model; nothing here runs physics.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/json_reader.h"
#include "solver/fem/colliders.h"
#include "solver/fem/material_types.h"
#include "solver/model/solver_options.h"

namespace galsculpt {

// The paper's shapes, made on demand (engine/scene/scene_mesh.h).
enum class Generator { Sphere, Charpy, Steak };
// "sphere", "charpy", "steak"; generatorFromName: none for another name.
const char* generatorName(Generator g);
std::optional<Generator> generatorFromName(const std::string& name);

// The fewest tets a scene may ask a generated or imported mesh for ($.mesh.tets).
inline constexpr int kMinSceneTets = 100;

struct MeshSource {
  enum class Kind { File, Generate, Import };
  Kind kind = Kind::File;
  std::filesystem::path path;               // File: tet mesh; Import: surface (absolute, resolved)
  Generator generator = Generator::Sphere;  // Generate
  std::string cgalMesh;  // Import from Debian's libcgal-demo data (e.g. "armadillo")
  int tets = 0;          // Generate / Import: target tet count
  double radius = 0.1;   // sphere
  double scale = 1.0;    // applied to the surface before meshing (Import)
  Eigen::Vector3d translate = Eigen::Vector3d::Zero();
};

struct MaterialDesc {
  std::string preset = "rubber";  // clay | rubber | flesh | steel | brittle_steel | ductile_steel
  MaterialModel model = MaterialModel::StableNeoHookean;
  double youngsModulus = 0.0;  // Pa
  double poissonRatio = 0.0;
  double density = 0.0;               // kg/m^3
  double yieldStress = 0.0;           // Pa, 0 = elastic
  double hardening = 0.0;             // Pa (linear isotropic hardening modulus)
  double fractureThreshold = 0.0;     // Pa, the preset's edge stress at break (fracture default)
  double compressiveThreshold = 0.0;  // Pa, crushing (fracture default; 0: never)
  double fractureEnergy = 0.0;        // J/m^2, G_c (fracture default; 0: thresholds as given)
  double fractureStrain = 0.0;        // edge strain at break (fracture default; 0: none)
};

// Default values of a named preset; throws std::invalid_argument for an unknown name.
MaterialDesc materialPreset(const std::string& name);
// Every preset's name, in the order the documentation lists them.
const std::vector<std::string>& materialPresetNames();

struct PathKey {
  double time = 0.0;                                 // s
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // m, from the rest position
};

struct AnchorDesc {
  enum class Shape { Box, Sphere, Vertices };
  Shape shape = Shape::Box;
  Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero();  // Box
  Eigen::Vector3d center = Eigen::Vector3d::Zero();                              // Sphere
  double radius = 0.0;
  std::vector<int> vertices;  // Vertices
  std::vector<PathKey> path;  // empty: fixed; else offsets, linearly interpolated in time
};

// A collider as the scene gives it: the model's own type (solver/fem/colliders.h: shape,
// pose, motion), and what the scene may say that the solver does not model yet.
struct ColliderDesc : Collider {
  double friction = 0.0;  // read and reported as not modelled: contacts are frictionless
};

// What becomes of pieces under debris_fraction (solver/fracture/debris.h).
enum class DebrisRule { Remove, Keep };
// What breaks an edge: its normal stress past `threshold` (the paper), its engineering strain
// past `strain` (ductile tearing), or whichever comes first.
enum class FractureCriterion { Stress, Strain, StressOrStrain };

struct FractureDesc {
  bool enabled = false;
  FractureCriterion criterion = FractureCriterion::Stress;
  double threshold = 0.0;        // Pa, edge normal stress that damages an edge
  double strain = 0.0;           // edge engineering strain that damages an edge
  double kernelRadius = 0.0;     // m, non-local averaging radius (0 = local)
  double thresholdJitter = 0.0;  // relative spread of random thresholds (0 = uniform)
  unsigned seed = 1;
  bool compressionResists = true;          // damaged edges still resist compression
  double crackWidth = kDefaultCrackWidth;  // strain the crack faces may press in (0: hard law)
  int iterations = 1;                      // solves per step while edges keep breaking
  double compressiveThreshold = 0.0;       // Pa, edges crushed beyond it break too (0: never)
  double criticalFraction = 0.0;  // (0, 1]: the most critical breaks first (0: all at once)
  double energy = 0.0;            // J/m^2, fracture energy G_c (0: none, the paper)
  // Parts whose undamaged elements share no face part: the edges still linking them break
  // (solver/fracture/cracked_sections.h; false: stress alone, the paper).
  bool partCrackedSections = true;
  // A piece holding less than this fraction of the body's rest volume is debris (metrics), cut
  // or broken off, fracture enabled or not; the rule says whether it is removed.
  double debrisFraction = 0.01;
  DebrisRule debris = DebrisRule::Keep;
};

// "corotational", "stvk", "stable_neo_hookean".
const char* materialModelName(MaterialModel m);
// "keep", "remove" (fracture.debris); debrisRuleFromName: none for another name.
const char* debrisRuleName(DebrisRule rule);
std::optional<DebrisRule> debrisRuleFromName(const std::string& name);

// The solver's options: solver/model/solver_options.h (one table drives the struct, its
// presets, the scene reader, the command line and the panel).

// Optional measurements written as metrics columns.
struct MeasureDesc {
  // Opening: the change in distance between the mesh vertices nearest two rest points (the
  // Charpy test's crack-mouth opening displacement, CMOD). Empty: not measured.
  std::vector<Eigen::Vector3d> opening;
  // Load: the force magnitude of one collider (index into colliders; -1: not measured), or
  // the elastic force the body exerts on one anchor's vertices (index into anchors; a grip).
  int loadCollider = -1;
  int loadAnchor = -1;
};

// The body's velocity at the start: a translation and a spin about a centre (the centre of
// mass at rest by default). Vertices a scene anchor holds start at rest.
struct InitialVelocityDesc {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // m/s
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // rad/s, about `center`
  std::optional<Eigen::Vector3d> center;              // m
};

struct SceneDescription {
  std::filesystem::path file;
  nlohmann::json source;  // the scene as read (projects store it)
  std::string name;
  MeshSource mesh;
  MaterialDesc material;
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, -9.81, 0.0);
  double timeStep = 1.0 / 60.0;
  int substeps = 1;
  double dampingMass = 0.0;
  double dampingStiffness = 0.0;
  std::vector<AnchorDesc> anchors;
  std::vector<ColliderDesc> colliders;
  FractureDesc fracture;
  SolverOptions solver;
  MeasureDesc measure;
  InitialVelocityDesc initialVelocity;
};

// One anchor object (box / sphere / vertices, optional path), as in a scene's "anchors" list.
AnchorDesc readAnchorDesc(JsonObject o);

// Reads and validates a scene; throws InputError naming file and JSON path.
SceneDescription loadScene(const std::filesystem::path& file);
// A mesh file (by its extension) where a scene or a script is expected: an InputError that says
// how to open it or which scene key takes it, instead of a JSON syntax error.
void refuseMeshAsJson(const std::filesystem::path& file);
// The same for a scene already parsed; `file` names it in errors and anchors relative paths.
SceneDescription parseScene(const nlohmann::json& root, const std::filesystem::path& file);

}  // namespace galsculpt
