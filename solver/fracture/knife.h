// Cutting: a knife stroke is a surface; every mesh edge that crosses it is damaged for good.
//
// The surface is a set of triangles in the current (deformed) configuration: the quad swept by
// a blade segment between two frames, or a screen-space stroke extruded along the view rays.
// Each edge is tested against each triangle with exact orientation predicates
// (exact_predicates.h), so grazing edges, edges through a blade vertex or along a blade edge,
// and edges parallel to the blade are decided consistently:
//   - the triangle is closed: an edge through its boundary or a corner is cut;
//   - an edge end exactly on the blade's plane counts as lying on its positive side (the side
//     its normal (b - a) x (c - a) points to), so a planar cut through mesh vertices assigns each
//     such vertex to one side and still separates the two sides completely;
//   - an edge lying in the blade's plane, and a zero-area (not moving) blade, cut nothing.
#pragma once

#include <vector>

#include "solver/model/sim_model.h"

namespace galsculpt {

struct BladeTriangle {
  Vec3 a, b, c;
};

// The surface swept by a blade segment moving from (from0, from1) to (to0, to1): two
// triangles of the ruled quad.
std::vector<BladeTriangle> sweptBladeSurface(const Vec3& from0, const Vec3& from1, const Vec3& to0,
                                             const Vec3& to1);

// A stroke drawn on the screen, extruded along the view rays: nearPoints[i] and farPoints[i]
// are the ends of the ray through the stroke's i-th point. Two triangles per stroke segment.
std::vector<BladeTriangle> extrudedStrokeSurface(const std::vector<Vec3>& nearPoints,
                                                 const std::vector<Vec3>& farPoints);

// Whether segment pq crosses the closed triangle, by the rules above.
bool segmentCrossesTriangle(const Vec3& p, const Vec3& q, const BladeTriangle& t);

// Where segment pq meets the plane of a triangle it crosses (segmentCrossesTriangle), as a
// fraction from p to q, kept kCrossingMargin away from both ends: a crossing at an end would
// give the crack surface triangles of zero area there.
inline constexpr double kCrossingMargin = 0.01;
double crossingFraction(const Vec3& p, const Vec3& q, const BladeTriangle& t);

// An edge the surface crosses, and where: a fraction along edges[edge] from its first vertex to
// its second (of the first triangle, in surface order, that it crosses).
struct EdgeCrossing {
  int edge = -1;
  float at = 0.5f;
};

// The edges (positions x) that cross any triangle of the surface, by ascending edge index.
std::vector<EdgeCrossing> edgesCrossingSurface(const std::vector<Vec3>& x,
                                               const std::vector<Edge>& edges,
                                               const std::vector<BladeTriangle>& surface);

// Damages every undamaged edge of the state that crosses the surface at the current
// positions and records where the blade crossed it (state.crossing); returns how many were
// newly damaged (and bumps state.damageRevision if any). Edges damaged before keep their
// crossing: damage is for good.
int cutAlongSurface(const SimModel& model, SimState& state,
                    const std::vector<BladeTriangle>& surface);

}  // namespace galsculpt
