// Orbit camera: a target, a distance and two angles; produces view and projection matrices.
#pragma once

#include <Eigen/Core>

#include "engine/session/playback.h"
#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

struct OrbitCamera {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double distance = 1.0;
  double yaw = 0.6;     // radians around +y
  double pitch = 0.35;  // radians above the horizontal
  double fovY = 0.75;   // radians

  Eigen::Vector3d eye() const;
  Eigen::Matrix4f view() const;
  Eigen::Matrix4f projection(double aspect) const;
  // Target the box centre and back off until the whole box is in view.
  void frame(const BoundingBox& box);
  void orbit(double dYaw, double dPitch);
  void pan(double dx, double dy);  // in units of the view height at the target
  void zoom(double factor);

  // The ray through pixel (px, py) of a width x height view (y down): from the eye, unit
  // direction.
  void ray(double px, double py, int width, int height, Eigen::Vector3d& origin,
           Eigen::Vector3d& direction) const;
  // Pixel position (y down) and distance along the view axis of a world point.
  Eigen::Vector3d project(const Eigen::Vector3d& point, int width, int height) const;
  // Unit vector the camera looks along.
  Eigen::Vector3d forward() const { return (target - eye()).normalized(); }

  // As scripts and projects record it.
  CameraPose pose() const { return CameraPose{target, distance, yaw, pitch}; }
  void setPose(const CameraPose& p) {
    target = p.target;
    distance = p.distance;
    yaw = p.yaw;
    pitch = p.pitch;
  }

  // Standard views.
  void viewFront() {
    yaw = 0.0;
    pitch = 0.0;
  }
  void viewSide() {
    yaw = 1.5707963267948966;
    pitch = 0.0;
  }
  void viewTop() {
    yaw = 0.0;
    pitch = 1.5607963267948966;
  }
};

}  // namespace galsculpt
