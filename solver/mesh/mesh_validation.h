// Strict validation shared by every tet-mesh reader.
//
// Errors name the file and line of the offending element. Inverted tets are not an error: they
// are reoriented (two vertices swapped) and counted in the report, since many exporters write
// the opposite orientation convention.
#pragma once

#include <string>
#include <vector>

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

struct MeshReadReport {
  int indexBase = 0;               // 0 or 1, as found in the file
  int reorientedTets = 0;          // inverted tets that were flipped
  int unusedVertices = 0;          // vertices no tet references
  std::vector<std::string> notes;  // human-readable remarks (reorientation, ignored data)
  std::string setStamp;            // the file set's stamp (atomic_file.h FileSet), or empty
};

// Checks range of indices, repeated vertices, zero volume and duplicates; reorients inverted tets.
// `tetLines[i]` is the line tet i came from (for messages). Throws InputError.
void validateTets(TetMesh& mesh, const std::string& file, const std::vector<int>& tetLines,
                  MeshReadReport& report);

}  // namespace galsculpt
