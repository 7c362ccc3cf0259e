// Surface mesh import and export through assimp.
//
// Import: OBJ, PLY, STL, OFF, glTF/GLB (and whatever else assimp reads); all meshes of the file
// are merged in world coordinates and vertices at identical positions are welded, so that an STL
// (one vertex per corner) comes back as a connected surface.
// Export: OBJ (no .mtl), PLY, STL (binary), glTF2 (.gltf + .bin, or .glb). Writes are atomic: the
// files are exported into a temporary folder beside the target and renamed into place.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "solver/tet_mesh.h"

namespace galsculpt {

bool isSurfaceFile(const std::filesystem::path& path);

TriMesh readSurface(const std::filesystem::path& path);

// `vertexNormals` (optional, one per vertex) are written where the format holds them.
void writeSurface(const std::filesystem::path& path, const TriMesh& mesh,
                  const std::vector<Vec3>* vertexNormals = nullptr);

}  // namespace galsculpt
