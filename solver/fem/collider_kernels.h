// A rigid collider's signed distance in plain arrays, __host__ __device__: the CPU's
// colliderDistance (colliders.h) and the device backend's contact both call it, with the pose
// (rotation, translation) computed once per sub-step on the host.
#pragma once

#include <cmath>

#include "solver/fem/element_kernels.h"

namespace galsculpt {

// A collider's shape: the one type the scene, the model (Collider) and both backends' kernels
// share.
enum class ColliderShape { Plane, Sphere, Box };

}  // namespace galsculpt

namespace galsculpt::kernels {

struct ColliderPose {
  ColliderShape type = ColliderShape::Plane;
  double point[3] = {0, 0, 0}, normal[3] = {0, 1, 0};  // plane; normal unit
  double center[3] = {0, 0, 0};                        // sphere, box (body frame)
  double radius = 0.0;
  double halfExtents[3] = {0, 0, 0};
  double cornerRadius = 0.0;  // box: its edges and corners rounded to this radius
  M3 rotation = identity3();  // x_world = rotation x_body + translation
  double translation[3] = {0, 0, 0};
  double contactStiffness = 100.0;
};

// Signed distance (negative inside) and outward unit normal of p.
GALSCULPT_HD double colliderDistance(const ColliderPose& c, const double p[3], double normal[3]) {
  double local[3];  // R^T (p - t)
  for (int i = 0; i < 3; ++i) {
    local[i] = 0.0;
    for (int k = 0; k < 3; ++k) local[i] += c.rotation(k, i) * (p[k] - c.translation[k]);
  }
  double n[3] = {0.0, 1.0, 0.0}, distance = 0.0;
  if (c.type == ColliderShape::Plane) {
    distance = 0.0;
    for (int i = 0; i < 3; ++i) {
      distance += (local[i] - c.point[i]) * c.normal[i];
      n[i] = c.normal[i];
    }
  } else if (c.type == ColliderShape::Sphere) {
    double d[3], len2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      d[i] = local[i] - c.center[i];
      len2 += d[i] * d[i];
    }
    const double len = sqrt(len2);
    distance = len - c.radius;
    if (len > 0.0)
      for (int i = 0; i < 3; ++i) n[i] = d[i] / len;
  } else {
    // A rounded box is the inner box (half extents less the radius) grown by the radius: its
    // distance is continuous in gradient wherever a vertex is less than the radius deep, so the
    // contact force turns smoothly round an edge instead of flipping from face to face.
    const double r = c.cornerRadius;
    double d[3], q[3];
    bool outside = false;
    for (int i = 0; i < 3; ++i) {
      d[i] = local[i] - c.center[i];
      q[i] = fabs(d[i]) - (c.halfExtents[i] - r);
      outside = outside || q[i] > 0.0;
    }
    if (outside) {
      double o[3], len2 = 0.0;
      for (int i = 0; i < 3; ++i) {
        o[i] = fmax(q[i], 0.0);
        len2 += o[i] * o[i];
      }
      const double len = sqrt(len2);
      distance = len - r;
      // Out along o with d's signs (o is nonzero only where d is: q > 0 there).
      if (len > 0.0)
        for (int i = 0; i < 3; ++i) n[i] = (d[i] < 0.0 ? -o[i] : o[i]) / len;
    } else {
      // Deeper than the radius: out through the nearest face.
      int axis = 0;
      for (int i = 1; i < 3; ++i)
        if (q[i] > q[axis]) axis = i;
      distance = q[axis] - r;
      for (int i = 0; i < 3; ++i) n[i] = i == axis ? (d[axis] >= 0.0 ? 1.0 : -1.0) : 0.0;
    }
  }
  for (int i = 0; i < 3; ++i)
    normal[i] = c.rotation(i, 0) * n[0] + c.rotation(i, 1) * n[1] + c.rotation(i, 2) * n[2];
  return distance;
}

// The penalty force of collider c on a vertex of mass m at p in a sub-step h, k (-phi) n with
// k = contactStiffness m / h^2 (colliders.h); false, and no force, outside the collider.
GALSCULPT_HD bool contactForce(const ColliderPose& c, const double p[3], double m, double h,
                               double force[3]) {
  double normal[3];
  const double d = colliderDistance(c, p, normal);
  if (d >= 0.0) return false;
  const double s = -c.contactStiffness * m / (h * h) * d;
  for (int k = 0; k < 3; ++k) force[k] = s * normal[k];
  return true;
}

}  // namespace galsculpt::kernels
