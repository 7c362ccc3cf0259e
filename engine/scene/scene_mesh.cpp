#include "engine/scene/scene_mesh.h"

#include "solver/mesh/locality_order.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>

#include "engine/meshing/mesh_files.h"
#include "engine/meshing/tetrahedralize.h"
#include "engine/surface/surface_io.h"
#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"
#include "solver/io/tetgen_io.h"
#include "solver/mesh/shape_generators.h"

namespace galsculpt {

namespace fs = std::filesystem;

fs::path cacheDirectory() {
  if (const char* dir = std::getenv("GALSCULPT_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return fs::path(xdg) / "galsculpt";
  if (const char* home = std::getenv("HOME"); home && *home)
    return fs::path(home) / ".cache" / "galsculpt";
  return fs::temp_directory_path() / "galsculpt-cache";
}

fs::path cgalMeshPath(const std::string& name) {
  return cacheDirectory() / "cgal" / (name + ".off");
}

namespace {
// Finest subdivision whose 20 * 4^s faces stay below targetTets / tetsPerFace.
int subdivisionsFor(int targetTets, double tetsPerFace, int minLevel, int maxLevel) {
  int level = minLevel;
  while (level < maxLevel && 20.0 * std::pow(4.0, level + 1) <= targetTets / tetsPerFace) ++level;
  return level;
}
}  // namespace

namespace {

// The charpy bar and the steak slab: one surface each.
TriMesh solidSurface(Generator generator, int targetTets) {
  switch (generator) {
    case Generator::Sphere:
      break;
    case Generator::Charpy:
      return makeCharpyBar();
    case Generator::Steak: {
      // Surface triangles of about the size of a tet edge at this count (8 surface faces per
      // 100 tets keeps the boundary from forcing extra tets); never coarser than 15 mm.
      const double area = 0.04;  // m^2, the slab's surface
      const double faces = std::max(200.0, 0.08 * targetTets);
      return makeSteakSlab(std::min(0.015, std::sqrt(area / (0.433 * faces))));
    }
  }
  throw std::logic_error("unhandled generator");
}

}  // namespace

TriMesh generatorSurface(Generator generator, double radius, int targetTets) {
  return generatorSurfaces(generator, radius, targetTets).front();
}

std::vector<TriMesh> generatorSurfaces(Generator generator, double radius, int targetTets) {
  if (generator != Generator::Sphere) return {solidSurface(generator, targetTets)};
  // 1280 faces for the paper's 35k-tet sphere; then the next two finer spheres, since TetGen's
  // refinement jumps over some small counts on one of them and reaches them on another.
  const int level = subdivisionsFor(targetTets, 20.0, 1, 5);
  std::vector<TriMesh> out;
  for (int l = level; l <= std::min(level + 2, 5); ++l) out.push_back(makeIcosphere(radius, l));
  return out;
}

namespace {

// `surfaces` makes the surfaces to mesh, only when the cache has no entry for `key`. The mesh
// comes in locality order (locality_order.h), read or made: entries TetGen's order left in a
// cache are put in it on reading.
using SurfaceMaker = std::function<std::vector<TriMesh>()>;

TetMesh cachedTetrahedralization(const SurfaceMaker& surfaces, const std::string& key,
                                 const std::string& name, int tets, const ProgressFn& progress,
                                 bool keepShape) {
  const fs::path dir = cacheDirectory() / "meshes";
  const fs::path stem = dir / key;
  std::error_code ec;
  if (fs::exists(fs::path(stem).concat(".node"), ec) &&
      fs::exists(fs::path(stem).concat(".ele"), ec)) {
    try {
      TetMesh mesh = readTetGen(stem);
      orderForLocality(mesh);  // (a no-op on an entry written in this order)
      return mesh;
    } catch (const InputError& e) {
      // A damaged entry (a disk that filled, a copy cut short) is made again, and said.
      if (progress)
        progress("the cached mesh is damaged (" + std::string(e.what()) + "): remeshing");
      for (const char* ext : {".node", ".ele", ".face", ".damage"})
        fs::remove(fs::path(stem).concat(ext), ec);
    }
  }
  fs::create_directories(dir, ec);
  if (ec) throw OutputError("cannot create the mesh cache " + dir.string() + ": " + ec.message());
  if (progress)
    progress("meshing " + name + " (" + std::to_string(tets) + " tets), cached in " + dir.string());
  TetrahedralizeOptions options;
  options.targetTets = tets;
  options.surfaceName = name;
  options.progress = progress;
  options.keepShape = keepShape;
  TetrahedralizeResult result = tetrahedralizeAny(surfaces(), options);
  orderForLocality(result.mesh);
  writeTetGen(stem, result.mesh);
  return std::move(result.mesh);
}

// A count TetGen cannot reach is the scene's error: it names the file, the key and a count
// that works.
TetMesh sceneTetrahedralization(const SceneDescription& scene, const SurfaceMaker& surfaces,
                                const std::string& key, const std::string& name,
                                const ProgressFn& progress) {
  try {
    // A generator's surface is made for the count: only an imported one must keep its shape.
    return cachedTetrahedralization(surfaces, key, name, scene.mesh.tets, progress,
                                    scene.mesh.kind == MeshSource::Kind::Import);
  } catch (const TetCountUnreachable& e) {
    // The closest count was reached, so it works, unless it is below what a scene may ask for.
    const std::string advice =
        e.closest >= kMinSceneTets
            ? std::to_string(e.closest) + " tets is a count that works"
            : "ask for more tets (the closest count is below the least a scene may ask, " +
                  std::to_string(kMinSceneTets) + ")";
    throw InputError(scene.file.string(), 0,
                     "$.mesh.tets: " + std::string(e.what()) + "; " + advice);
  }
}

// FNV-1a over the file's bytes: a cache key, not a checksum against tampering.
std::uint64_t contentHash(const fs::path& file) {
  std::uint64_t h = 1469598103934665603ull;
  for (const char c : readWholeFile(file)) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return h;
}

void transformSurface(TriMesh& surface, const MeshSource& m) {
  for (Vec3& v : surface.vertices) v = v * m.scale + m.translate;
}

}  // namespace

TetMesh loadSceneMesh(const SceneDescription& scene, const ProgressFn& progress) {
  const MeshSource& m = scene.mesh;
  switch (m.kind) {
    case MeshSource::Kind::File: {
      std::error_code ec;
      if (!fs::exists(m.path, ec) && !fs::exists(fs::path(m.path).concat(".node"), ec))
        throw InputError(scene.file.string(), 0,
                         "$.mesh.file: " + m.path.string() + " does not exist");
      TetMesh mesh = readTetMesh(m.path);
      for (Vec3& v : mesh.vertices) v = v * m.scale + m.translate;
      return mesh;
    }
    case MeshSource::Kind::Generate: {
      const SurfaceMaker surfaces = [&m] {
        std::vector<TriMesh> out = generatorSurfaces(m.generator, m.radius, m.tets);
        for (TriMesh& surface : out) transformSurface(surface, m);
        return out;
      };
      std::ostringstream key;
      key << generatorName(m.generator) << "-" << m.tets;
      if (m.generator == Generator::Sphere) key << "-r" << m.radius;
      if (m.scale != 1.0 || !m.translate.isZero())
        key << "-s" << m.scale << "-t" << m.translate.transpose();
      std::string k = key.str();
      for (char& c : k)
        if (c == ' ') c = '_';
      return sceneTetrahedralization(scene, surfaces, k, generatorName(m.generator), progress);
    }
    case MeshSource::Kind::Import: {
      fs::path source = m.path;
      std::string name = m.path.filename().string();
      if (!m.cgalMesh.empty()) {
        source = cgalMeshPath(m.cgalMesh);
        name = m.cgalMesh;
        std::error_code ec;
        if (!fs::exists(source, ec)) {
          throw InputError(scene.file.string(), 0,
                           "$.mesh.import: " + source.string() +
                               " is missing; run scripts/fetch-cgal-meshes.sh (installs Debian's "
                               "libcgal-demo and unpacks its meshes)");
        }
      }
      std::error_code ec;
      if (!fs::exists(source, ec))
        throw InputError(scene.file.string(), 0,
                         "$.mesh.import: " + source.string() + " does not exist");
      const SurfaceMaker surfaces = [&m, &source] {
        TriMesh surface = readSurface(source);
        transformSurface(surface, m);
        return std::vector<TriMesh>{std::move(surface)};
      };
      // Everything that decides the mesh: the source's content (two files of one name differ),
      // the transform and the count.
      std::ostringstream key;
      key << "import-" << fs::path(name).stem().string() << "-" << m.tets << "-s" << m.scale << "-t"
          << m.translate.transpose() << "-h" << std::hex << contentHash(source);
      std::string k = key.str();
      for (char& c : k)
        if (c == ' ') c = '_';
      return sceneTetrahedralization(scene, surfaces, k, name, progress);
    }
  }
  throw std::logic_error("unhandled mesh source");
}

std::optional<EdgeDamageState> sceneMeshDamage(const SceneDescription& scene, const TetMesh& mesh) {
  if (scene.mesh.kind != MeshSource::Kind::File) return std::nullopt;
  const fs::path& file = scene.mesh.path;
  const bool tetgen = meshFileKind(file) == MeshFileKind::TetGen;
  const fs::path stem = tetgen ? tetgenStem(file) : fs::path(file).replace_extension();
  const fs::path damagePath = fs::path(stem).concat(".damage");
  std::error_code ec;
  if (!fs::exists(damagePath, ec)) return std::nullopt;
  EdgeDamageState damage = readDamage(damagePath, uniqueEdges(mesh));
  if (tetgen) {
    const fs::path node = fs::path(stem).concat(".node");
    checkSameSet(node, findSetStamp(readWholeFile(node)), damagePath, damage.setStamp);
  }
  return damage;
}

}  // namespace galsculpt
