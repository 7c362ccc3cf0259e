// Surface mesh import and export through assimp.
//
// Import: OBJ, PLY, STL, OFF, glTF/GLB (and whatever else assimp reads); all meshes of the file
// are merged in world coordinates and vertices at identical positions are welded, so that an STL
// (one vertex per corner) comes back as a connected surface.
// Export: OBJ (no .mtl), PLY, STL (binary), glTF2 (.gltf + .bin, or .glb). Writes are atomic: the
// files are exported into a temporary folder beside the target and renamed into place.
// The visualization surface (writeVisualSurface) keeps its tags: OBJ groups `outer` and `crack`
// over one shared vertex list (written by us: assimp's OBJ exporter merges vertices at equal
// positions, which would weld the two sides of a closed crack), glTF one mesh per tag;
// PLY and STL hold one untagged triangle list. readSurface welds vertices at equal positions
// (STL needs it; assimp's OBJ reader does not keep the file's indexing), so a crack whose two
// sides still touch comes back closed: the files themselves keep them apart.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "engine/surface/surface_builder.h"
#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

bool isSurfaceFile(const std::filesystem::path& path);

TriMesh readSurface(const std::filesystem::path& path);

// `vertexNormals` (optional, one per vertex) are written where the format holds them.
void writeSurface(const std::filesystem::path& path, const TriMesh& mesh,
                  const std::vector<Vec3>* vertexNormals = nullptr);

// The visualization surface, by extension (see above).
void writeVisualSurface(const std::filesystem::path& path, const VisualSurface& surface);

}  // namespace galsculpt
