// Ray picking against the visualization surface: a bounding volume hierarchy over its
// triangles. Built when the surface's triangles change (new damage), refitted when only the
// positions moved (every frame), so a pick costs O(log n) instead of a scan of every triangle.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

struct RayHit {
  int face = -1;
  double distance = 0.0;  // along the ray, in units of its (normalized) direction
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::Zero();  // the face's unit normal (counter-clockwise side)
};

class SurfaceBvh {
 public:
  // Builds over `mesh`'s faces (median splits along the longest axis, up to 4 faces a leaf).
  void build(const TriMesh& mesh);
  // Same faces, new positions: recomputes the boxes bottom-up.
  void refit(const TriMesh& mesh);
  int numFaces() const { return static_cast<int>(faces_.size()); }

  // The nearest face hit from either side by the ray origin + t * direction, t in (0, maxT].
  std::optional<RayHit> intersect(const TriMesh& mesh, const Vec3& origin, const Vec3& direction,
                                  double maxT = 1e300) const;
  // The distance from `p` to the nearest point of the faces (0 with no faces: none built).
  double distance(const TriMesh& mesh, const Vec3& p) const;

 private:
  struct Node {
    Vec3 min = Vec3::Zero(), max = Vec3::Zero();
    int left = -1, right = -1;  // children; -1: a leaf
    int first = 0, count = 0;   // leaf: range in faces_
  };
  int buildNode(const TriMesh& mesh, std::vector<Vec3>& centroids, int first, int count);
  std::vector<Node> nodes_;
  std::vector<int> faces_;  // face ids in leaf order
};

// Picking on a surface that changes between picks (the simulation's, the window's drawn copy):
// one BVH, rebuilt when the surface's faces may have changed (another `topology` key, another
// face count) and refitted when only its positions moved (another `generation`).
class SurfacePicker {
 public:
  std::optional<RayHit> intersect(const TriMesh& mesh, std::uint64_t topology,
                                  std::uint64_t generation, const Vec3& origin,
                                  const Vec3& direction);

 private:
  SurfaceBvh bvh_;
  std::uint64_t topology_ = ~0ull, generation_ = ~0ull;
  int faces_ = -1;
};

}  // namespace galsculpt
