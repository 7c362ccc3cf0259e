// Parts of a triangle surface picked by a grouping of its faces (shells, pieces, groups of
// shells), each a surface of its own.
#pragma once

#include <vector>

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

// The faces whose group is `which`, with their own vertex numbering (in order of first use).
TriMesh facesOfGroup(const TriMesh& mesh, const std::vector<int>& groupOfFace, int which);

// Every group's faces, groups 0 .. count - 1 (faces of a group outside that range are left
// out), each as facesOfGroup makes it, in one pass over the faces.
std::vector<TriMesh> splitByGroup(const TriMesh& mesh, const std::vector<int>& groupOfFace,
                                  int count);

// `part`'s vertices and faces added to `to`, its vertices numbered after `to`'s.
void appendSurface(TriMesh& to, const TriMesh& part);

}  // namespace galsculpt
