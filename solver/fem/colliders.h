// Rigid colliders (ground plane, sphere, box), static, kinematic or a rigid pendulum, acting
// through a penalty energy on the vertices that penetrate them.
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
  double angularVelocity = 0.0;  // rad/s (a rigid pendulum's at time 0)
  // Pendulum: > 0 makes it a rigid body of this mass (kg) at the collider's centre, swinging
  // freely about the axis under gravity and the body's contact forces (two-way contact): it
  // slows as the body absorbs its energy. 0: kinematic, at angularVelocity for ever.
  double mass = 0.0;
  bool rigidPendulum() const { return type == Type::Pendulum && mass > 0.0; }
};

struct Collider {
  using Type = ColliderShape;
  Type type = Type::Plane;
  Vec3 point = Vec3::Zero(), normal = Vec3::UnitY();  // Plane
  Vec3 center = Vec3::Zero();                         // Sphere, Box: position at time 0
  double radius = 0.0;
  Vec3 halfExtents = Vec3::Zero();
  double cornerRadius = 0.0;  // Box: edges and corners rounded (0 <= r <= the least half extent)
  ColliderMotion motion;
  double contactStiffness = 100.0;  // in units of m_v / h^2
};

// A rigid pendulum's state (SimState::colliders; kinematic colliders ignore theirs).
struct ColliderState {
  double angle = 0.0;            // rad about the motion's axis, from the collider as given
  double angularVelocity = 0.0;  // rad/s
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

// The collider at `time` as the shared kernel takes it; a rigid pendulum at its state's angle.
kernels::ColliderPose colliderPose(const Collider& c, double time,
                                   const ColliderState* state = nullptr);

// Where the collider's centre is at `time` (a rigid pendulum's at its state's angle).
Vec3 colliderCentre(const Collider& c, double time, const ColliderState* state = nullptr);

// What a collider's state is at time 0: angle 0 and the motion's angular velocity.
ColliderState initialColliderState(const Collider& c);

// A rigid pendulum's moment of inertia about its axis (kg m^2): its mass at the collider's
// centre, at the centre's distance from the axis.
double pendulumInertia(const Collider& c);
// Gravity's moment about the axis on the pendulum at `angle` (N m).
double pendulumGravityMoment(const Collider& c, double angle, const Vec3& gravity);
// Kinetic plus gravitational energy (J), the latter zero at angle 0.
double pendulumEnergy(const Collider& c, const ColliderState& s, const Vec3& gravity);
// One sub-step h of the pendulum under `contactMoment` (N m about the axis, from the body, at
// the end of the sub-step): the angle advanced with the velocity it started with (the pose the
// body was solved against), then the velocity with the moments at that angle (semi-implicit
// Euler; the body's 4 g against a 20 kg hammer keeps the explicit coupling far from unstable).
void advancePendulum(const Collider& c, ColliderState& s, double h, double contactMoment,
                     const Vec3& gravity);

}  // namespace galsculpt
