// One entry point for every mesh file format, chosen by extension.
//
// Tet meshes: TetGen (.node/.ele/.face, read and write), Gmsh 4.1 (.msh, read and write), legacy
// VTK (.vtk, write only). Surfaces: through assimp (surface_io.h).
#pragma once

#include <filesystem>
#include <string>

#include "solver/mesh/mesh_validation.h"
#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

enum class MeshFileKind { TetGen, Gmsh, Vtk, Surface, Unknown };

MeshFileKind meshFileKind(const std::filesystem::path& path);
bool isTetMeshFile(const std::filesystem::path& path);

// Reads a tet mesh (.node, .ele, stem with .node, or .msh). Throws InputError.
TetMesh readTetMesh(const std::filesystem::path& path, MeshReadReport* report = nullptr);

// Writes a tet mesh; `damage` (optional, one value per tet) goes to the .ele attribute or the
// VTK cell data. Throws OutputError.
void writeTetMesh(const std::filesystem::path& path, const TetMesh& mesh,
                  const std::vector<double>* damage = nullptr);

}  // namespace galsculpt
