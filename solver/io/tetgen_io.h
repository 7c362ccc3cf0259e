// TetGen file formats: .node (vertices), .ele (tetrahedra), .face (boundary faces).
//
// Reader: comments (#), blank lines, CRLF, attributes and boundary markers, 0- or 1-based
// numbering (taken from the first vertex, as TetGen does), 10-node tets (corners kept). Strict:
// every count, index and number is checked and errors say `file:line: message`. Malformed or
// binary input raises InputError; it never crashes or hangs.
// Writer: 0-based files with boundary faces, committed as one set (atomic_file.h FileSet):
// every file carries the set's stamp and the reader refuses .node/.ele/.face from different
// writes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "solver/io/atomic_file.h"
#include "solver/mesh/mesh_validation.h"
#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

// `path` is the .node, the .ele or the common stem; the .face file is read when present.
TetMesh readTetGen(const std::filesystem::path& path, MeshReadReport* report = nullptr);

// The stem of a TetGen file set: "a/b.node" -> "a/b"; "a/b" stays.
std::filesystem::path tetgenStem(const std::filesystem::path& path);

// Writes stem.node, stem.ele and stem.face (the boundary, outward). `tetAttribute` (optional,
// one value per tet) is written as the .ele attribute column.
// Writes and commits stem.node/.ele/.face as one set; a stem.damage left from another write is
// removed with it.
void writeTetGen(const std::filesystem::path& stem, const TetMesh& mesh,
                 const std::vector<double>* tetAttribute = nullptr);
// Adds stem.node/.ele/.face to a set the caller commits with other members (a .damage).
void addTetGen(FileSet& set, const std::filesystem::path& stem, const TetMesh& mesh,
               const std::vector<double>* tetAttribute = nullptr);

// Throws InputError naming `other` when its set stamp differs from `first`'s.
void checkSameSet(const std::filesystem::path& first, const std::string& firstStamp,
                  const std::filesystem::path& other, const std::string& otherStamp);

}  // namespace galsculpt
