// Tetrahedral and triangle mesh containers and their basic geometry.
//
// TetMesh is the computational mesh M_c: it is never remeshed. Tets are stored positively
// oriented (det[b-a, c-a, d-a] > 0); readers reorient inverted input and report it.
// TriMesh is a surface (import/export, the visualization mesh M_v).
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace galsculpt {

using Vec3 = Eigen::Vector3d;
using Tet = std::array<int, 4>;
using Tri = std::array<int, 3>;
using Edge = std::array<int, 2>;  // always stored with [0] < [1]

struct TetMesh {
  std::vector<Vec3> vertices;      // (nVerts)
  std::vector<Tet> tets;           // (nTets), positively oriented
  std::vector<Tri> faces;          // (nFaces) boundary faces as read from a .face file, if any
  std::vector<int> faceMarkers;    // (nFaces or empty)
  std::vector<int> vertexMarkers;  // (nVerts or empty)

  int numVertices() const { return static_cast<int>(vertices.size()); }
  int numTets() const { return static_cast<int>(tets.size()); }
};

struct TriMesh {
  std::vector<Vec3> vertices;  // (nVerts)
  std::vector<Tri> faces;      // (nFaces), counter-clockwise seen from outside

  int numVertices() const { return static_cast<int>(vertices.size()); }
  int numFaces() const { return static_cast<int>(faces.size()); }
};

struct BoundingBox {
  Vec3 min = Vec3::Constant(0.0);
  Vec3 max = Vec3::Constant(0.0);
  Vec3 size() const { return max - min; }
  Vec3 center() const { return 0.5 * (min + max); }
};

// Six times the signed volume: positive when (a, b, c, d) is positively oriented.
inline double tetSixVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a));
}
// Flat to 1e-10 of its own size (its longest edge cubed): what a mesh reader refuses as a
// zero-volume tet. Slivers of poor but real quality are not flat.
bool isFlatTet(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
double tetVolume(const TetMesh& mesh, int tet);
// Sum of tet volumes.
double totalVolume(const TetMesh& mesh);

// The four faces of a positively oriented tet, each counter-clockwise seen from outside.
std::array<Tri, 4> tetFacesOutward(const Tet& t);

// Faces that belong to exactly one tet, oriented outward (the tet mesh's boundary).
std::vector<Tri> boundaryFaces(const TetMesh& mesh);
// For each tet, the tet across its face opposite each corner (tetFacesOutward's order); -1 on
// the boundary (and where more than two tets share a face, which a valid mesh never has).
std::vector<std::array<int, 4>> tetFaceNeighbours(const TetMesh& mesh);
// The boundary as a surface with its own compact vertex numbering; `toTetVertex` (optional)
// receives the tet-mesh index of each surface vertex.
TriMesh boundarySurface(const TetMesh& mesh, std::vector<int>* toTetVertex = nullptr);

// Unique edges of the mesh, sorted lexicographically.
std::vector<Edge> uniqueEdges(const TetMesh& mesh);

BoundingBox boundingBox(const std::vector<Vec3>& points);

// Area-weighted vertex normals of a surface (zero for unused vertices); the second form uses
// only the given faces (a subset of a surface's, e.g. one tag's).
std::vector<Vec3> vertexNormals(const TriMesh& mesh);
std::vector<Vec3> vertexNormals(const std::vector<Vec3>& vertices, const std::vector<Tri>& faces);

// Mean-ratio quality in [0, 1]: 1 for a regular tet, 0 for a flat one (negative if inverted).
double tetMeanRatio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// Connected parts of the mesh: tets that share a vertex are in one piece. Returns the number of
// pieces; `pieceOfVertex` (optional) gets the piece of each vertex (-1 for unused vertices).
int countPieces(const TetMesh& mesh, std::vector<int>* pieceOfVertex = nullptr);

}  // namespace galsculpt
