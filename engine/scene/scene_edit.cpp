#include "engine/scene/scene_edit.h"

#include "engine/scene/solver_options_json.h"

namespace galsculpt {

namespace fs = std::filesystem;

SceneSettings sceneSettings(const SceneDescription& scene) {
  SceneSettings s;
  s.material = scene.material;
  s.fracture = scene.fracture.enabled;
  s.fractureThreshold = scene.fracture.threshold;
  s.solver = scene.solver;
  return s;
}

SceneDescription editScene(const SceneDescription& base, const SceneSettings& s) {
  nlohmann::json j = base.source;
  const fs::path dir = base.file.parent_path();
  if (j.contains("mesh") && j["mesh"].is_object()) {
    nlohmann::json& mesh = j["mesh"];
    for (const char* key : {"file", "import"}) {
      if (!mesh.contains(key) || !mesh[key].is_string()) continue;
      const std::string path = mesh[key].get<std::string>();
      if (path.rfind("cgal:", 0) != 0)
        mesh[key] = fs::absolute(dir / path).lexically_normal().string();
    }
  }
  const MaterialDesc& m = s.material;
  j["material"] = {{"preset", m.preset},
                   {"model", materialModelName(m.model)},
                   {"youngs_modulus", m.youngsModulus},
                   {"poisson_ratio", m.poissonRatio},
                   {"density", m.density},
                   {"yield_stress", m.yieldStress},
                   {"hardening", m.hardening},
                   {"fracture_threshold", m.fractureThreshold},
                   {"compressive_threshold", m.compressiveThreshold},
                   {"fracture_energy", m.fractureEnergy},
                   {"fracture_strain", m.fractureStrain}};
  nlohmann::json fracture = j.contains("fracture") ? j["fracture"] : nlohmann::json::object();
  fracture["enabled"] = s.fracture;
  // The strain criterion takes no stress threshold.
  if (base.fracture.criterion != FractureCriterion::Strain)
    fracture["threshold"] = s.fractureThreshold;
  j["fracture"] = fracture;
  j["solver"] = solverOptionsJson(s.solver);
  return parseScene(j, base.file.parent_path() / (base.file.stem().string() + ".edited.json"));
}

}  // namespace galsculpt
