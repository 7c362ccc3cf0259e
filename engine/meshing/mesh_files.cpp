#include "engine/meshing/mesh_files.h"

#include <algorithm>

#include "engine/surface/surface_io.h"
#include "solver/io/gmsh_io.h"
#include "solver/io/input_error.h"
#include "solver/io/tetgen_io.h"
#include "solver/io/vtk_io.h"

namespace galsculpt {

namespace fs = std::filesystem;

MeshFileKind meshFileKind(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".node" || ext == ".ele" || ext == ".face") return MeshFileKind::TetGen;
  if (ext == ".msh") return MeshFileKind::Gmsh;
  if (ext == ".vtk") return MeshFileKind::Vtk;
  if (isSurfaceFile(path)) return MeshFileKind::Surface;
  if (ext.empty()) {
    std::error_code ec;
    if (fs::exists(fs::path(path).concat(".node"), ec)) return MeshFileKind::TetGen;
  }
  return MeshFileKind::Unknown;
}

bool isTetMeshFile(const fs::path& path) {
  const MeshFileKind k = meshFileKind(path);
  return k == MeshFileKind::TetGen || k == MeshFileKind::Gmsh;
}

TetMesh readTetMesh(const fs::path& path, MeshReadReport* report) {
  switch (meshFileKind(path)) {
    case MeshFileKind::TetGen:
      return readTetGen(path, report);
    case MeshFileKind::Gmsh:
      return readGmsh(path, report);
    case MeshFileKind::Vtk:
      throw InputError(path.string(), 0, "legacy VTK is an output format; read .node/.ele or .msh");
    case MeshFileKind::Surface:
      throw InputError(path.string(), 0,
                       "this is a surface mesh; tetrahedralize it with 'galsculpt mesh import'");
    case MeshFileKind::Unknown:
      break;
  }
  throw InputError(
      path.string(), 0,
      "unknown mesh format (expected .node, .ele, .msh, .obj, .ply, .stl, .off, .gltf, .glb)");
}

void writeTetMesh(const fs::path& path, const TetMesh& mesh, const std::vector<double>* damage) {
  switch (meshFileKind(path)) {
    case MeshFileKind::TetGen:
      writeTetGen(path, mesh, damage);
      return;
    case MeshFileKind::Gmsh:
      writeGmsh(path, mesh);
      return;
    case MeshFileKind::Vtk: {
      std::vector<VtkCellField> fields;
      if (damage) fields.push_back({"damage", *damage});
      writeVtk(path, mesh, fields);
      return;
    }
    default:
      break;
  }
  throw OutputError("cannot write " + path.string() +
                    ": unknown tet mesh format (use .node, .msh or .vtk)");
}

}  // namespace galsculpt
