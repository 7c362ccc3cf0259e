#include "engine/session/session_loader.h"

#include "engine/meshing/mesh_files.h"
#include "engine/session/project_file.h"
#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

SceneDescription sceneForMesh(const fs::path& mesh, int importTets) {
  const fs::path absolute = fs::absolute(mesh).lexically_normal();
  nlohmann::json source = {{"name", mesh.stem().string()},
                           {"material", {{"preset", "clay"}}},
                           {"gravity", {0.0, 0.0, 0.0}},
                           {"damping", {{"mass", 2.0}, {"stiffness", 0.01}}},
                           {"solver", {{"type", "multigrid"}, {"grid", "50/all"}}}};
  if (isTetMeshFile(absolute))
    source["mesh"] = {{"file", absolute.string()}};
  else
    source["mesh"] = {{"import", absolute.string()}, {"tets", importTets}};
  return parseScene(source, absolute.parent_path() / (mesh.stem().string() + ".scene.json"));
}

OpenedSession openSession(const fs::path& file, const ProgressFn& progress, int importTets,
                          const SolverOverrides& solver) {
  requirePathExists(file);
  OpenedSession opened;
  // By content, or by name: a .gsproj whose magic is broken is a broken project, not an
  // unknown mesh format.
  if (looksLikeProject(file) || file.extension() == ".gsproj") {
    if (progress) progress("reading project " + file.string());
    Project project = readProject(file);
    project.scene = withSolverOverrides(project.scene, solver);
    opened.camera = project.camera;
    opened.session = sessionFromProject(project, file);
    return opened;
  }
  const std::string ext = file.extension().string();
  const nlohmann::json json = ext == ".json" ? parseJsonFile(file) : nlohmann::json();
  if (json.contains("events")) {
    // A playback script: its scene, replayed to the script's end, then sculpted on.
    PlaybackScript script = parsePlaybackScript(json, file);
    script.scene = withSolverOverrides(script.scene, solver);
    const TetMesh mesh = loadSceneMesh(script.scene, progress);
    opened.session = std::make_unique<SculptSession>(script.scene, mesh);
    opened.session->replay(script, [&](int frame, int frames) {
      if (progress && (frame % 10 == 0 || frame == frames))
        progress("replaying " + file.filename().string() + ": frame " + std::to_string(frame) +
                 " of " + std::to_string(frames));
    });
    return opened;
  }
  SceneDescription scene = ext == ".json" ? parseScene(json, file) : sceneForMesh(file, importTets);
  if (ext != ".json" && meshFileKind(file) == MeshFileKind::Unknown)
    throw InputError(file.string() + ": not a project, scene or mesh file this version reads");
  scene = withSolverOverrides(scene, solver);
  const TetMesh mesh = loadSceneMesh(scene, progress);
  if (progress) progress("building the simulation (" + std::to_string(mesh.numTets()) + " tets)");
  opened.session = std::make_unique<SculptSession>(scene, mesh);
  return opened;
}

}  // namespace galsculpt
