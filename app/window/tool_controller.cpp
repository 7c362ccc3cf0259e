#include "app/window/tool_controller.h"

#include <algorithm>
#include <cmath>

namespace galsculpt {

ToolController::ToolController(SculptSession& session, OrbitCamera& camera,
                               const ToolSettings& settings)
    : session_(session), camera_(camera), settings_(settings) {}

void ToolController::setViewport(int width, int height) {
  width_ = std::max(width, 1);
  height_ = std::max(height, 1);
}

std::optional<RayHit> ToolController::pick(double x, double y) {
  const Simulation& sim = session_.simulation();
  const VisualSurface& surface = sim.surface();
  Vec3 origin, direction;
  camera_.ray(x, y, width_, height_, origin, direction);
  return picker_.intersect(surface.mesh, sim.state().damageRevision, sim.generation(), origin,
                           direction);
}

void ToolController::cutTo(double x, double y) {
  Vec3 origin, direction;
  camera_.ray(x, y, width_, height_, origin, direction);
  const Vec3 nearPoint = origin + knifeNear_ * direction, farPoint = origin + knifeFar_ * direction;
  knifeCut_ += session_.knife(bladeNear_, bladeFar_, nearPoint, farPoint, settings_.plane());
  bladeNear_ = nearPoint;
  bladeFar_ = farPoint;
}

void ToolController::paintTo(const RayHit& hit) {
  // Dabs at most half a radius apart from the last one to this hit.
  const double spacing = 0.5 * settings_.radius;
  const double length = (hit.point - lastDab_).norm();
  const int dabs = std::max(1, static_cast<int>(std::ceil(length / spacing)));
  const bool erase = settings_.tool == Tool::AnchorErase;
  const Vec3 from = lastDab_;
  for (int i = 1; i <= dabs; ++i) {
    const Vec3 p = from + (hit.point - from) * (static_cast<double>(i) / dabs);
    session_.paint(p, settings_.radius, i == dabs ? paintSeed_ : -1, erase, settings_.plane());
  }
  lastDab_ = hit.point;
}

void ToolController::mouseButton(MouseButton button, bool pressed, bool shift) {
  if (!pressed) {
    if (active_ == Active::Brush) session_.endStroke();
    if (active_ == Active::Knife && knifeCut_ == 0)
      notice_ = "the knife crossed no edge: drag it across the body";
    active_ = Active::None;
    return;
  }
  if (active_ != Active::None) return;  // one action at a time
  const bool navigate = settings_.tool == Tool::Navigate && button == MouseButton::Left;
  if (button == MouseButton::Middle || (button == MouseButton::Right && shift)) {
    active_ = Active::Pan;
    return;
  }
  if (button == MouseButton::Right || navigate) {
    active_ = Active::Orbit;
    return;
  }
  switch (toolRow(settings_.tool).kind) {
    case ToolKind::Navigate:
      break;
    case ToolKind::Knife: {
      // The blade reaches through the whole body along every ray: from in front of its
      // bounding sphere to behind it.
      const BoundingBox box = boundingBox(session_.simulation().state().x);
      const double radius = 0.5 * box.size().norm() * 1.05 + 1e-9;
      const double centerDepth = (box.center() - camera_.eye()).norm();
      knifeNear_ = std::max(1e-6, centerDepth - radius);
      knifeFar_ = centerDepth + radius;
      Vec3 origin, direction;
      camera_.ray(x_, y_, width_, height_, origin, direction);
      bladeNear_ = origin + knifeNear_ * direction;
      bladeFar_ = origin + knifeFar_ * direction;
      session_.beginAction(toolRow(settings_.tool).label);
      active_ = Active::Knife;
      knifeCut_ = 0;
      break;
    }
    case ToolKind::Paint: {
      const std::optional<RayHit> hit = pick(x_, y_);
      if (!hit) break;
      session_.beginAction(toolRow(settings_.tool).label);
      paintSeed_ = session_.simulation().surface().cellVertex[hit->face];
      lastDab_ = hit->point;
      session_.paint(hit->point, settings_.radius, paintSeed_, settings_.tool == Tool::AnchorErase,
                     settings_.plane());
      active_ = Active::Paint;
      break;
    }
    case ToolKind::Brush: {
      const std::optional<RayHit> hit = pick(x_, y_);
      if (!hit) break;
      session_.beginAction(toolRow(settings_.tool).label);
      BrushStroke stroke;
      stroke.kind = settings_.tool;
      stroke.center = hit->point;
      stroke.normal = hit->normal;
      stroke.radius = settings_.radius;
      stroke.strength = settings_.strength;
      stroke.seed = session_.simulation().surface().cellVertex[hit->face];
      stroke.symmetry = settings_.plane();
      session_.beginStroke(stroke);
      grabPoint_ = hit->point;
      grabNormal_ = camera_.forward();
      active_ = Active::Brush;
      break;
    }
  }
}

void ToolController::mouseMove(double x, double y) {
  const double dx = x - x_, dy = y - y_;
  x_ = x;
  y_ = y;
  switch (active_) {
    case Active::None:
      break;
    case Active::Orbit:
      camera_.orbit(-dx * 0.01, dy * 0.01);
      break;
    case Active::Pan:
      camera_.pan(dx / height_, dy / height_);
      break;
    case Active::Knife:
      if (dx != 0.0 || dy != 0.0) cutTo(x, y);
      break;
    case Active::Paint:
      if (const std::optional<RayHit> hit = pick(x, y)) paintTo(*hit);
      break;
    case Active::Brush:
      if (settings_.tool == Tool::Grab) {
        // The cursor drags the grabbed point on the plane through it that faces the camera.
        Vec3 origin, direction;
        camera_.ray(x, y, width_, height_, origin, direction);
        const double denominator = direction.dot(grabNormal_);
        if (std::abs(denominator) < 1e-9) break;
        const double t = (grabPoint_ - origin).dot(grabNormal_) / denominator;
        if (t > 0.0) session_.moveStroke(origin + t * direction, -grabNormal_);
      } else if (const std::optional<RayHit> hit = pick(x, y)) {
        session_.moveStroke(hit->point, hit->normal);
      }
      break;
  }
}

void ToolController::scroll(double steps) {
  if (steps != 0.0) camera_.zoom(std::pow(0.9, steps));
}

void ToolController::cancelStroke() {
  if (active_ == Active::Brush) session_.endStroke();
  active_ = Active::None;
}

}  // namespace galsculpt
