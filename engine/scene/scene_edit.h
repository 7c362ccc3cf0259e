// Scene settings changed in the app (material, fracture, solver): a new scene description made
// from the old one's JSON with those values replaced, validated like a scene file. Mesh paths
// become absolute, so the edited scene can be saved anywhere (beside a recording) and still
// find its mesh.
#pragma once

#include "engine/scene/scene.h"

namespace galsculpt {

struct SceneSettings {
  MaterialDesc material;
  bool fracture = false;
  double fractureThreshold = 0.0;  // Pa; 0: the material's
  SolverOptions solver;
};

SceneSettings sceneSettings(const SceneDescription& scene);

// Throws InputError (naming the JSON path) for a value no scene file may hold.
SceneDescription editScene(const SceneDescription& base, const SceneSettings& settings);

}  // namespace galsculpt
