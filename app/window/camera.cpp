#include "app/window/camera.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace galsculpt {

Eigen::Vector3d OrbitCamera::eye() const {
  const Eigen::Vector3d dir(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                            std::cos(pitch) * std::cos(yaw));
  return target + distance * dir;
}

Eigen::Matrix4f OrbitCamera::view() const {
  const Eigen::Vector3d e = eye();
  const Eigen::Vector3d f = (target - e).normalized();
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  if (std::abs(f.dot(up)) > 0.999) up = -Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d s = f.cross(up).normalized();
  const Eigen::Vector3d u = s.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(e);
  m(1, 3) = -u.dot(e);
  m(2, 3) = f.dot(e);
  return m.cast<float>();
}

Eigen::Matrix4f OrbitCamera::projection(double aspect) const {
  const double nearPlane = std::max(1e-6, distance * 0.01);
  const double farPlane = distance * 100.0;
  const double f = 1.0 / std::tan(fovY / 2.0);
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = f / aspect;
  p(1, 1) = f;
  p(2, 2) = (farPlane + nearPlane) / (nearPlane - farPlane);
  p(2, 3) = 2.0 * farPlane * nearPlane / (nearPlane - farPlane);
  p(3, 2) = -1.0;
  return p.cast<float>();
}

void OrbitCamera::frame(const BoundingBox& box) {
  target = box.center();
  const double radius = std::max(0.5 * box.size().norm(), 1e-9);
  distance = radius / std::sin(fovY / 2.0) * 1.05;
}

void OrbitCamera::orbit(double dYaw, double dPitch) {
  yaw += dYaw;
  pitch = std::clamp(pitch + dPitch, -1.55, 1.55);
}

void OrbitCamera::pan(double dx, double dy) {
  const Eigen::Vector3d f = (target - eye()).normalized();
  const Eigen::Vector3d s = f.cross(Eigen::Vector3d::UnitY()).normalized();
  const Eigen::Vector3d u = s.cross(f);
  const double h = 2.0 * distance * std::tan(fovY / 2.0);
  target += (-dx * s + dy * u) * h;
}

void OrbitCamera::zoom(double factor) {
  distance = std::max(1e-9, distance * factor);
}

}  // namespace galsculpt

namespace galsculpt {

void OrbitCamera::ray(double px, double py, int width, int height, Eigen::Vector3d& origin,
                      Eigen::Vector3d& direction) const {
  const double aspect = static_cast<double>(width) / std::max(height, 1);
  const double ndcX = 2.0 * px / std::max(width, 1) - 1.0;
  const double ndcY = 1.0 - 2.0 * py / std::max(height, 1);
  const double t = std::tan(fovY / 2.0);
  const Eigen::Matrix3d rotation = view().cast<double>().topLeftCorner<3, 3>();
  // View space: x right, y up, looking down -z; rows of `rotation` are those axes in world space.
  const Eigen::Vector3d inView(ndcX * t * aspect, ndcY * t, -1.0);
  origin = eye();
  direction = (rotation.transpose() * inView).normalized();
}

Eigen::Vector3d OrbitCamera::project(const Eigen::Vector3d& point, int width, int height) const {
  const Eigen::Vector4d v = view().cast<double>() * point.homogeneous();
  const double aspect = static_cast<double>(width) / std::max(height, 1);
  const double t = std::tan(fovY / 2.0);
  const double depth = -v.z();
  const double ndcX = v.x() / (depth * t * aspect), ndcY = v.y() / (depth * t);
  return Eigen::Vector3d(0.5 * (ndcX + 1.0) * width, 0.5 * (1.0 - ndcY) * height, depth);
}

}  // namespace galsculpt
