// `galsculpt open`, `galsculpt render` and `galsculpt scene check`.
#include <cstdlib>
#include <filesystem>

#include "app/cli/cli.h"
#include "app/cli/cli_args.h"
#include "app/cli/command_table.h"
#include "app/render/render_mesh.h"
#include "app/render/snapshot_renderer.h"
#include "app/render/view_content.h"
#include "app/window/camera.h"
#include "app/window/sculpt_window.h"
#include "engine/meshing/mesh_files.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_mesh.h"
#include "engine/session/project_file.h"
#include "engine/session/session_loader.h"
#include "engine/session/simulation.h"
#include "engine/surface/surface_io.h"
#include "solver/io/atomic_file.h"
#include "solver/io/folder_lock.h"
#include "solver/io/input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

bool haveDisplay() {
  const char* x = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (wayland && *wayland);
}

std::string describeMaterial(const MaterialDesc& m) {
  std::ostringstream s;
  s << "material: " << m.preset << " (" << materialModelName(m.model) << ", E " << m.youngsModulus
    << " Pa, nu " << m.poissonRatio << ", " << m.density << " kg/m^3)";
  return s.str();
}

// The surface a scene's tet mesh shows: its boundary, or, with a .damage beside the mesh file
// (an export with its cracks), the surface of the cracked body.
TriMesh sceneSurface(const SceneDescription& scene, const TetMesh& mesh, ViewContent& c) {
  if (!sceneMeshDamage(scene, mesh)) return boundarySurface(mesh);
  Simulation sim(scene, mesh);
  int damaged = 0;
  for (std::uint8_t d : sim.state().damaged) damaged += d;
  c.facts.push_back(std::to_string(damaged) + " damaged edges (" +
                    fs::path(scene.mesh.path).replace_extension(".damage").filename().string() +
                    "), " + std::to_string(sim.pieceStats().pieces) + " piece(s)");
  return sim.surface().mesh;
}

}  // namespace

ViewContent loadViewContent(const fs::path& file, std::ostream& log) {
  ViewContent c;
  c.title = file.filename().string();
  std::string ext = file.extension().string();
  if (looksLikeProject(file) || file.extension() == ".gsproj") {
    const Project project = readProject(file);
    const std::unique_ptr<SculptSession> session = sessionFromProject(project, file);
    c.title = project.scene.name + " (project, frame " + std::to_string(project.state.frame) + ")";
    c.surface = session->simulation().surface().mesh;
    c.facts.push_back(std::to_string(project.mesh.numVertices()) + " vertices, " +
                      std::to_string(project.mesh.numTets()) + " tets");
    return c;
  }
  if (ext == ".json") {
    const SceneDescription scene = loadScene(file);
    const TetMesh mesh =
        loadSceneMesh(scene, [&log](const std::string& line) { log << line << '\n'; });
    c.title = scene.name;
    c.surface = sceneSurface(scene, mesh, c);
    c.facts.push_back(std::to_string(mesh.numVertices()) + " vertices, " +
                      std::to_string(mesh.numTets()) + " tets");
    c.facts.push_back(describeMaterial(scene.material));
    c.facts.push_back(std::string("solver: ") + enumName(scene.solver.type) + " " +
                      scene.solver.grid);
    return c;
  }
  if (meshFileKind(file) == MeshFileKind::Surface) {
    c.surface = readSurface(file);
    c.facts.push_back(std::to_string(c.surface.numVertices()) + " vertices, " +
                      std::to_string(c.surface.numFaces()) + " faces (surface)");
    return c;
  }
  const TetMesh mesh = readTetMesh(file);
  c.surface = sceneSurface(sceneForMesh(file, 20000), mesh, c);
  c.facts.push_back(std::to_string(mesh.numVertices()) + " vertices, " +
                    std::to_string(mesh.numTets()) + " tets");
  return c;
}

std::vector<std::string> renderViewsOffscreen(const ViewContent& content, const fs::path& outDir,
                                              int width, int height) {
  SnapshotRenderer snapshots(width, height);
  snapshots.setMesh(makeRenderMesh(content.surface, kSurfaceColor));
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (ec) throw OutputError("cannot create " + outDir.string() + ": " + ec.message());
  const FolderLock lock(outDir);  // one writer at a time

  OrbitCamera camera;
  camera.frame(boundingBox(content.surface.vertices));
  struct View {
    const char* name;
    double yaw, pitch;
  };
  const OrbitCamera standard;  // its default angles are the perspective view
  const View views[] = {{"perspective", standard.yaw, standard.pitch},
                        {"front", 0.0, 0.0},
                        {"side", 1.5707963, 0.0},
                        {"top", 0.0, 1.55}};
  std::vector<std::string> written;
  for (const View& v : views) {
    camera.yaw = v.yaw;
    camera.pitch = v.pitch;
    const fs::path file = outDir / (std::string("view_") + v.name + ".png");
    snapshots.write(camera, file);
    written.push_back(file.string());
  }
  return written;
}

int renderCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  const CliArgs a(args, commandSpec("render"));
  const auto [w, h] = a.sizeValue("--size", {1280, 800});
  const ViewContent content = loadViewContent(a.positional()[0], err);
  for (const std::string& f : renderViewsOffscreen(content, *a.value("--out"), w, h))
    out << "wrote " << f << '\n';
  return kExitOk;
}

int openCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  const CliArgs a(args, commandSpec("open"));
  applyThreadsOption(a);
  const SolverOverrides solver = solverOverrides(a);
  const fs::path file = a.positional().empty() ? defaultScenePath() : a.positional()[0];
  requirePathExists(file);
  bool headless = a.has("--headless");
  if (!headless && !haveDisplay()) {
    out << "no display found (DISPLAY and WAYLAND_DISPLAY are unset): running headless\n";
    headless = true;
  }
  if (!headless) {
    SculptWindowOptions o;
    o.file = file;
    std::tie(o.width, o.height) = a.sizeValue("--size", {1280, 800});
    if (a.has("--input-script")) o.inputScript = *a.value("--input-script");
    if (a.has("--save-project")) o.saveProjectOnExit = *a.value("--save-project");
    if (a.has("--save-recording")) o.saveRecordingOnExit = *a.value("--save-recording");
    o.autosaveSeconds = a.doubleValue("--autosave", 60.0, 0.0, 1e9);
    o.offerRecovery = !a.has("--no-recovery") && !o.inputScript;
    o.startPlaying = !a.has("--paused");
    o.solver = solver;
    std::string error;
    if (runSculptWindow(o, out, &error)) return kExitOk;
    out << "cannot open a window (" << error << "): running headless\n";
  }
  if (a.has("--input-script"))
    throw UsageError(
        "--input-script drives the window: it cannot run headless (no display, or "
        "--headless)");
  // A playback script is replayed, and a session is saved, as in the window: both need the
  // whole session, not just the mesh.
  const bool script = file.extension() == ".json" && !looksLikeProject(file) &&
                      parseJsonFile(file).contains("events");
  ViewContent content;
  if (script || a.has("--save-project") || a.has("--save-recording")) {
    OpenedSession opened = openSession(
        file, [&err](const std::string& line) { err << line << '\n'; }, 20000, solver);
    const Simulation& sim = opened.session->simulation();
    content.title = opened.session->scene().name + " (frame " + std::to_string(sim.frame()) + ")";
    content.surface = sim.surface().mesh;
    content.facts.push_back(std::to_string(sim.model().numVertices()) + " vertices, " +
                            std::to_string(sim.model().numTets()) + " tets");
    if (auto project = a.value("--save-project")) {
      writeProject(*project, *opened.session, opened.camera);
      out << "wrote project " << *project << '\n';
    }
    if (auto recording = a.value("--save-recording")) {
      opened.session->saveRecording(*recording);
      out << "wrote recording " << *recording << '\n';
    }
  } else {
    content = loadViewContent(file, err);
  }
  const fs::path outDir = a.value("--out").value_or("galsculpt-out");
  const auto [w, h] = a.sizeValue("--size", {1280, 800});
  const auto files = renderViewsOffscreen(content, outDir, w, h);
  out << content.title << ": wrote " << files.size() << " images to "
      << fs::absolute(outDir).lexically_normal().string() << "/\n";
  for (const std::string& f : files) out << "  " << f << '\n';
  return kExitOk;
}

int sceneCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  subcommandOf("scene", args);
  const CliArgs a(std::vector<std::string>(args.begin() + 1, args.end()),
                  commandSpec("scene check"));
  const SceneDescription s = loadScene(a.positional()[0]);
  out << "scene: " << s.name << '\n';
  out << describeMaterial(s.material) << '\n';
  out << "anchors: " << s.anchors.size() << "\ncolliders: " << s.colliders.size() << '\n';
  out << "fracture: " << (s.fracture.enabled ? "on" : "off") << '\n';
  out << "solver: " << enumName(s.solver.type) << " " << s.solver.grid << " ("
      << s.solver.fineSweeps << " sweeps, " << s.solver.coarseIterations << " coarse iterations)\n";
  out << "time_step: " << s.timeStep << " s x " << s.substeps << " substep(s)\n";
  if (a.has("--load-mesh")) {
    const TetMesh mesh = loadSceneMesh(s, [&err](const std::string& line) { err << line << '\n'; });
    checkSceneAnchors(s, mesh);  // what run would refuse, refused here too
    out << "mesh: " << mesh.numVertices() << " vertices, " << mesh.numTets() << " tets\n";
  }
  out << "ok\n";
  return kExitOk;
}

}  // namespace galsculpt
