#include "solver/fem/colliders.h"

#include <Eigen/Geometry>
#include <cmath>

namespace galsculpt {

Eigen::Matrix3d colliderRotation(const Collider& c, double time) {
  if (c.motion.type != ColliderMotion::Type::Pendulum) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(c.motion.angularVelocity * time, c.motion.axis.normalized())
      .toRotationMatrix();
}

Vec3 colliderTranslation(const Collider& c, double time) {
  switch (c.motion.type) {
    case ColliderMotion::Type::Static:
      return Vec3::Zero();
    case ColliderMotion::Type::Linear:
      return c.motion.velocity * time;
    case ColliderMotion::Type::Pendulum: {
      const Eigen::Matrix3d r = colliderRotation(c, time);
      return c.motion.pivot - r * c.motion.pivot;  // rotation about the pivot
    }
  }
  return Vec3::Zero();
}

kernels::ColliderPose colliderPose(const Collider& c, double time) {
  kernels::ColliderPose pose;
  pose.type = static_cast<int>(c.type);
  const Vec3 n = c.normal.normalized();
  for (int i = 0; i < 3; ++i) {
    pose.point[i] = c.point[i];
    pose.normal[i] = n[i];
    pose.center[i] = c.center[i];
    pose.halfExtents[i] = c.halfExtents[i];
  }
  pose.radius = c.radius;
  const Eigen::Matrix3d r = colliderRotation(c, time);
  for (int i = 0; i < 9; ++i) pose.rotation.a[i] = r.data()[i];
  const Vec3 t = colliderTranslation(c, time);
  for (int i = 0; i < 3; ++i) pose.translation[i] = t[i];
  pose.contactStiffness = c.contactStiffness;
  return pose;
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
