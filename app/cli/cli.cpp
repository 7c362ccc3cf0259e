#include "app/cli/cli.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "app/cli/cli_args.h"
#include "solver/io/input_error.h"
#include "solver/io/stop_request.h"

namespace galsculpt {

namespace {

const char* kUsage = R"(usage: galsculpt [COMMAND] [ARGS]

With no command, opens the default scene (a window; with no display, a headless run that
writes images and says where).

commands:
  open FILE [--headless] [--out DIR] [--size WxH]
                         open a scene (.json), a tet mesh or a surface mesh
  render FILE --out DIR [--size WxH]
                         render FILE offscreen (EGL) from standard views into PNG files
  run SCENE --frames N [--solver reference] --out DIR [--metrics FILE.csv] [--export-every K]
                         simulate headless: metrics CSV per frame, surfaces as OBJ
  play SCRIPT --out DIR [--export-every K] [--metrics FILE.csv] [--solver reference]
                         run a playback script (scene + timed knife/brush/anchor events)
                         headless; always writes DIR/final.obj
  bench [--scene NAME[,NAME...]] [--quick] [--sweep] [--cracks] [--frames N]
        [--settle N[,N...]] [--json FILE] [--reference-dir DIR]
                         speed against error of the multigrid vs the reference solver
  mesh info FILE [--json]
                         counts, bounding box, volume, quality, watertightness, pieces
  mesh convert IN OUT [--tets N]
                         convert between .node/.ele, .msh, .vtk and .obj/.ply/.stl/.gltf/.glb
  mesh import SURFACE OUT --tets N [--timeout S] [--tolerance F] [--quality Q]
                         tetrahedralize a closed surface with TetGen, N tets within +-15 %
  mesh generate sphere|charpy|steak OUT [--tets N] [--radius R]
                         the paper's shapes: a tet mesh of N tets (.node, .msh, .vtk), or
                         the closed surface resolved for N tets (.obj, .ply, .stl, .gltf)
  scene check SCENE [--load-mesh]
                         validate a scene file (and build its mesh)
  help, --help           this text;  version, --version

open, run, play and bench take --threads N: the CPU's threads (default: GALSCULPT_THREADS,
else OMP_NUM_THREADS, else every core; docs/cli.md, "Threads").

exit codes: 0 ok, 1 failure, 2 usage, 3 bad input, 4 output not written
)";

}  // namespace

std::string assetDirectory() {
  if (const char* env = std::getenv("GALSCULPT_ASSETS"); env && *env) return env;
  return GALSCULPT_ASSET_DIR;
}

std::string defaultScenePath() {
  return (std::filesystem::path(assetDirectory()) / "scenes" / "default.json").string();
}

int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  try {
    if (args.empty()) return openCommand({defaultScenePath()}, out, err);
    const std::string& command = args[0];
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    if (command == "help" || command == "--help" || command == "-h") {
      out << kUsage;
      return kExitOk;
    }
    if (command == "version" || command == "--version") {
      out << "galsculpt " << GALSCULPT_VERSION << '\n';
      return kExitOk;
    }
    if (command == "mesh") return meshCommand(rest, out, err);
    if (command == "scene") return sceneCommand(rest, out, err);
    if (command == "open") return openCommand(rest, out, err);
    if (command == "render") return renderCommand(rest, out, err);
    if (command == "run") return runCommand(rest, out, err);
    if (command == "play") return playCommand(rest, out, err);
    if (command == "bench") return benchCommand(rest, out, err);
    throw UsageError("unknown command '" + command + "'");
  } catch (const Interrupted& e) {
    err << "galsculpt: " << e.what() << '\n';
    return 128 + e.signal();
  } catch (const UsageError& e) {
    err << "galsculpt: " << e.what() << "\n(run 'galsculpt --help' for usage)\n";
    return kExitUsage;
  } catch (const InputError& e) {
    err << "galsculpt: error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const OutputError& e) {
    err << "galsculpt: error: " << e.what() << '\n';
    return kExitOutput;
  } catch (const std::exception& e) {
    err << "galsculpt: error: " << e.what() << '\n';
    return kExitFailure;
  }
}

}  // namespace galsculpt
