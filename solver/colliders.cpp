#include "colliders.h"

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

ContactSample colliderDistance(const Collider& c, const Vec3& p, double time) {
  const Eigen::Matrix3d r = colliderRotation(c, time);
  const Vec3 t = colliderTranslation(c, time);
  const Vec3 local = r.transpose() * (p - t);  // the point in the collider's frame at time 0
  ContactSample s;
  switch (c.type) {
    case Collider::Type::Plane: {
      const Vec3 n = c.normal.normalized();
      s.distance = (local - c.point).dot(n);
      s.normal = r * n;
      break;
    }
    case Collider::Type::Sphere: {
      const Vec3 d = local - c.center;
      const double len = d.norm();
      s.distance = len - c.radius;
      s.normal = r * (len > 0.0 ? Vec3(d / len) : Vec3::UnitY());
      break;
    }
    case Collider::Type::Box: {
      const Vec3 d = local - c.center;
      const Vec3 q = d.cwiseAbs() - c.halfExtents;
      if ((q.array() > 0.0).any()) {
        const Vec3 outside = q.cwiseMax(0.0);
        s.distance = outside.norm();
        Vec3 n = outside.cwiseProduct(d.cwiseSign());
        s.normal = r * (n.norm() > 0.0 ? Vec3(n.normalized()) : Vec3::UnitY());
      } else {
        // Inside: push out through the nearest face.
        int axis = 0;
        q.maxCoeff(&axis);
        s.distance = q[axis];
        Vec3 n = Vec3::Zero();
        n[axis] = d[axis] >= 0.0 ? 1.0 : -1.0;
        s.normal = r * n;
      }
      break;
    }
  }
  return s;
}

}  // namespace galsculpt
