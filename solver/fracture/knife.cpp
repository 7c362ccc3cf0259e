#include "solver/fracture/knife.h"

#include <algorithm>

#include "solver/frame/parallel.h"
#include "solver/mesh/exact_predicates.h"

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

double crossingFraction(const Vec3& p, const Vec3& q, const BladeTriangle& t) {
  const Vec3 n = (t.b - t.a).cross(t.c - t.a);
  const double dp = n.dot(p - t.a), dq = n.dot(q - t.a);
  // dp and dq have opposite signs (or one is zero) for a crossing edge, so the quotient is in
  // [0, 1] up to rounding; an edge in the plane crosses nothing, but stay defined for it.
  const double at = dp != dq ? dp / (dp - dq) : 0.5;
  return std::clamp(at, kCrossingMargin, 1.0 - kCrossingMargin);
}

std::vector<EdgeCrossing> edgesCrossingSurface(const std::vector<Vec3>& x,
                                               const std::vector<Edge>& edges,
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
  std::vector<float> crossing(edges.size(), -1.0f);
  const int n = static_cast<int>(edges.size());
  parallelFor(
      n,
      [&](int e) {
        const Vec3& p = x[edges[e][0]];
        const Vec3& q = x[edges[e][1]];
        const Vec3 lo = p.cwiseMin(q), hi = p.cwiseMax(q);
        if ((hi.array() < all.lo.array()).any() || (lo.array() > all.hi.array()).any()) return;
        for (size_t i = 0; i < surface.size(); ++i) {
          if ((hi.array() < boxes[i].lo.array()).any() || (lo.array() > boxes[i].hi.array()).any())
            continue;
          if (segmentCrossesTriangle(p, q, surface[i])) {
            crossing[e] = static_cast<float>(crossingFraction(p, q, surface[i]));
            break;
          }
        }
      },
      8 + static_cast<long>(surface.size()));
  std::vector<EdgeCrossing> out;
  for (int e = 0; e < n; ++e) {
    if (crossing[e] >= 0.0f) out.push_back({e, crossing[e]});
  }
  return out;
}

int cutAlongSurface(const SimModel& model, SimState& state,
                    const std::vector<BladeTriangle>& surface) {
  int cut = 0;
  if (state.crossing.size() != state.damaged.size())
    state.crossing.assign(state.damaged.size(), kNoCrossing);
  for (const EdgeCrossing& c : edgesCrossingSurface(state.x, model.edges, surface)) {
    if (!state.damaged[c.edge]) {
      state.damaged[c.edge] = 1;
      state.crossing[c.edge] = c.at;
      ++cut;
    }
  }
  if (cut > 0) ++state.damageRevision;
  return cut;
}

}  // namespace galsculpt
