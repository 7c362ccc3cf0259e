#include "engine/session/tool_reach.h"

#include <algorithm>
#include <limits>

namespace galsculpt {

double distanceToTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // The closest point by the region of the triangle's plane p projects into (Ericson, Real-Time
  // Collision Detection, 5.1.5).
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return ap.norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denominator = va + vb + vc;
  if (!(std::abs(denominator) > 0.0)) return std::min({ap.norm(), bp.norm(), cp.norm()});
  const double v = vb / denominator, w = vc / denominator;
  return (p - (a + v * ab + w * ac)).norm();
}

double distanceToBlade(const std::vector<BladeTriangle>& blade, const std::vector<Vec3>& points) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Vec3& p : points)
    for (const BladeTriangle& t : blade)
      nearest = std::min(nearest, distanceToTriangle(p, t.a, t.b, t.c));
  return nearest;
}

}  // namespace galsculpt
