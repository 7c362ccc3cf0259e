#include "engine/session/sculptor.h"

#include <algorithm>
#include <stdexcept>

namespace galsculpt {

namespace {

double falloff(double distance, double radius) {
  const double s = 1.0 - (distance * distance) / (radius * radius);
  return s > 0.0 ? s * s : 0.0;
}

Vec3 closestOnSegment(const Vec3& a, const Vec3& b, const Vec3& p) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 <= 0.0) return a;
  return a + std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) * ab;
}

}  // namespace

Vec3 Symmetry::point(const Vec3& p) const {
  Vec3 q = p;
  if (enabled()) q[axis] = 2.0 * offset - p[axis];
  return q;
}

Vec3 Symmetry::direction(const Vec3& d) const {
  Vec3 q = d;
  if (enabled()) q[axis] = -d[axis];
  return q;
}

int Sculptor::cut(const std::vector<BladeTriangle>& blade, const Symmetry& symmetry) {
  int n = sim_.cut(blade);
  if (symmetry.enabled()) {
    std::vector<BladeTriangle> mirrored;
    mirrored.reserve(blade.size());
    for (const BladeTriangle& t : blade)
      mirrored.push_back({symmetry.point(t.a), symmetry.point(t.b), symmetry.point(t.c)});
    n += sim_.cut(mirrored);
  }
  return n;
}

void Sculptor::selectUnderBrush(const Vec3& a, const Vec3& b, double radius, int seed,
                                std::vector<int>& vertices, std::vector<double>& weights) const {
  vertices.clear();
  weights.clear();
  if (seed < 0) seed = sim_.nearestVertex(b);
  const int piece = sim_.pieceOf(seed);
  const std::vector<Vec3>& x = sim_.state().x;
  for (int v = 0; v < sim_.model().numVertices(); ++v) {
    if (sim_.pieceOf(v) != piece) continue;
    const double w = falloff((x[v] - closestOnSegment(a, b, x[v])).norm(), radius);
    if (w <= 0.0) continue;
    vertices.push_back(v);
    weights.push_back(w);
  }
}

void Sculptor::beginBrush(const BrushStroke& stroke) {
  if (toolRow(stroke.kind).kind != ToolKind::Brush)
    throw std::invalid_argument(std::string(toolRow(stroke.kind).name) + " is not a brush (" +
                                toolNames(ToolKind::Brush) + ")");
  endBrush();
  stroke_ = stroke;
  strokeReach_ = 0;
  const int sides = stroke.symmetry.enabled() ? 2 : 1;
  for (int s = 0; s < sides; ++s) {
    Side side;
    side.mirrored = s == 1;
    side.center = side.mirrored ? stroke.symmetry.point(stroke.center) : stroke.center;
    side.normal = side.mirrored ? stroke.symmetry.direction(stroke.normal) : stroke.normal;
    // A brush on the mirror plane is its own image: act once.
    if (side.mirrored && (side.center - stroke.center).norm() < 0.5 * stroke.radius) break;
    side.startCenter = side.previousCenter = side.center;
    side.seed = side.mirrored || stroke.seed < 0 ? sim_.nearestVertex(side.center) : stroke.seed;
    if (stroke.kind == Tool::Grab) {
      selectUnderBrush(side.center, side.center, stroke.radius, side.seed, side.vertices,
                       side.weights);
      strokeReach_ += static_cast<int>(side.vertices.size());
      if (!side.vertices.empty()) {
        side.anchor = sim_.anchors().add(side.vertices);
        for (int v : side.vertices) side.start.push_back(sim_.state().x[v]);
      }
    }
    sides_.push_back(std::move(side));
  }
}

void Sculptor::moveBrush(const Vec3& center, const Vec3& normal) {
  for (Side& side : sides_) {
    side.center = side.mirrored ? stroke_.symmetry.point(center) : center;
    side.normal = side.mirrored ? stroke_.symmetry.direction(normal) : normal;
    if (stroke_.kind != Tool::Grab || side.anchor < 0) continue;
    const Vec3 offset = side.center - side.startCenter;
    std::vector<Vec3> targets(side.vertices.size());
    for (size_t i = 0; i < side.vertices.size(); ++i) targets[i] = side.start[i] + offset;
    sim_.anchors().setTargets(side.anchor, targets);
  }
}

void Sculptor::endBrush() {
  for (const Side& side : sides_)
    if (side.anchor >= 0) sim_.anchors().remove(side.anchor);
  sides_.clear();
}

Vec3 Sculptor::brushDirection(const Side& side, const Vec3& x, const Vec3& nearest) const {
  switch (stroke_.kind) {
    case Tool::Push:
      return -side.normal;
    case Tool::Pull:
      return side.normal;
    case Tool::Inflate: {
      const Vec3 d = x - (nearest - stroke_.radius * side.normal);
      const double len = d.norm();
      return len > 0.0 ? Vec3(d / len) : side.normal;
    }
    case Tool::Pinch: {
      Vec3 d = nearest - x;
      d -= d.dot(side.normal) * side.normal;  // towards the axis, not into the surface
      return d / stroke_.radius;
    }
    default:  // grab moves what it holds with it; the other tools are no brushes
      break;
  }
  return Vec3::Zero();
}

void Sculptor::beforeFrame() {
  if (stroke_.kind == Tool::Grab) return;
  const double step = stroke_.strength * sim_.settings().dt;
  for (Side& side : sides_) {
    const Vec3 from = side.previousCenter;
    side.previousCenter = side.center;
    selectUnderBrush(from, side.center, stroke_.radius, side.seed, side.vertices, side.weights);
    strokeReach_ += static_cast<int>(side.vertices.size());
    if (side.vertices.empty()) {  // nothing under the brush this frame: it holds nothing
      if (side.anchor >= 0) sim_.anchors().remove(side.anchor);
      side.anchor = -1;
      continue;
    }
    const std::vector<Vec3>& x = sim_.state().x;
    std::vector<Vec3> targets(side.vertices.size());
    std::map<int, Vec3> kept;
    for (size_t i = 0; i < side.vertices.size(); ++i) {
      const int v = side.vertices[i];
      const Vec3& p = x[v];
      const auto was = side.targets.find(v);
      const Vec3 nearest = closestOnSegment(from, side.center, p);
      targets[i] = (was == side.targets.end() ? p : was->second) +
                   side.weights[i] * step * brushDirection(side, p, nearest);
      kept.emplace(v, targets[i]);
    }
    side.targets = std::move(kept);
    // The stroke's one anchor, reshaped each frame (its id and place among the anchors kept).
    if (side.anchor < 0) side.anchor = sim_.anchors().add(side.vertices);
    sim_.anchors().reshape(side.anchor, side.vertices, std::move(targets), side.weights);
  }
}

int Sculptor::paintAnchors(const Vec3& center, double radius, int seed, bool erase,
                           const Symmetry& symmetry) {
  std::vector<int> vertices, mirrored;
  std::vector<double> weights;
  selectUnderBrush(center, center, radius, seed, vertices, weights);
  if (symmetry.enabled()) {
    const Vec3 image = symmetry.point(center);
    selectUnderBrush(image, image, radius, -1, mirrored, weights);
    vertices.insert(vertices.end(), mirrored.begin(), mirrored.end());
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  }
  if (erase) return sim_.anchors().unanchor(vertices);
  const std::vector<int> held = sim_.anchors().heldVertices();
  std::vector<int> fresh;
  std::set_difference(vertices.begin(), vertices.end(), held.begin(), held.end(),
                      std::back_inserter(fresh));
  if (!fresh.empty()) sim_.anchors().add(fresh);
  return static_cast<int>(fresh.size());
}

}  // namespace galsculpt
