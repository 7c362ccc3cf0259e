#include "solver/fem/colliders.h"

#include <Eigen/Geometry>
#include <cmath>

namespace galsculpt {

namespace {

Eigen::Matrix3d rotationAbout(const Collider& c, double angle) {
  return Eigen::AngleAxisd(angle, c.motion.axis.normalized()).toRotationMatrix();
}

// The pose at `time`: a rigid pendulum at its state's angle (when given), a kinematic one at
// angularVelocity * time.
Eigen::Matrix3d rotationAt(const Collider& c, double time, const ColliderState* state) {
  if (c.motion.type != ColliderMotion::Type::Pendulum) return Eigen::Matrix3d::Identity();
  const bool rigid = state && c.motion.rigidPendulum();
  return rotationAbout(c, rigid ? state->angle : c.motion.angularVelocity * time);
}

Vec3 translationAt(const Collider& c, double time, const ColliderState* state) {
  switch (c.motion.type) {
    case ColliderMotion::Type::Static:
      return Vec3::Zero();
    case ColliderMotion::Type::Linear:
      return c.motion.velocity * time;
    case ColliderMotion::Type::Pendulum: {
      const Eigen::Matrix3d r = rotationAt(c, time, state);
      return c.motion.pivot - r * c.motion.pivot;  // rotation about the pivot
    }
  }
  return Vec3::Zero();
}

}  // namespace

Eigen::Matrix3d colliderRotation(const Collider& c, double time) {
  return rotationAt(c, time, nullptr);
}

Vec3 colliderTranslation(const Collider& c, double time) {
  return translationAt(c, time, nullptr);
}

kernels::ColliderPose colliderPose(const Collider& c, double time, const ColliderState* state) {
  kernels::ColliderPose pose;
  pose.type = c.type;
  const Vec3 n = c.normal.normalized();
  for (int i = 0; i < 3; ++i) {
    pose.point[i] = c.point[i];
    pose.normal[i] = n[i];
    pose.center[i] = c.center[i];
    pose.halfExtents[i] = c.halfExtents[i];
  }
  pose.radius = c.radius;
  pose.cornerRadius = c.cornerRadius;
  const Eigen::Matrix3d r = rotationAt(c, time, state);
  for (int i = 0; i < 9; ++i) pose.rotation.a[i] = r.data()[i];
  const Vec3 t = translationAt(c, time, state);
  for (int i = 0; i < 3; ++i) pose.translation[i] = t[i];
  pose.contactStiffness = c.contactStiffness;
  return pose;
}

Vec3 colliderCentre(const Collider& c, double time, const ColliderState* state) {
  const kernels::ColliderPose pose = colliderPose(c, time, state);
  Vec3 p;
  for (int i = 0; i < 3; ++i)
    p[i] = pose.rotation(i, 0) * c.center[0] + pose.rotation(i, 1) * c.center[1] +
           pose.rotation(i, 2) * c.center[2] + pose.translation[i];
  return p;
}

ColliderState initialColliderState(const Collider& c) {
  ColliderState s;
  if (c.motion.type == ColliderMotion::Type::Pendulum) s.angularVelocity = c.motion.angularVelocity;
  return s;
}

namespace {

// The centre's offset from the axis (perpendicular to it) at `angle`.
Vec3 armAt(const Collider& c, double angle) {
  const Vec3 a = c.motion.axis.normalized();
  Vec3 arm = c.center - c.motion.pivot;
  arm -= a * a.dot(arm);
  return rotationAbout(c, angle) * arm;
}

}  // namespace

double pendulumInertia(const Collider& c) {
  return c.motion.mass * armAt(c, 0.0).squaredNorm();
}

double pendulumGravityMoment(const Collider& c, double angle, const Vec3& gravity) {
  return armAt(c, angle).cross(c.motion.mass * gravity).dot(c.motion.axis.normalized());
}

double pendulumEnergy(const Collider& c, const ColliderState& s, const Vec3& gravity) {
  const double kinetic = 0.5 * pendulumInertia(c) * s.angularVelocity * s.angularVelocity;
  const double potential = -c.motion.mass * gravity.dot(armAt(c, s.angle) - armAt(c, 0.0));
  return kinetic + potential;
}

void advancePendulum(const Collider& c, ColliderState& s, double h, double contactMoment,
                     const Vec3& gravity) {
  s.angle += h * s.angularVelocity;
  const double inertia = pendulumInertia(c);
  if (inertia > 0.0)
    s.angularVelocity += h * (contactMoment + pendulumGravityMoment(c, s.angle, gravity)) / inertia;
}

ContactSample colliderDistance(const Collider& c, const Vec3& p, double time) {
  const kernels::ColliderPose pose = colliderPose(c, time);
  ContactSample s;
  double normal[3];
  s.distance = kernels::colliderDistance(pose, p.data(), normal);
  s.normal = Vec3(normal[0], normal[1], normal[2]);
  return s;
}

}  // namespace galsculpt
