// Turns a scene's mesh source into a tet mesh: reads a file, or generates / imports and caches.
//
// Large meshes are never committed: they are generated on demand by a deterministic generator
// (or meshed from Debian's CGAL data) and cached as TetGen files under the cache folder:
// $GALSCULPT_CACHE_DIR, else $XDG_CACHE_HOME/galsculpt, else ~/.cache/galsculpt.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/scene.h"
#include "solver/io/damage_io.h"
#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

std::filesystem::path cacheDirectory();

// Where Debian's libcgal-demo data are unpacked by scripts/fetch-cgal-meshes.sh.
std::filesystem::path cgalMeshPath(const std::string& name);

// The closed surface a generator makes, resolved for about
// `targetTets` tets: a surface finer than the volume mesh needs would force extra tets.
TriMesh generatorSurface(Generator generator, double radius, int targetTets);
// The surfaces to tetrahedralize for that count, the one above first and finer ones after it to
// try when TetGen cannot reach the count on it (tetrahedralizeAny).
std::vector<TriMesh> generatorSurfaces(Generator generator, double radius, int targetTets);

using ProgressFn = std::function<void(const std::string&)>;

TetMesh loadSceneMesh(const SceneDescription& scene, const ProgressFn& progress = {});

// The damage a scene's tet mesh file carries beside it (`stem.damage`, solver/io/damage_io.h:
// what `--export-tets` and `export_tets` write), so that an exported mesh reopens cracked.
// Checked against `mesh` (every edge one of its edges) and, beside a TetGen set, to be of the
// same write as its .node (InputError naming the file otherwise). nullopt when the scene's mesh
// is not a file or has no damage beside it.
std::optional<EdgeDamageState> sceneMeshDamage(const SceneDescription& scene, const TetMesh& mesh);

}  // namespace galsculpt
