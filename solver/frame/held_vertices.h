// The vertices a sub-step does not solve for: anchored ones, moved along their paths to the
// sub-step's end, and removed debris (solver/fracture/debris.h), held where the state has them.
// Computed on the host when the anchors or the removed debris changed, or when an anchor's path
// moves it (not at every sub-step: a brush changes its anchor once a frame), and uploaded only
// where they changed: the held flags (fixed), the removed flags, and the anchored and removed
// vertices' targets in the frame's data.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "solver/fem/dense_kernels.h"
#include "solver/fracture/debris.h"
#include "solver/frame/frame_data.h"
#include "solver/frame/step.h"
#include "solver/model/sim_model.h"

namespace galsculpt {

template <typename Exec>
class HeldVertexSet {
 public:
  HeldVertexSet(Exec& ex, const SimModel& model, FrameData<Exec>& data)
      : ex_(ex), model_(model), d_(data) {}

  // The debris rule: the vertices of pieces under model.debrisRemoval of the body's rest volume
  // (in `census`, of the current damage) are held where they are, out of the solve, and the
  // elements around them stop pushing back on the rest of the body.
  void updateRemovedDebris(const PieceCensus& census) {
    std::vector<std::uint8_t> removed = debrisVertices(census, model_.debrisRemoval);
    if (removed.empty()) removed.assign(d_.n, 0);
    if (removed == hostRemoved_) return;
    hostRemoved_ = std::move(removed);
    removedChanged_ = true;
    d_.removed.upload(hostRemoved_);
    removedVertices_.clear();
    for (int v = 0; v < d_.n; ++v)
      if (hostRemoved_[v]) removedVertices_.push_back(v);
  }

  // Removed debris stays where `state` has it (a backend may step several states).
  void holdRemovedAt(const SimState& state) {
    std::vector<double> targets;
    targets.reserve(3 * removedVertices_.size());
    for (int v : removedVertices_)
      targets.insert(targets.end(), {state.x[v].x(), state.x[v].y(), state.x[v].z()});
    if (targets == removedTargets_) return;
    removedTargets_ = std::move(targets);
    removedChanged_ = true;
  }

  // The held vertices and their targets at `time` (the sub-step's end), and the soft anchors'
  // springs: a vertex two springs pull goes to their stiffness-weighted target.
  void prepare(const std::vector<AnchorConstraint>& anchors, double time) {
    // Nothing moved since the last prepare (the same anchors, none on a path, the same removed
    // debris): what the executor holds stands. The anchors are compared by content (a backend
    // may step several states): what they hold, not the body.
    const bool onPaths = std::any_of(anchors.begin(), anchors.end(),
                                     [](const AnchorConstraint& a) { return !a.path.empty(); });
    if (prepared_ && !onPaths && !removedChanged_ && sameAnchors(anchors, preparedAnchors_)) return;
    prepared_ = true;
    removedChanged_ = false;
    preparedAnchors_ = anchors;
    std::vector<std::uint8_t> fixed(d_.n, 0);
    std::vector<int> vertices;
    std::vector<double> targets;
    std::vector<double> springK(d_.n, 0.0), springTarget(3 * static_cast<size_t>(d_.n), 0.0);
    for (const AnchorConstraint& a : anchors) {
      const Vec3 offset = anchorOffset(a, time);
      for (size_t i = 0; i < a.vertices.size(); ++i) {
        const int v = a.vertices[i];
        const Vec3 p = (a.origin.empty() ? model_.mesh.vertices[v] : a.origin[i]) + offset;
        if (!a.springWeights.empty()) {
          const double k = a.springWeights[i] * kAnchorSpring * model_.material.lame.mu *
                           std::cbrt(model_.mass[v] / model_.material.density);
          springK[v] += k;
          for (int c = 0; c < 3; ++c) springTarget[3 * v + c] += k * p[c];
          continue;
        }
        fixed[v] = 1;
        vertices.push_back(v);
        targets.insert(targets.end(), {p.x(), p.y(), p.z()});
      }
    }
    for (int v = 0; v < d_.n; ++v)
      if (springK[v] > 0.0)
        for (int c = 0; c < 3; ++c) springTarget[3 * v + c] /= springK[v];
    uploadChanged(springK, hostSpringK_, d_.springK);
    uploadChanged(springTarget, hostSpringTarget_, d_.springTarget);
    for (size_t i = 0; i < removedVertices_.size(); ++i) {
      const int v = removedVertices_[i];
      if (fixed[v]) continue;  // an anchor keeps it on its path
      fixed[v] = 1;
      vertices.push_back(v);
      targets.insert(targets.end(), removedTargets_.begin() + 3 * i,
                     removedTargets_.begin() + 3 * i + 3);
    }
    uploadChanged(fixed, hostFixed_, d_.fixed);
    d_.anchorCount = vertices.size();
    uploadChanged(vertices, hostAnchorVertices_, d_.anchorVertices);
    uploadChanged(targets, hostAnchorTargets_, d_.anchorTargets);
  }

  // The anchored vertices on their paths at the sub-step's end (in x).
  void place() {
    double* x = d_.x.data();
    const int* anchorVertex = d_.anchorVertices.data();
    const double* anchorTarget = d_.anchorTargets.data();
    ex_.forEach(static_cast<int>(d_.anchorCount), [=] GALSCULPT_LAMBDA(int i) {
      for (int k = 0; k < 3; ++k) x[3 * anchorVertex[i] + k] = anchorTarget[3 * i + k];
    });
  }

 private:
  static bool sameAnchors(const std::vector<AnchorConstraint>& a,
                          const std::vector<AnchorConstraint>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
      if (a[i].vertices != b[i].vertices || a[i].origin != b[i].origin ||
          a[i].springWeights != b[i].springWeights || !a[i].path.empty() || !b[i].path.empty())
        return false;
    return true;
  }

  // Uploads `values` to the executor's `buffer` when they differ from its host shadow.
  template <typename T, typename Buffer>
  static void uploadChanged(const std::vector<T>& values, std::vector<T>& shadow, Buffer& buffer) {
    if (values == shadow) return;
    shadow = values;
    buffer.upload(shadow);
  }

  Exec& ex_;
  const SimModel& model_;
  FrameData<Exec>& d_;
  // Host shadows: what the executor holds, to upload only changes.
  std::vector<std::uint8_t> hostFixed_, hostRemoved_;
  std::vector<int> hostAnchorVertices_;
  std::vector<double> hostAnchorTargets_;
  std::vector<double> hostSpringK_, hostSpringTarget_;
  std::vector<int> removedVertices_;    // ascending
  std::vector<double> removedTargets_;  // (3 per removed vertex) where each is held
  bool prepared_ = false;
  bool removedChanged_ = false;  // the removed debris or its targets, since the last prepare
  std::vector<AnchorConstraint> preparedAnchors_;  // the anchors of the last prepare
};

}  // namespace galsculpt
