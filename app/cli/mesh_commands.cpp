// `galsculpt mesh info | convert | import | generate`.
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli/cli.h"
#include "app/cli/cli_args.h"
#include "app/cli/command_table.h"
#include "app/cli/progress_text.h"
#include "engine/meshing/mesh_files.h"
#include "engine/meshing/tetrahedralize.h"
#include "engine/scene/scene_mesh.h"
#include "engine/surface/surface_io.h"
#include "solver/io/damage_io.h"
#include "solver/io/input_error.h"
#include "solver/io/tetgen_io.h"
#include "solver/mesh/mesh_stats.h"
#include "solver/mesh/surface_checks.h"
#include "solver/mesh/surface_parts.h"
#include "solver/mesh/union_find.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

std::string vec(const Vec3& v) {
  std::ostringstream s;
  s << std::setprecision(9) << v.x() << ' ' << v.y() << ' ' << v.z();
  return s.str();
}

// The damage written beside a TetGen mesh (stem.damage), checked to be of the same write.
struct DamageBeside {
  bool present = false;
  int damaged = 0, crossed = 0;
  int pieces = 0;  // parts joined by undamaged edges (vertices of no tet aside)
};

int piecesThroughDamage(const TetMesh& mesh, const std::vector<Edge>& edges,
                        const std::vector<std::uint8_t>& damaged) {
  UnionFind parts(mesh.numVertices());
  for (size_t e = 0; e < edges.size(); ++e)
    if (!damaged[e]) parts.unite(edges[e][0], edges[e][1]);
  std::vector<char> used(mesh.numVertices(), 0), root(mesh.numVertices(), 0);
  for (const Tet& t : mesh.tets)
    for (int v : t) used[v] = 1;
  int pieces = 0;
  for (int v = 0; v < mesh.numVertices(); ++v) {
    if (!used[v]) continue;
    char& seen = root[parts.find(v)];
    pieces += !seen;
    seen = 1;
  }
  return pieces;
}
DamageBeside readDamageBeside(const fs::path& file, const TetMesh& mesh,
                              const MeshReadReport& report) {
  DamageBeside d;
  if (meshFileKind(file) != MeshFileKind::TetGen) return d;
  const fs::path stem = tetgenStem(file);
  const fs::path damagePath = fs::path(stem).concat(".damage");
  std::error_code ec;
  if (!fs::exists(damagePath, ec)) return d;
  const std::vector<Edge> edges = uniqueEdges(mesh);
  const EdgeDamageState state = readDamage(damagePath, edges);
  checkSameSet(fs::path(stem).concat(".node"), report.setStamp, damagePath, state.setStamp);
  d.present = true;
  for (size_t e = 0; e < state.damaged.size(); ++e) {
    d.damaged += state.damaged[e];
    d.crossed += hasCrossing(state.crossing[e]);
  }
  d.pieces = piecesThroughDamage(mesh, edges, state.damaged);
  return d;
}

int infoTet(const fs::path& file, bool json, std::ostream& out) {
  MeshReadReport report;
  const TetMesh mesh = readTetMesh(file, &report);
  const DamageBeside damage = readDamageBeside(file, mesh, report);
  const TetMeshStats s = computeStats(mesh);
  if (json) {
    nlohmann::json j;
    j["file"] = file.string();
    j["kind"] = "tet";
    j["vertices"] = s.vertices;
    j["tets"] = s.tets;
    j["edges"] = s.edges;
    j["boundary_faces"] = s.boundaryFaces;
    j["bbox_min"] = vec3Json(s.box.min);
    j["bbox_max"] = vec3Json(s.box.max);
    j["volume"] = s.volume;
    j["quality_min"] = s.minQuality;
    j["quality_mean"] = s.meanQuality;
    j["quality_histogram"] = s.qualityHistogram;
    j["watertight"] = s.watertight;
    j["pieces"] = damage.present ? damage.pieces : s.pieces;
    j["mesh_pieces"] = s.pieces;
    j["reoriented_tets"] = report.reorientedTets;
    j["unused_vertices"] = report.unusedVertices;
    if (damage.present) {
      j["damaged_edges"] = damage.damaged;
      j["blade_crossings"] = damage.crossed;
    }
    out << j.dump(2) << '\n';
    return kExitOk;
  }
  out << std::setprecision(9);
  out << "file: " << file.string() << "\nkind: tet mesh\n";
  out << "vertices: " << s.vertices << "\ntets: " << s.tets << "\nedges: " << s.edges
      << "\nboundary_faces: " << s.boundaryFaces << '\n';
  out << "bbox_min: " << vec(s.box.min) << "\nbbox_max: " << vec(s.box.max) << '\n';
  out << "volume: " << s.volume << '\n';
  out << "quality_min: " << s.minQuality << "\nquality_mean: " << s.meanQuality << '\n';
  out << "quality_histogram:";
  for (int b = 0; b < 10; ++b)
    out << ' ' << std::fixed << std::setprecision(1) << b / 10.0 << ':' << s.qualityHistogram[b];
  out << std::defaultfloat << std::setprecision(9) << '\n';
  out << "watertight: " << (s.watertight ? "yes" : "no (" + s.boundaryProblem + ")") << '\n';
  out << "pieces: " << (damage.present ? damage.pieces : s.pieces) << '\n';
  out << "mesh_pieces: " << s.pieces << '\n';
  out << "reoriented_tets: " << report.reorientedTets
      << "\nunused_vertices: " << report.unusedVertices << '\n';
  if (damage.present)
    out << "damaged_edges: " << damage.damaged << "\nblade_crossings: " << damage.crossed << '\n';
  return kExitOk;
}

// What the shells of a surface are: closed pieces (enclosing positive volume) and the rest
// (cavities, inside-out shells), and which crossing face pairs lie inside one shell
// (self-intersection) and which between two (pieces in contact through each other).
struct ShellCensus {
  int shells = 0, pieces = 0, inwardShells = 0;
  size_t selfCrossings = 0, contactCrossings = 0;
  bool capped = false;      // the census stopped at its bound: more contact pairs may exist
  bool selfCapped = false;  // ditto, for the crossings inside a shell
};
ShellCensus censusOfShells(const TriMesh& mesh) {
  constexpr size_t kMaxPairs = 1000;
  ShellCensus c;
  std::vector<int> shellOfFace;
  c.shells = countSurfacePieces(mesh, &shellOfFace);
  for (double v : enclosedVolumes(mesh, shellOfFace, c.shells))
    (v > 0.0 ? c.pieces : c.inwardShells)++;
  const auto crossings = findSelfIntersections(mesh, kMaxPairs);
  c.capped = c.selfCapped = crossings.size() >= kMaxPairs;
  for (const auto& [f, g] : crossings)
    (shellOfFace[f] == shellOfFace[g] ? c.selfCrossings : c.contactCrossings)++;
  if (c.capped) {
    c.selfCapped = false;
    // The pairs found first may all be contact: each shell is checked on its own, so that a
    // crossing inside one is never hidden behind the cap.
    c.selfCrossings = 0;
    for (const TriMesh& shell : splitByGroup(mesh, shellOfFace, c.shells)) {
      const size_t found = findSelfIntersections(shell, kMaxPairs).size();
      c.selfCrossings += found;
      c.selfCapped |= found >= kMaxPairs;
    }
  }
  return c;
}

int infoSurface(const fs::path& file, bool json, std::ostream& out) {
  const TriMesh mesh = readSurface(file);
  const SurfaceTopology topo = analyzeSurface(mesh);
  const ShellCensus shells = censusOfShells(mesh);
  const BoundingBox box = boundingBox(mesh.vertices);
  const bool watertight = topo.closedManifold() && shells.selfCrossings == 0;
  const std::string more = shells.capped ? "+" : "";
  const std::string moreSelf = shells.selfCapped ? "+" : "";
  std::string problem = topo.describeProblem();
  if (problem.empty() && shells.selfCrossings > 0) {
    problem = "self-intersecting: " + std::to_string(shells.selfCrossings) + moreSelf +
              " crossing face pair(s) inside a shell";
  }
  if (json) {
    nlohmann::json j;
    j["file"] = file.string();
    j["kind"] = "surface";
    j["vertices"] = mesh.numVertices();
    j["faces"] = mesh.numFaces();
    j["bbox_min"] = vec3Json(box.min);
    j["bbox_max"] = vec3Json(box.max);
    j["volume"] = enclosedVolume(mesh);
    j["area"] = surfaceArea(mesh);
    j["watertight"] = watertight;
    j["problem"] = problem;
    j["self_intersections"] = shells.selfCrossings;
    j["shells"] = shells.shells;
    j["pieces"] = shells.pieces;
    j["inward_shells"] = shells.inwardShells;
    j["contact_crossings"] = shells.contactCrossings;
    out << j.dump(2) << '\n';
    return kExitOk;
  }
  out << std::setprecision(9);
  out << "file: " << file.string() << "\nkind: surface\n";
  out << "vertices: " << mesh.numVertices() << "\nfaces: " << mesh.numFaces() << '\n';
  out << "bbox_min: " << vec(box.min) << "\nbbox_max: " << vec(box.max) << '\n';
  out << "volume: " << enclosedVolume(mesh) << "\narea: " << surfaceArea(mesh) << '\n';
  out << "watertight: " << (watertight ? "yes" : "no (" + problem + ")") << '\n';
  out << "self_intersections: " << shells.selfCrossings << moreSelf << '\n';
  out << "shells: " << shells.shells << '\n';
  out << "pieces: " << shells.pieces << '\n';
  out << "inward_shells: " << shells.inwardShells << '\n';
  out << "contact: "
      << (shells.contactCrossings == 0 ? std::string("none (no two shells cross)")
                                       : std::to_string(shells.contactCrossings) + more +
                                             " crossing face pair(s) between shells")
      << '\n';
  return kExitOk;
}

TetMesh meshSurface(const std::vector<TriMesh>& surfaces, const std::string& name, const CliArgs& a,
                    std::ostream& err) {
  TetrahedralizeOptions options;
  options.targetTets = a.intValue("--tets", 0, 1, 50000000);
  options.timeoutSeconds = a.doubleValue("--timeout", 300.0, 1.0, 86400.0);
  options.tolerance = a.doubleValue("--tolerance", 0.15, 0.01, 1.0);
  options.radiusEdgeRatio = a.doubleValue("--quality", 1.414, 1.05, 10.0);
  options.surfaceName = name;
  // Each step's line with the time since the import began (TetGen's attempts say how many
  // there may be at most: the time left is not known before the count is reached).
  const auto started = std::chrono::steady_clock::now();
  options.progress = [&err, started](const std::string& line) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    err << '[' << durationText(elapsed) << "] " << line << '\n' << std::flush;
  };
  return tetrahedralizeAny(surfaces, options).mesh;
}

void writeAny(const fs::path& path, const TetMesh& mesh, std::ostream& out) {
  if (meshFileKind(path) == MeshFileKind::Surface) {
    const TriMesh surface = boundarySurface(mesh);
    writeSurface(path, surface);
    out << "wrote " << path.string() << " (" << surface.numVertices() << " vertices, "
        << surface.numFaces() << " faces: the tet mesh's boundary)\n";
    return;
  }
  writeTetMesh(path, mesh);
  out << "wrote " << path.string() << " (" << mesh.numVertices() << " vertices, " << mesh.numTets()
      << " tets)\n";
}

// The output as given, or, without an extension, a TetGen basename (OUT -> OUT.node, .ele,
// .face), as TetGen's own tools take it.
fs::path checkedOutput(const fs::path& path) {
  if (path.extension().empty() && !path.filename().empty()) return fs::path(path).concat(".node");
  const MeshFileKind k = meshFileKind(path);
  if (k == MeshFileKind::Unknown) {
    throw UsageError("unknown output format '" + path.extension().string() +
                     "' (use .node, .msh, .vtk, .obj, .ply, .stl, .gltf or .glb, or a basename "
                     "without extension for .node/.ele/.face)");
  }
  return path;
}

// mesh info FILE [--json]: what a tet or surface mesh holds and whether it is sound.
int meshInfo(const std::vector<std::string>& rest, std::ostream& out) {
  const CliArgs a(rest, commandSpec("mesh info"));
  fs::path file = a.positional()[0];
  // A .damage file is read with the mesh it belongs to (stem.node/.ele beside it).
  if (file.extension() == ".damage")
    file = fs::path(tetgenStem(file.replace_extension())).concat(".node");
  const MeshFileKind kind = meshFileKind(file);
  if (kind == MeshFileKind::Surface) return infoSurface(file, a.has("--json"), out);
  if (kind == MeshFileKind::Vtk)
    throw InputError(file.string(), 0, "legacy VTK is an output format");
  if (kind == MeshFileKind::Unknown) throw InputError(file.string(), 0, "unknown mesh format");
  return infoTet(file, a.has("--json"), out);
}

// mesh convert IN OUT [--tets N]: between formats; a surface to tets through TetGen.
int meshConvert(const std::vector<std::string>& rest, std::ostream& out, std::ostream& err) {
  const CliArgs a(rest, commandSpec("mesh convert"));
  const fs::path in = a.positional()[0], outPath = checkedOutput(a.positional()[1]);
  const bool outSurface = meshFileKind(outPath) == MeshFileKind::Surface;
  if (meshFileKind(in) == MeshFileKind::Surface) {
    const TriMesh surface = readSurface(in);
    if (outSurface) {
      writeSurface(outPath, surface);
      out << "wrote " << outPath.string() << " (" << surface.numVertices() << " vertices, "
          << surface.numFaces() << " faces)\n";
      return kExitOk;
    }
    if (!a.has("--tets")) throw UsageError("converting a surface to a tet mesh needs --tets N");
    writeAny(outPath, meshSurface({surface}, in.filename().string(), a, err), out);
    return kExitOk;
  }
  MeshReadReport report;
  const TetMesh mesh = readTetMesh(in, &report);
  for (const std::string& note : report.notes) err << "note: " << note << '\n';
  writeAny(outPath, mesh, out);
  return kExitOk;
}

// mesh import SURFACE OUT --tets N: a surface tetrahedralized to about N tets.
int meshImport(const std::vector<std::string>& rest, std::ostream& out, std::ostream& err) {
  const CliArgs a(rest, commandSpec("mesh import"));
  a.intValue("--tets", 0, 1, 50000000);  // a malformed count is a usage error before any I/O
  const fs::path in = a.positional()[0], outPath = checkedOutput(a.positional()[1]);
  if (meshFileKind(outPath) == MeshFileKind::Surface)
    throw UsageError("mesh import writes a tet mesh: use .node, .msh or .vtk");
  if (meshFileKind(in) != MeshFileKind::Surface) {
    throw InputError(in.string(), 0,
                     "not a surface mesh (expected .obj, .ply, .stl, .off, .gltf or .glb)");
  }
  const TriMesh surface = readSurface(in);
  writeAny(outPath, meshSurface({surface}, in.string(), a, err), out);
  return kExitOk;
}

// mesh generate sphere|charpy|steak OUT: a generated shape, as a surface or tets.
int meshGenerate(const std::vector<std::string>& rest, std::ostream& out, std::ostream& err) {
  const CliArgs a(rest, commandSpec("mesh generate"));
  const std::string name = a.positional()[0];
  const std::optional<Generator> generator = generatorFromName(name);
  if (!generator) throw UsageError("unknown shape '" + name + "' (sphere, charpy or steak)");
  const fs::path outPath = checkedOutput(a.positional()[1]);
  // A surface alone (no --tets) gets the resolution of the paper's scene.
  const int tets =
      a.intValue("--tets", *generator == Generator::Steak ? 186000 : 35000, 1, 50000000);
  const std::vector<TriMesh> surfaces =
      generatorSurfaces(*generator, a.doubleValue("--radius", 0.1, 1e-6, 1e6), tets);
  const TriMesh& surface = surfaces.front();
  if (meshFileKind(outPath) == MeshFileKind::Surface) {
    writeSurface(outPath, surface);
    out << "wrote " << outPath.string() << " (" << surface.numVertices() << " vertices, "
        << surface.numFaces() << " faces)\n";
    return kExitOk;
  }
  if (!a.has("--tets")) throw UsageError("a tet mesh output needs --tets N");
  writeAny(outPath, meshSurface(surfaces, name, a, err), out);
  return kExitOk;
}

}  // namespace

int meshCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  subcommandOf("mesh", args);
  const std::string sub = args[0];
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (sub == "info") return meshInfo(rest, out);
  if (sub == "convert") return meshConvert(rest, out, err);
  if (sub == "import") return meshImport(rest, out, err);
  if (sub == "generate") return meshGenerate(rest, out, err);
  throw std::logic_error("mesh " + sub + " is in the command table but not dispatched");
}

}  // namespace galsculpt
