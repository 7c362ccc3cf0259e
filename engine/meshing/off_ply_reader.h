// Strict readers for OFF and PLY surfaces.
//
// assimp reads both, but not strictly: its OFF reader clamps a face index past the vertex count
// and accepts negative ones, and its PLY reader passes indices out of range through, reads a
// list whose count runs past its line into the next faces, and makes up vertices when the header
// promises more than the file holds. These readers check everything before use: counts against
// the file's size before allocating, every index against the vertex count, list counts against
// the data actually there, finite coordinates, nothing left over. Errors name the file and the
// line (text) or the byte offset (binary PLY).
//
// Polygons are split into triangle fans (as assimp's triangulation does); faces of fewer than
// three corners are errors. Only the vertices' x, y, z and the faces' index list are kept.
#pragma once

#include <filesystem>
#include <vector>

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

// Vertices as written and triangles indexing them (no welding).
struct RawSurface {
  std::vector<Vec3> vertices;
  std::vector<Tri> faces;
};

// OFF (also COFF / NOFF / CNOFF: per-vertex extras after x y z are skipped), `#` comments.
RawSurface readOff(const std::filesystem::path& path);

// PLY 1.0: ascii, binary_little_endian, binary_big_endian; a `vertex` element with x, y, z and
// a `face` element with a list property `vertex_indices` (or `vertex_index`); other elements
// and properties are read and skipped.
RawSurface readPly(const std::filesystem::path& path);

}  // namespace galsculpt
