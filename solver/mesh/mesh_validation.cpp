#include "solver/mesh/mesh_validation.h"

#include <algorithm>
#include <cmath>

#include "solver/io/input_error.h"

namespace galsculpt {

void validateTets(TetMesh& mesh, const std::string& file, const std::vector<int>& tetLines,
                  MeshReadReport& report) {
  const int n = mesh.numVertices();
  std::vector<char> used(mesh.vertices.size(), 0);
  for (size_t i = 0; i < mesh.tets.size(); ++i) {
    Tet& t = mesh.tets[i];
    const int line = tetLines[i];
    for (int k = 0; k < 4; ++k) {
      if (t[k] < 0 || t[k] >= n) {
        throw InputError(file, line,
                         "vertex index " + std::to_string(t[k] + report.indexBase) +
                             " out of range [" + std::to_string(report.indexBase) + ", " +
                             std::to_string(n - 1 + report.indexBase) + "]");
      }
    }
    for (int a = 0; a < 4; ++a) {
      for (int b = a + 1; b < 4; ++b) {
        if (t[a] == t[b]) {
          throw InputError(file, line,
                           "degenerate tet: vertex " + std::to_string(t[a] + report.indexBase) +
                               " appears twice");
        }
      }
    }
    const Vec3& p0 = mesh.vertices[t[0]];
    const Vec3& p1 = mesh.vertices[t[1]];
    const Vec3& p2 = mesh.vertices[t[2]];
    const Vec3& p3 = mesh.vertices[t[3]];
    const double sixVolume = tetSixVolume(p0, p1, p2, p3);
    if (isFlatTet(p0, p1, p2, p3))
      throw InputError(file, line, "degenerate tet: zero volume (its four vertices are coplanar)");
    if (sixVolume < 0.0) {
      std::swap(t[2], t[3]);
      ++report.reorientedTets;
    }
    for (int k = 0; k < 4; ++k) used[t[k]] = 1;
  }

  std::vector<std::pair<Tet, int>> keyed;
  keyed.reserve(mesh.tets.size());
  for (size_t i = 0; i < mesh.tets.size(); ++i) {
    Tet key = mesh.tets[i];
    std::sort(key.begin(), key.end());
    keyed.push_back({key, static_cast<int>(i)});
  }
  std::sort(keyed.begin(), keyed.end());
  for (size_t i = 1; i < keyed.size(); ++i) {
    if (keyed[i].first == keyed[i - 1].first) {
      const int a = std::min(keyed[i].second, keyed[i - 1].second);
      const int b = std::max(keyed[i].second, keyed[i - 1].second);
      throw InputError(
          file, tetLines[b],
          "duplicate tet: same vertices as the tet on line " + std::to_string(tetLines[a]));
    }
  }

  report.unusedVertices = static_cast<int>(std::count(used.begin(), used.end(), 0));
  if (report.reorientedTets > 0) {
    report.notes.push_back(file + ": reoriented " + std::to_string(report.reorientedTets) +
                           " inverted tet(s)");
  }
  if (report.unusedVertices > 0) {
    report.notes.push_back(file + ": " + std::to_string(report.unusedVertices) +
                           " vertex(es) belong to no tet");
  }
}

}  // namespace galsculpt
