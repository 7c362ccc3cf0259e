// Opening anything as a sculpting session: a project (.gsproj), a scene (.json), a playback
// script (.json with "events": replayed to its end, then sculpted on), a tet mesh
// (.node/.ele/.msh) or a surface mesh (.obj/.ply/.stl/.gltf/.glb/.off, tetrahedralized with
// TetGen). A bare mesh becomes a scene of its own: clay, no gravity, nothing anchored, the
// multigrid solver; a surface is meshed to about `importTets` tets.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>

#include "engine/scene/scene_mesh.h"
#include "engine/scene/solver_options_json.h"
#include "engine/session/sculpt_session.h"

namespace galsculpt {

struct OpenedSession {
  std::unique_ptr<SculptSession> session;
  std::optional<CameraPose> camera;  // a project's saved view
};

// The scene a bare mesh file is sculpted in (see above).
SceneDescription sceneForMesh(const std::filesystem::path& mesh, int importTets);

// Throws InputError for a file that cannot be opened (naming it and the problem).
// `solver`: solver keys set over the scene's own (withSolverOverrides: --solver-option, --backend).
OpenedSession openSession(const std::filesystem::path& file, const ProgressFn& progress = {},
                          int importTets = 20000, const SolverOverrides& solver = {});

}  // namespace galsculpt
