// Orbit camera: a target, a distance and two angles; produces view and projection matrices.
#pragma once

#include <Eigen/Core>

#include "solver/tet_mesh.h"

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
