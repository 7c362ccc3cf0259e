#include "engine/scene/scene.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <limits>
#include <set>
#include <stdexcept>

#include "engine/scene/json_reader.h"
#include "engine/scene/solver_options_json.h"
#include "solver/fem/material_table.h"
#include "solver/io/input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

// A stress threshold: 0 (none, or the preset's) or a stress a squared comparison can hold. A
// threshold of 1e-300 Pa squares to zero and broke nothing while 1e-100 broke everything.
constexpr double kMinStressThreshold = 1e-6;  // Pa
double stressThreshold(JsonObject& o, const std::string& key, double fallback) {
  const double v = o.number(key, fallback, 0.0, 1e13);
  if (v > 0.0 && v < kMinStressThreshold) {
    char got[32];
    std::snprintf(got, sizeof got, "%g", v);
    o.fail(key, std::string("must be 0 or at least 1e-06 Pa, got ") + got);
  }
  return v;
}

constexpr double kInf = std::numeric_limits<double>::infinity();

const std::vector<std::string> kPresets = {"clay",  "rubber",        "flesh",
                                           "steel", "brittle_steel", "ductile_steel"};
// Enum values and their names, in enum order.
template <typename E>
struct Named {
  E value;
  const char* name;
};
constexpr Named<Generator> kGeneratorNames[] = {
    {Generator::Sphere, "sphere"}, {Generator::Charpy, "charpy"}, {Generator::Steak, "steak"}};
constexpr Named<DebrisRule> kDebrisRuleNames[] = {{DebrisRule::Remove, "remove"},
                                                  {DebrisRule::Keep, "keep"}};
constexpr Named<FractureCriterion> kCriterionNames[] = {
    {FractureCriterion::Stress, "stress"},
    {FractureCriterion::Strain, "strain"},
    {FractureCriterion::StressOrStrain, "stress_or_strain"}};

// The value of a row of a names table: Named<E>, or a material model's row of the solver's table
// (solver/fem/material_table.h).
template <typename E>
E valueOfRow(const Named<E>& n) {
  return n.value;
}
MaterialModel valueOfRow(const MaterialInfo& m) {
  return m.model;
}

template <typename Row, size_t N, typename E>
const char* nameOf(const Row (&names)[N], E value) {
  for (const Row& n : names)
    if (valueOfRow(n) == value) return n.name;
  return "?";
}

template <typename Row, size_t N>
auto valueOf(const Row (&names)[N], const std::string& name)
    -> std::optional<decltype(valueOfRow(names[0]))> {
  for (const Row& n : names)
    if (name == n.name) return valueOfRow(n);
  return std::nullopt;
}

// An optional enum member of a scene object, by name; unknown names fail with the choices.
template <typename Row, size_t N, typename E>
E readEnum(JsonObject& o, const std::string& key, E fallback, const Row (&names)[N]) {
  std::vector<std::string> allowed;
  for (const Row& n : names) allowed.push_back(n.name);
  return valueOf(names, o.string(key, nameOf(names, fallback), allowed)).value_or(fallback);
}

MeshSource readMesh(JsonObject o, const fs::path& sceneDir) {
  MeshSource m;
  const int kinds = o.has("file") + o.has("generate") + o.has("import");
  if (kinds != 1) o.fail("", "give exactly one of 'file', 'generate' or 'import'");
  if (o.has("file")) {
    m.kind = MeshSource::Kind::File;
    const std::string f = o.string("file", "");
    if (f.empty()) o.fail("file", "must not be empty");
    m.path = fs::absolute(sceneDir / f).lexically_normal();
  } else if (o.has("generate")) {
    m.kind = MeshSource::Kind::Generate;
    m.generator = readEnum(o, "generate", Generator::Sphere, kGeneratorNames);
    m.tets = o.integer("tets", 0, kMinSceneTets, 5000000);
    if (m.tets == 0) o.fail("tets", "is required with 'generate'");
    m.radius = o.number("radius", 0.1, 1e-6, 1e3);
  } else {
    m.kind = MeshSource::Kind::Import;
    const std::string source = o.string("import", "");
    if (source.rfind("cgal:", 0) == 0) {
      m.cgalMesh = source.substr(5);
      if (m.cgalMesh.empty()) o.fail("import", "name the CGAL mesh, e.g. cgal:armadillo");
    } else {
      if (source.empty()) o.fail("import", "must not be empty");
      m.path = fs::absolute(sceneDir / source).lexically_normal();
    }
    m.tets = o.integer("tets", 0, kMinSceneTets, 5000000);
    if (m.tets == 0) o.fail("tets", "is required with 'import'");
  }
  m.scale = o.number("scale", 1.0, 1e-12, 1e12);
  m.translate = o.vec3("translate", Eigen::Vector3d::Zero(), kMaxCoordinate);
  o.rejectUnknownKeys();
  return m;
}

MaterialDesc readMaterial(JsonObject o) {
  const std::string preset = o.string("preset", "rubber", kPresets);
  MaterialDesc m = materialPreset(preset);
  m.model = readEnum(o, "model", m.model, kMaterialModels);
  m.youngsModulus = o.number("youngs_modulus", m.youngsModulus, 1e-3, 1e13);
  m.poissonRatio = o.number("poisson_ratio", m.poissonRatio, -0.99, 0.4999);
  m.density = o.number("density", m.density, 1e-3, 1e6);
  m.yieldStress = o.number("yield_stress", m.yieldStress, 0.0, 1e13);
  m.hardening = o.number("hardening", m.hardening, 0.0, 1e13);
  m.fractureThreshold = stressThreshold(o, "fracture_threshold", m.fractureThreshold);
  m.compressiveThreshold = stressThreshold(o, "compressive_threshold", m.compressiveThreshold);
  m.fractureEnergy = o.number("fracture_energy", m.fractureEnergy, 0.0, 1e9);
  m.fractureStrain = o.number("fracture_strain", m.fractureStrain, 0.0, 1e3);
  o.rejectUnknownKeys();
  return m;
}

std::vector<PathKey> readPath(JsonObject& o, const std::string& key) {
  std::vector<PathKey> keys;
  const auto items = o.array(key);
  for (size_t i = 0; i < items.size(); ++i) {
    JsonObject k(items[i], o.childPath(key) + "[" + std::to_string(i) + "]", o.file());
    PathKey p;
    p.time = k.requiredNumber("t", 0.0, 1e9);
    p.offset = k.vec3("offset", Eigen::Vector3d::Zero(), kMaxCoordinate);
    if (!keys.empty() && p.time <= keys.back().time) k.fail("t", "path times must increase");
    k.rejectUnknownKeys();
    keys.push_back(p);
  }
  return keys;
}

}  // namespace

AnchorDesc readAnchorDesc(JsonObject o) {
  AnchorDesc a;
  const int shapes = o.has("box") + o.has("sphere") + o.has("vertices");
  if (shapes != 1) o.fail("", "give exactly one of 'box', 'sphere' or 'vertices'");
  if (o.has("box")) {
    a.shape = AnchorDesc::Shape::Box;
    JsonObject b = o.object("box");
    a.min = b.vec3("min", Eigen::Vector3d::Constant(-kInf));
    a.max = b.vec3("max", Eigen::Vector3d::Constant(kInf));
    if (!b.has("min") && !b.has("max")) b.fail("", "give 'min' and/or 'max'");
    if ((a.min.array() > a.max.array()).any()) b.fail("", "'min' must not exceed 'max'");
    b.rejectUnknownKeys();
  } else if (o.has("sphere")) {
    a.shape = AnchorDesc::Shape::Sphere;
    JsonObject s = o.object("sphere");
    a.center = s.vec3("center", Eigen::Vector3d::Zero(), kMaxCoordinate);
    a.radius = s.requiredNumber("radius", 0.0, kInf);
    s.rejectUnknownKeys();
  } else {
    a.shape = AnchorDesc::Shape::Vertices;
    const auto items = o.array("vertices");
    for (size_t i = 0; i < items.size(); ++i) {
      if (!items[i].is_number_integer() || items[i].get<long long>() < 0 ||
          items[i].get<long long>() > std::numeric_limits<int>::max()) {
        o.fail("vertices", "element " + std::to_string(i) + " is not a vertex index");
      }
      a.vertices.push_back(items[i].get<int>());
    }
    if (a.vertices.empty()) o.fail("vertices", "must not be empty");
  }
  a.path = readPath(o, "path");
  o.rejectUnknownKeys();
  return a;
}

namespace {

ColliderMotion readMotion(JsonObject o) {
  ColliderMotion m;
  const std::string type = o.string("type", "static", {"static", "linear", "pendulum"});
  if (type == "linear") {
    m.type = ColliderMotion::Type::Linear;
    m.velocity = o.vec3("velocity", Eigen::Vector3d::Zero(), kMaxSpeed);
  } else if (type == "pendulum") {
    m.type = ColliderMotion::Type::Pendulum;
    m.pivot = o.vec3("pivot", Eigen::Vector3d::Zero(), kMaxCoordinate);
    m.axis = o.vec3("axis", Eigen::Vector3d::UnitZ());
    if (m.axis.norm() < 1e-12) o.fail("axis", "must not be zero");
    m.axis.normalize();
    m.angularVelocity = o.requiredNumber("angular_velocity", -1e6, 1e6);
    m.mass = o.number("mass", 0.0, 0.0, 1e9);
  }
  o.rejectUnknownKeys();
  return m;
}

ColliderDesc readCollider(JsonObject o) {
  ColliderDesc c;
  const std::string type = o.string("type", "", {"plane", "sphere", "box"});
  if (type.empty()) o.fail("type", "is required (plane, sphere or box)");
  if (type == "plane") {
    c.type = Collider::Type::Plane;
    c.point = o.vec3("point", Eigen::Vector3d::Zero(), kMaxCoordinate);
    c.normal = o.vec3("normal", Eigen::Vector3d::UnitY());
    if (c.normal.norm() < 1e-12) o.fail("normal", "must not be zero");
    c.normal.normalize();
  } else if (type == "sphere") {
    c.type = Collider::Type::Sphere;
    c.center = o.vec3("center", Eigen::Vector3d::Zero(), kMaxCoordinate);
    c.radius = o.requiredNumber("radius", 1e-9, kInf);
  } else {
    c.type = Collider::Type::Box;
    c.center = o.vec3("center", Eigen::Vector3d::Zero(), kMaxCoordinate);
    if (!o.has("half_extents")) o.fail("half_extents", "is required for a box");
    c.halfExtents = o.vec3("half_extents", Eigen::Vector3d::Zero(), kMaxCoordinate);
    if ((c.halfExtents.array() <= 0.0).any()) o.fail("half_extents", "must be positive");
    c.cornerRadius = o.number("corner_radius", 0.0, 0.0, kInf);
    if (c.cornerRadius > c.halfExtents.minCoeff())
      o.fail("corner_radius", "must not exceed the least half extent");
  }
  c.friction = o.number("friction", 0.0, 0.0, 10.0);
  if (o.has("motion")) c.motion = readMotion(o.object("motion"));
  if (c.motion.mass > 0.0) {
    if (c.type == Collider::Type::Plane) o.fail("motion", "a plane cannot be a rigid pendulum");
    const Eigen::Vector3d arm = c.center - c.motion.pivot;
    if ((arm - c.motion.axis * c.motion.axis.dot(arm)).norm() < 1e-9)
      o.fail("motion", "a rigid pendulum's centre must lie off its axis (it has no inertia)");
  }
  o.rejectUnknownKeys();
  return c;
}

FractureDesc readFracture(JsonObject o) {
  FractureDesc f;
  f.enabled = o.boolean("enabled", true);
  f.criterion = readEnum(o, "criterion", f.criterion, kCriterionNames);
  f.threshold = stressThreshold(o, "threshold", 0.0);  // 0: the material preset's
  f.strain = o.number("strain", 0.0, 0.0, 1e3);        // 0: the material preset's
  f.kernelRadius = o.number("kernel_radius", 0.0, 0.0, 1e6);
  f.thresholdJitter = o.number("threshold_jitter", 0.0, 0.0, 0.99);
  f.seed = static_cast<unsigned>(o.integer("seed", 1, 0, std::numeric_limits<int>::max()));
  f.compressionResists = o.boolean("compression_resists", true);
  f.crackWidth = o.number("crack_width", f.crackWidth, 0.0, 0.1);
  f.iterations = o.integer("iterations", 1, 1, 100);
  f.compressiveThreshold = stressThreshold(o, "compressive_threshold", 0.0);
  f.criticalFraction = o.number("critical_fraction", 0.0, 0.0, 1.0);
  f.energy = o.number("energy", 0.0, 0.0, 1e9);
  f.partCrackedSections = o.boolean("part_cracked_sections", f.partCrackedSections);
  f.debrisFraction = o.number("debris_fraction", f.debrisFraction, 0.0, 1.0);
  f.debris = readEnum(o, "debris", f.debris, kDebrisRuleNames);
  o.rejectUnknownKeys();
  return f;
}

}  // namespace

const char* materialModelName(MaterialModel m) {
  return nameOf(kMaterialModels, m);
}
const char* generatorName(Generator g) {
  return nameOf(kGeneratorNames, g);
}
std::optional<Generator> generatorFromName(const std::string& name) {
  return valueOf(kGeneratorNames, name);
}
const char* debrisRuleName(DebrisRule rule) {
  return nameOf(kDebrisRuleNames, rule);
}
std::optional<DebrisRule> debrisRuleFromName(const std::string& name) {
  return valueOf(kDebrisRuleNames, name);
}

const std::vector<std::string>& materialPresetNames() {
  return kPresets;
}

MaterialDesc materialPreset(const std::string& name) {
  MaterialDesc m;
  m.preset = name;
  if (name == "clay") {  // modelling clay: soft, nearly incompressible, yields early
    // Hencky: its flow is part of each Newton iteration's energy, so a converged frame is in
    // equilibrium after the clay has flowed, and its continued logarithm keeps the equations
    // well posed however hard a brush presses, through inversion (docs/physics.md).
    m.model = MaterialModel::Hencky;
    m.youngsModulus = 2.0e5;
    m.poissonRatio = 0.45;
    m.density = 1800.0;
    m.yieldStress = 5.0e3;
    m.hardening = 1.0e4;
    m.fractureThreshold = 3.0e4;
  } else if (name == "rubber") {
    m.model = MaterialModel::StableNeoHookean;
    m.youngsModulus = 1.0e6;
    m.poissonRatio = 0.48;
    m.density = 1100.0;
    m.fractureThreshold = 1.5e6;
  } else if (name == "flesh") {  // soft tissue; plastic before it tears (ductile)
    m.model = MaterialModel::Hencky;
    m.youngsModulus = 5.0e4;
    m.poissonRatio = 0.45;
    m.density = 1060.0;
    m.yieldStress = 2.0e4;
    m.hardening = 1.0e4;
    m.fractureThreshold = 5.0e4;
    m.fractureStrain = 0.5;      // raw muscle tears at tens of per cent
  } else if (name == "steel") {  // structural steel, brittle fracture preset
    m.model = MaterialModel::Corotational;
    m.youngsModulus = 2.0e11;
    m.poissonRatio = 0.3;
    m.density = 7850.0;
    m.fractureThreshold = 4.0e8;
  } else if (name == "brittle_steel" || name == "ductile_steel") {
    // Ferritic steel below and above its transition (docs/scenes.md): both cleave where the
    // normal stress passes the cleavage stress, crush at twice it; the ductile one yields
    // first (S355), and only the hardening and the triaxiality under a notch raise its stress to
    // the break.
    m.model = MaterialModel::Corotational;
    m.youngsModulus = 2.0e11;
    m.poissonRatio = 0.3;
    m.density = 7850.0;
    if (name == "brittle_steel") {
      m.fractureThreshold = 2.0e9;
      // Lower-shelf toughness, K_Ic = sqrt(E G_c) ~ 49 MPa sqrt(m): with a local stress the
      // Charpy bar breaks at the same load on 14k, 28k and 56k tets within 3 % (docs/physics.md).
      m.fractureEnergy = 1.2e4;
    } else {
      m.yieldStress = 3.55e8;
      m.hardening = 1.0e9;
      m.fractureThreshold = 1.2e9;
      // An edge of the notch root torn at 15 % stretch: on the 28k-tet specimen a crack starts
      // there after the bar has bent, and the bar absorbs about 170 J (docs/benchmarks.md).
      m.fractureStrain = 0.15;
    }
    m.compressiveThreshold = 2.0 * m.fractureThreshold;
  } else {
    throw std::invalid_argument("unknown material preset '" + name + "'");
  }
  return m;
}

void refuseMeshAsJson(const fs::path& file) {
  // A surface goes in a scene's mesh.import (meshed with TetGen), a tet mesh in its mesh.file.
  static const std::set<std::string> kTetMeshExtensions{".node", ".ele", ".face",
                                                        ".msh",  ".vtk", ".damage"};
  static const std::set<std::string> kSurfaceExtensions{".obj",  ".ply", ".stl",
                                                        ".gltf", ".glb", ".off"};
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const bool surface = kSurfaceExtensions.count(extension) > 0;
  if (!surface && !kTetMeshExtensions.count(extension)) return;
  // (Appended piece by piece: GCC 12 warns of a restrict overlap, wrongly, in a chain of +.)
  std::string message = "a mesh, not a scene: open it with 'galsculpt open ";
  message.append(file.string());
  message.append("' (sculpted as clay), or name it in a scene's ");
  message.append(surface ? "mesh.import with mesh.tets (docs/quick-start.md)"
                         : "mesh.file (docs/scenes.md)");
  throw InputError(file.string(), 0, message);
}

SceneDescription loadScene(const fs::path& file) {
  refuseMeshAsJson(file);
  return parseScene(parseJsonFile(file), file);
}

SceneDescription parseScene(const nlohmann::json& root, const fs::path& file) {
  JsonObject o(root, "$", file.string());
  SceneDescription s;
  s.source = root;
  s.file = fs::absolute(file);
  const fs::path dir = s.file.parent_path();
  s.name = o.string("name", file.stem().string());
  if (!o.has("mesh")) {
    o.fail("mesh", root.is_object() && root.contains("events")
                       ? "is required (this looks like a playback script: galsculpt play FILE)"
                       : "is required");
  }
  s.mesh = readMesh(o.object("mesh"), dir);
  if (o.has("material"))
    s.material = readMaterial(o.object("material"));
  else
    s.material = materialPreset("rubber");
  s.gravity = o.vec3("gravity", s.gravity, kMaxAcceleration);
  if (o.has("initial_velocity")) {
    JsonObject v = o.object("initial_velocity");
    s.initialVelocity.linear = v.vec3("linear", Eigen::Vector3d::Zero(), kMaxSpeed);
    s.initialVelocity.angular = v.vec3("angular", Eigen::Vector3d::Zero(), kMaxAngularSpeed);
    if (v.has("center"))
      s.initialVelocity.center = v.vec3("center", Eigen::Vector3d::Zero(), kMaxCoordinate);
    v.rejectUnknownKeys();
  }
  s.timeStep = o.number("time_step", s.timeStep, 1e-7, 1.0);
  s.substeps = o.integer("substeps", s.substeps, 1, 1000);
  if (o.has("damping")) {
    JsonObject d = o.object("damping");
    s.dampingMass = d.number("mass", 0.0, 0.0, 1e6);
    s.dampingStiffness = d.number("stiffness", 0.0, 0.0, 1e6);
    d.rejectUnknownKeys();
  }
  const auto anchors = o.array("anchors");
  for (size_t i = 0; i < anchors.size(); ++i) {
    s.anchors.push_back(readAnchorDesc(
        JsonObject(anchors[i], "$.anchors[" + std::to_string(i) + "]", file.string())));
  }
  const auto colliders = o.array("colliders");
  for (size_t i = 0; i < colliders.size(); ++i) {
    s.colliders.push_back(readCollider(
        JsonObject(colliders[i], "$.colliders[" + std::to_string(i) + "]", file.string())));
  }
  if (o.has("fracture")) {
    JsonObject f = o.object("fracture");
    s.fracture = readFracture(f);
    const bool stress = s.fracture.criterion != FractureCriterion::Strain;
    const bool strain = s.fracture.criterion != FractureCriterion::Stress;
    if (stress && s.fracture.enabled && s.fracture.threshold <= 0.0) {
      s.fracture.threshold = s.material.fractureThreshold;
      if (s.fracture.threshold <= 0.0)
        f.fail("threshold",
               "must be positive when fracture is enabled (the material has no default)");
    }
    if (strain && s.fracture.enabled && s.fracture.strain <= 0.0) {
      s.fracture.strain = s.material.fractureStrain;
      if (s.fracture.strain <= 0.0)
        f.fail("strain",
               "must be positive when the criterion uses strain (the material has no "
               "fracture_strain)");
    }
    // A key the criterion would not use is an error, not silently ignored.
    if (!stress)
      for (const char* key : {"threshold", "compressive_threshold", "kernel_radius"})
        if (f.has(key)) f.fail(key, "the strain criterion uses no stress (stress_or_strain does)");
    if (!strain && f.has("strain"))
      f.fail("strain", "the stress criterion uses no strain (stress_or_strain does)");
    if (stress && !f.has("compressive_threshold"))
      s.fracture.compressiveThreshold = s.material.compressiveThreshold;
    if (!f.has("energy")) s.fracture.energy = s.material.fractureEnergy;
  }
  if (o.has("solver")) s.solver = readSolverOptions(o.object("solver"));
  if (o.has("measure")) {
    JsonObject m = o.object("measure");
    if (m.has("opening")) {
      const nlohmann::json& pts = m.raw("opening");
      if (!pts.is_array() || pts.size() != 2)
        m.fail("opening", "must be two points [[x, y, z], [x, y, z]]");
      for (const nlohmann::json& p : pts) {
        if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() ||
            !p[2].is_number())
          m.fail("opening", "must be two points [[x, y, z], [x, y, z]]");
        s.measure.opening.emplace_back(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
      }
    }
    s.measure.loadCollider = m.integer("load_collider", -1, 0, 1000000);
    if (s.measure.loadCollider >= static_cast<int>(s.colliders.size()))
      m.fail("load_collider",
             "names no collider (the scene has " + std::to_string(s.colliders.size()) + ")");
    s.measure.loadAnchor = m.integer("load_anchor", -1, 0, 1000000);
    if (s.measure.loadAnchor >= static_cast<int>(s.anchors.size()))
      m.fail("load_anchor",
             "names no anchor (the scene has " + std::to_string(s.anchors.size()) + ")");
    if (s.measure.loadAnchor >= 0 && s.measure.loadCollider >= 0)
      m.fail("load_anchor", "load_n measures one thing: give load_collider or load_anchor");
    m.rejectUnknownKeys();
  }
  o.rejectUnknownKeys();
  return s;
}

}  // namespace galsculpt
