// Rigid colliders (ground plane, sphere, box), static or kinematic, acting through a penalty
// energy on the vertices that penetrate them.
//
// Each penetrating vertex v adds 1/2 k_v phi(x_v)^2 with phi the signed distance (negative
// inside) and k_v = contactStiffness * m_v / h^2: scaled by the vertex's own inertia term, the
// penalty is equally stiff at every mesh scale and time step, and the Hessian k n n^T is PSD.
#pragma once

#include <vector>

#include "solver/fem/collider_kernels.h"
#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

struct ColliderMotion {
  enum class Type { Static, Linear, Pendulum };
  Type type = Type::Static;
  Vec3 velocity = Vec3::Zero();  // Linear (m/s)
  Vec3 pivot = Vec3::Zero();     // Pendulum: rotation about the axis through the pivot
  Vec3 axis = Vec3::UnitZ();
  double angularVelocity = 0.0;  // rad/s
};

struct Collider {
  enum class Type { Plane, Sphere, Box };
  Type type = Type::Plane;
  Vec3 point = Vec3::Zero(), normal = Vec3::UnitY();  // Plane
  Vec3 center = Vec3::Zero();                         // Sphere, Box: position at time 0
  double radius = 0.0;
  Vec3 halfExtents = Vec3::Zero();
  ColliderMotion motion;
  double contactStiffness = 100.0;  // in units of m_v / h^2
};

struct ContactSample {
  double distance = 0.0;        // signed, negative inside
  Vec3 normal = Vec3::UnitY();  // outward, unit
};

// Signed distance and outward normal of `p` against the collider posed at `time`
// (collider_kernels.h computes it, for both backends).
ContactSample colliderDistance(const Collider& c, const Vec3& p, double time);

// The collider's rigid pose at `time`: x_world = rotation * x_body + translation, where the
// body frame is the collider at time 0.
Eigen::Matrix3d colliderRotation(const Collider& c, double time);
Vec3 colliderTranslation(const Collider& c, double time);

// The collider at `time` as the shared kernel takes it.
kernels::ColliderPose colliderPose(const Collider& c, double time);

}  // namespace galsculpt
