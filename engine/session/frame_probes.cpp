#include "engine/session/frame_probes.h"

#include "engine/session/simulation.h"
#include "solver/fem/colliders.h"
#include "solver/frame/step.h"

namespace galsculpt {

FrameProbes::FrameProbes(const MeasureDesc& measure, const TetMesh& mesh)
    : loadCollider_(measure.loadCollider), loadAnchor_(measure.loadAnchor) {
  for (const Vec3& p : measure.opening) {
    int best = 0;
    for (int v = 1; v < mesh.numVertices(); ++v) {
      if ((mesh.vertices[v] - p).squaredNorm() < (mesh.vertices[best] - p).squaredNorm()) best = v;
    }
    openingVertices_.push_back(best);
  }
}

void FrameProbes::read(const SimModel& model, const SimState& state, const AnchorRegistry& anchors,
                       const std::vector<Vec3>& contactForces, FrameMetrics& m) const {
  if (loadCollider_ >= 0 && loadCollider_ < static_cast<int>(contactForces.size())) {
    m.loadN = contactForces[loadCollider_].norm();
    const Collider& c = model.colliders[loadCollider_];
    const ColliderState& now = state.colliders[loadCollider_];
    m.strikerDisplacementM = (colliderCentre(c, state.time, &now) - c.center).norm();
    if (c.motion.rigidPendulum())
      m.absorbedEnergyJ = pendulumEnergy(c, initialColliderState(c), model.gravity) -
                          pendulumEnergy(c, now, model.gravity);
  }
  // The elastic force the body exerts on the scene anchor's vertices (0 once it is removed).
  if (loadAnchor_ >= 0) {
    const AnchorConstraint* grip = anchors.find(-loadAnchor_ - 1);
    m.loadN = grip ? elasticGradientSum(model, state.x, state, grip->vertices).norm() : 0.0;
  }
  if (openingVertices_.size() == 2) {
    const int a = openingVertices_[0], b = openingVertices_[1];
    m.openingM =
        (state.x[a] - state.x[b]).norm() - (model.mesh.vertices[a] - model.mesh.vertices[b]).norm();
  }
}

}  // namespace galsculpt
