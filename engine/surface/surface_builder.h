// The visualization surface M_v, rebuilt from the damage state and the current positions; the
// tet mesh M_c is never remeshed.
//
// Construction (docs/surface.md has the figure). Every tet is split into four corner cells, one
// per vertex, bounded by the tet's edge midpoints, face centroids and centroid. All corner cells
// of one vertex are glued to each other; the cells of an edge's two ends are glued across their
// shared quad (edge midpoint, the two face centroids beside it, tet centroid) unless the edge is
// damaged. The surface is the boundary of this glued complex:
//   - outer faces: the tet mesh's boundary; a boundary triangle with no damaged edge is kept as
//     it is, one with a damaged edge is split into its corner sectors around its centroid;
//   - crack faces: for every damaged edge of every tet, its quad, once from each side.
// A point where cells meet that are not glued around it gets one copy per group of glued cells
// (an edge midpoint: one per side of a damaged edge; a face or tet centroid: one per group of
// its corners joined by undamaged edges). With those copies every piece's surface is a closed,
// consistently oriented 2-manifold, a slit's two sides meet only along the crack front, and
// before any damage the surface is exactly the tet mesh's boundary.
//
// Positions: a point whose copy holds all the corners that define it (both ends of an edge, the
// three corners of a face, ...) sits at their mean. A copy that holds only some of them follows
// its own side: each corner v it holds places it at x_v + F_v (X_p - X_v), F_v being v's local
// deformation fitted over its undamaged edges, so no triangle stretches across an opened crack.
//
// Knife cuts: X_p follows the blade. A damaged edge that a blade crossed (SimState::crossing)
// has its point where the blade crossed it instead of at its midpoint; a face with exactly two
// damaged edges, both crossed, has its point half way between their crossings; a tet whose
// damaged edges split its corners cleanly into two groups, all of them crossed, has its centre
// at the mean of their crossings. The crack faces of such a tet then tile the polygon through
// the crossing points (marching tetrahedra on the blade's side), so a planar blade leaves planar
// crack faces. Only positions change: the topology, and every guarantee above, stay as they are.
//
// Cost: topology work is limited to the tets and boundary faces around edges damaged since the
// previous update; every frame re-evaluates the positions of the surface's vertices.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "solver/model/sim_model.h"

namespace galsculpt {

enum class SurfaceTag : std::uint8_t { Outer = 0, Crack = 1 };

// A triangle surface with, per face, its tag and the tet-mesh vertex whose corner cell it
// bounds (the face belongs to that vertex's piece).
struct VisualSurface {
  TriMesh mesh;
  std::vector<SurfaceTag> tags;  // (nFaces)
  std::vector<int> cellVertex;   // (nFaces) tet-mesh vertex
};

// The faces of one tag with their own compact vertex numbering (shading and export use it so
// that normals stay smooth within a tag and sharp where crack faces meet the outer surface).
// `source` (optional) gets each compact vertex's index in the surface.
TriMesh facesWithTag(const VisualSurface& surface, SurfaceTag tag,
                     std::vector<int>* source = nullptr);

// Smooth shading normals of the outer faces, sharp where crack faces meet them: per vertex, the
// area-weighted normal over the outer faces around it (zero where it has none). Crack faces are
// shaded flat, each with its own normal.
std::vector<Vec3> outerShadingNormals(const VisualSurface& surface);  // (nVerts)

struct SurfaceUpdateStats {
  int rebuiltOwners = 0;  // boundary faces and tets whose triangles were regenerated
  bool topologyChanged = false;
  double msTopology = 0.0;
  double msPositions = 0.0;
};

class SurfaceBuilder {
 public:
  explicit SurfaceBuilder(const SimModel& model);

  // Brings the surface up to `state` (its damage and positions). `model` must be the one the
  // builder was made for.
  SurfaceUpdateStats update(const SimModel& model, const SimState& state);
  const VisualSurface& surface() const { return surface_; }
  // Per surface vertex, the mean current position of the mesh corners its copy holds: where a
  // crack-side copy (one that holds only some of its point's corners) retracts to when the
  // surface is exported (engine/surface/export_surface.h). Every other vertex gets its own
  // position. `state` must be the one of the last update.
  std::vector<Vec3> heldCentres(const SimState& state) const;

 private:
  // Numbers every tet face (faceCorners_, faceEdges_, faceOfTet_) and lists the boundary faces
  // (boundary_); returns (edge, boundary face) for each boundary face's edges.
  std::vector<std::pair<int, int>> numberFaces(const SimModel& model);
  struct BoundaryFace {
    Tri corners;               // outward order
    std::array<int, 3> edges;  // global edge of (c0,c1), (c1,c2), (c2,c0)
    int face = -1;             // global face id
  };
  // A triangle before numbering: each corner is a mesh vertex -(v + 1) or, >= 0, a point key
  // (while emitted) and then the point's slot (once stored).
  struct PendingTri {
    std::array<std::int64_t, 3> corner;
    SurfaceTag tag;
    int cellVertex;
  };

  void regenerateOwner(const SimModel& model, const SimState& state, int owner);
  void emitBoundaryFace(const SimModel& model, const std::vector<std::uint8_t>& damaged, int b,
                        std::vector<PendingTri>& out);
  void emitTet(const SimModel& model, const std::vector<std::uint8_t>& damaged, int t,
               std::vector<PendingTri>& out);
  std::int64_t acquirePoint(std::uint64_t key);
  Vec3 restPoint(const SimModel& model, const SimState& state, std::uint64_t key) const;
  void releasePoint(std::int64_t corner);
  void renumber();
  void evaluatePositions(const SimModel& model, const SimState& state);
  int supportOf(const SimModel& model, std::uint64_t key, int (&support)[4]) const;
  void preparePlacements(const SimModel& model);
  Eigen::Matrix3d fitDeformation(const SimModel& model, const SimState& state, int v) const;

  // Mesh adjacency, built once.
  std::vector<BoundaryFace> boundary_;                 // (nBoundary)
  std::vector<std::array<int, 4>> faceOfTet_;          // (nTets) face opposite each local corner
  std::vector<std::array<int, 3>> faceCorners_;        // (nFaces) sorted
  std::vector<std::array<int, 3>> faceEdges_;          // (nFaces) its three global edges
  std::vector<int> edgeTetStart_, edgeTets_;           // CSR: tets around each edge
  std::vector<int> edgeBoundaryStart_, edgeBoundary_;  // CSR: boundary faces on each edge
  std::vector<int> vertexEdgeStart_, vertexEdges_;     // CSR: edges at each vertex

  // Topology, kept between updates. Owners: boundary faces [0, nB), then tets.
  std::vector<std::uint8_t> damagedSeen_;  // (nEdges) the damage of the last update
  std::vector<float> crossingSeen_;        // (nEdges) the crossings of the last update
  std::uint64_t revisionSeen_ = ~0ull;
  std::vector<int> slotOfOwner_;  // (nB + nTets) index into ownerTris_, -1: default or empty
  std::vector<std::vector<PendingTri>> ownerTris_;
  std::vector<int> freeOwnerSlots_;
  std::unordered_map<std::uint64_t, std::int64_t> pointOfKey_;
  std::vector<std::uint64_t> pointKey_;  // (nSlots)
  std::vector<int> pointRefs_;           // (nSlots)
  std::vector<Vec3> pointRest_;          // (nSlots) X_p, the point's rest position
  // Points acquired during the current update, their rest positions refreshed once at its end.
  std::vector<std::int64_t> acquiredPoints_;
  std::vector<std::uint32_t> pointStamp_;  // (nSlots) the update that last listed the point
  std::uint32_t updateStamp_ = 0;
  std::vector<std::int64_t> freePoints_;

  // Output numbering: each surface vertex is a point slot (>= 0) or a mesh vertex -(v + 1).
  std::vector<std::int64_t> outSource_;
  std::vector<int> vertexOut_, pointOut_;  // renumbering scratch
  // How each surface vertex is placed: a mesh vertex (count 0, support[0]), or a point copy: its
  // support, the corners it holds (mask) and its rest position.
  struct Placement {
    std::array<int, 4> support{};
    int count = 0;
    unsigned mask = 0;
    Vec3 rest = Vec3::Zero();
  };
  std::vector<Placement> placements_;         // (nSurfaceVertices)
  std::vector<int> deformedVertices_;         // vertices whose F_v some copy needs
  std::vector<Eigen::Matrix3d> deformation_;  // (nVerts) F_v, refreshed for those each update

  VisualSurface surface_;
};

}  // namespace galsculpt
