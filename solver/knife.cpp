#include "knife.h"

#include <algorithm>

#include "exact_predicates.h"

namespace galsculpt {

std::vector<BladeTriangle> sweptBladeSurface(const Vec3& from0, const Vec3& from1, const Vec3& to0,
                                             const Vec3& to1) {
  return {{from0, from1, to1}, {from0, to1, to0}};
}

std::vector<BladeTriangle> extrudedStrokeSurface(const std::vector<Vec3>& nearPoints,
                                                 const std::vector<Vec3>& farPoints) {
  std::vector<BladeTriangle> out;
  const size_t n = std::min(nearPoints.size(), farPoints.size());
  for (size_t i = 0; i + 1 < n; ++i) {
    out.push_back({nearPoints[i], nearPoints[i + 1], farPoints[i + 1]});
    out.push_back({nearPoints[i], farPoints[i + 1], farPoints[i]});
  }
  return out;
}

bool segmentCrossesTriangle(const Vec3& p, const Vec3& q, const BladeTriangle& t) {
  int sp = orient3d(t.a, t.b, t.c, p);
  int sq = orient3d(t.a, t.b, t.c, q);
  if (sp == 0 && sq == 0) return false;  // in the blade's plane, or a degenerate blade
  // Symbolic perturbation: a point on the plane counts as lying on the side the blade's normal
  // (b - a) x (c - a) points to, where orient3d is negative.
  if (sp == 0) sp = -1;
  if (sq == 0) sq = -1;
  if (sp == sq) return false;
  // The line pq meets the plane inside the closed triangle iff it passes on the same side of
  // all three triangle edges (zeros: through an edge or a corner).
  const int s1 = orient3d(p, q, t.a, t.b);
  const int s2 = orient3d(p, q, t.b, t.c);
  const int s3 = orient3d(p, q, t.c, t.a);
  const bool anyPositive = s1 > 0 || s2 > 0 || s3 > 0;
  const bool anyNegative = s1 < 0 || s2 < 0 || s3 < 0;
  return !(anyPositive && anyNegative);
}

std::vector<int> edgesCrossingSurface(const std::vector<Vec3>& x, const std::vector<Edge>& edges,
                                      const std::vector<BladeTriangle>& surface) {
  struct Box {
    Vec3 lo, hi;
  };
  std::vector<Box> boxes(surface.size());
  Box all{Vec3::Constant(1e300), Vec3::Constant(-1e300)};
  for (size_t i = 0; i < surface.size(); ++i) {
    const BladeTriangle& t = surface[i];
    boxes[i] = {t.a.cwiseMin(t.b).cwiseMin(t.c), t.a.cwiseMax(t.b).cwiseMax(t.c)};
    all.lo = all.lo.cwiseMin(boxes[i].lo);
    all.hi = all.hi.cwiseMax(boxes[i].hi);
  }
  std::vector<char> crosses(edges.size(), 0);
  const int n = static_cast<int>(edges.size());
#pragma omp parallel for schedule(static)
  for (int e = 0; e < n; ++e) {
    const Vec3& p = x[edges[e][0]];
    const Vec3& q = x[edges[e][1]];
    const Vec3 lo = p.cwiseMin(q), hi = p.cwiseMax(q);
    if ((hi.array() < all.lo.array()).any() || (lo.array() > all.hi.array()).any()) continue;
    for (size_t i = 0; i < surface.size(); ++i) {
      if ((hi.array() < boxes[i].lo.array()).any() || (lo.array() > boxes[i].hi.array()).any())
        continue;
      if (segmentCrossesTriangle(p, q, surface[i])) {
        crosses[e] = 1;
        break;
      }
    }
  }
  std::vector<int> out;
  for (int e = 0; e < n; ++e) {
    if (crosses[e]) out.push_back(e);
  }
  return out;
}

int cutAlongSurface(const SimModel& model, SimState& state,
                    const std::vector<BladeTriangle>& surface) {
  int cut = 0;
  for (int e : edgesCrossingSurface(state.x, model.edges, surface)) {
    if (!state.damaged[e]) {
      state.damaged[e] = 1;
      ++cut;
    }
  }
  if (cut > 0) ++state.damageRevision;
  return cut;
}

}  // namespace galsculpt
