// TetGen file formats: .node (vertices), .ele (tetrahedra), .face (boundary faces).
//
// Reader: comments (#), blank lines, CRLF, attributes and boundary markers, 0- or 1-based
// numbering (taken from the first vertex, as TetGen does), 10-node tets (corners kept). Strict:
// every count, index and number is checked and errors say `file:line: message`. Malformed or
// binary input raises InputError; it never crashes or hangs.
// Writer: 0-based files with boundary faces; each file is written atomically.
#pragma once

#include <filesystem>
#include <vector>

#include "mesh_validation.h"
#include "tet_mesh.h"

namespace galsculpt {

// `path` is the .node, the .ele or the common stem; the .face file is read when present.
TetMesh readTetGen(const std::filesystem::path& path, MeshReadReport* report = nullptr);

// The stem of a TetGen file set: "a/b.node" -> "a/b"; "a/b" stays.
std::filesystem::path tetgenStem(const std::filesystem::path& path);

// Writes stem.node, stem.ele and stem.face (the boundary, outward). `tetAttribute` (optional,
// one value per tet) is written as the .ele attribute column.
void writeTetGen(const std::filesystem::path& stem, const TetMesh& mesh,
                 const std::vector<double>* tetAttribute = nullptr);

}  // namespace galsculpt
