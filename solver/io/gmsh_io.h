// Gmsh MSH 4.1 ASCII: read linear (and the corners of quadratic) tetrahedra; write linear tets.
//
// Only the $MeshFormat, $Nodes and $Elements sections are interpreted; other sections are
// skipped. Node tags may be sparse. Binary files are rejected with a clear message.
#pragma once

#include <filesystem>

#include "solver/mesh/mesh_validation.h"
#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

TetMesh readGmsh(const std::filesystem::path& path, MeshReadReport* report = nullptr);
void writeGmsh(const std::filesystem::path& path, const TetMesh& mesh);

}  // namespace galsculpt
