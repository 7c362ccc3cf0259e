// The tools' input: mouse and keys (window pixels, y down; no GLFW here) turned into camera
// moves and sculpting actions on a SculptSession. The window feeds it GLFW's events and the UI
// test feeds it synthetic ones (app/window/input_script.h): the same path either way.
//
// Mouse: the left button uses the current tool; the right button orbits, the middle button (or
// shift + right) pans, the wheel zooms. With the Navigate tool the left button orbits too.
// Every cursor sample between two frames is used: a knife stroke cuts the quad swept between
// consecutive samples, anchor paint lays dabs at most half a radius apart along the way, and
// brushes cover the capsule they swept (sculptor.h), so fast strokes are never dropped.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "app/window/camera.h"
#include "engine/session/sculpt_session.h"
#include "engine/surface/surface_bvh.h"

namespace galsculpt {

// The tools are the table's (engine/session/tool_table.h): their labels, keys and kinds.

enum class MouseButton { Left, Right, Middle };

struct ToolSettings {
  Tool tool = Tool::Grab;
  double radius = 0.02;    // m
  double strength = 0.15;  // m/s, for push, pull, inflate and pinch
  bool symmetry = false;
  int symmetryAxis = 0;         // 0 x, 1 y, 2 z
  double symmetryOffset = 0.0;  // plane position along the axis (m)
  Symmetry plane() const { return symmetry ? Symmetry{symmetryAxis, symmetryOffset} : Symmetry{}; }
};

class ToolController {
 public:
  // `settings` are the app's (panel, keys): read at each event, never copied.
  ToolController(SculptSession& session, OrbitCamera& camera, const ToolSettings& settings);

  void setViewport(int width, int height);
  void mouseMove(double x, double y);
  void mouseButton(MouseButton button, bool pressed, bool shift);
  void scroll(double steps);
  // A tool in use when the window loses the mouse (or an undo comes) ends cleanly.
  void cancelStroke();
  bool strokeActive() const { return active_ != Active::None; }
  // What the last stroke did not do, to tell the user once ("the knife crossed no edge: ..."),
  // or empty; taking it clears it.
  std::string takeNotice() { return std::exchange(notice_, {}); }
  // Nothing under way but, at most, an orbit or a pan (which touch only the camera).
  bool navigating() const {
    return active_ == Active::None || active_ == Active::Orbit || active_ == Active::Pan;
  }
  // The last cursor position it was given (window pixels).
  double cursorX() const { return x_; }
  double cursorY() const { return y_; }

  // The surface point under pixel (x, y).
  std::optional<RayHit> pick(double x, double y);

 private:
  enum class Active { None, Orbit, Pan, Knife, Brush, Paint };
  void cutTo(double x, double y);
  void paintTo(const RayHit& hit);

  SculptSession& session_;
  int knifeCut_ = 0;    // edges the knife stroke under way has cut
  std::string notice_;  // takeNotice
  OrbitCamera& camera_;
  const ToolSettings& settings_;
  int width_ = 1, height_ = 1;
  double x_ = 0.0, y_ = 0.0;
  Active active_ = Active::None;
  SurfacePicker picker_;
  // Knife: the blade of the last sample (near and far ends of its ray through the body).
  Vec3 bladeNear_ = Vec3::Zero(), bladeFar_ = Vec3::Zero();
  double knifeNear_ = 0.0, knifeFar_ = 0.0;
  // Grab: the plane (through the grabbed point, facing the camera) the cursor drags on.
  Vec3 grabPoint_ = Vec3::Zero(), grabNormal_ = Vec3::UnitY();
  Vec3 lastDab_ = Vec3::Zero();
  int paintSeed_ = -1;
};

}  // namespace galsculpt
