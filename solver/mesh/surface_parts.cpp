#include "solver/mesh/surface_parts.h"

namespace galsculpt {

TriMesh facesOfGroup(const TriMesh& mesh, const std::vector<int>& groupOfFace, int which) {
  return splitByGroup(
      mesh,
      [&] {
        std::vector<int> picked(groupOfFace.size(), -1);
        for (size_t f = 0; f < picked.size(); ++f)
          if (groupOfFace[f] == which) picked[f] = 0;
        return picked;
      }(),
      1)[0];
}

std::vector<TriMesh> splitByGroup(const TriMesh& mesh, const std::vector<int>& groupOfFace,
                                  int count) {
  std::vector<TriMesh> parts(count);
  // Faces bucketed by group (a counting sort keeps their order), then each group numbered in
  // turn: a vertex two groups share is a vertex of each.
  std::vector<int> start(count + 1, 0);
  for (int f = 0; f < mesh.numFaces(); ++f)
    if (groupOfFace[f] >= 0 && groupOfFace[f] < count) ++start[groupOfFace[f] + 1];
  for (int g = 0; g < count; ++g) start[g + 1] += start[g];
  std::vector<int> order(start[count]);
  std::vector<int> next(start.begin(), start.end() - 1);
  for (int f = 0; f < mesh.numFaces(); ++f)
    if (groupOfFace[f] >= 0 && groupOfFace[f] < count) order[next[groupOfFace[f]]++] = f;
  std::vector<int> stamp(mesh.numVertices(), -1), number(mesh.numVertices(), 0);
  for (int g = 0; g < count; ++g) {
    TriMesh& part = parts[g];
    for (int k = start[g]; k < start[g + 1]; ++k) {
      Tri tri = mesh.faces[order[k]];
      for (int& v : tri) {
        if (stamp[v] != g) {
          stamp[v] = g;
          number[v] = part.numVertices();
          part.vertices.push_back(mesh.vertices[v]);
        }
        v = number[v];
      }
      part.faces.push_back(tri);
    }
  }
  return parts;
}

void appendSurface(TriMesh& to, const TriMesh& part) {
  const int base = to.numVertices();
  to.vertices.insert(to.vertices.end(), part.vertices.begin(), part.vertices.end());
  for (Tri f : part.faces) {
    for (int& v : f) v += base;
    to.faces.push_back(f);
  }
}

}  // namespace galsculpt
