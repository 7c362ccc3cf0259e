// What a scene's `measure` asks to read after each frame (docs/scenes.md): the opening between
// two vertices (Charpy's crack-mouth opening), the load on one collider (with the striker's
// travel and, for a rigid pendulum, the energy the body absorbed) or on one scene anchor.
#pragma once

#include <vector>

#include "engine/scene/scene.h"
#include "engine/session/anchor_registry.h"
#include "solver/frame/frame_statistics.h"

namespace galsculpt {

struct FrameMetrics;

class FrameProbes {
 public:
  // The opening's vertices are the mesh's nearest to the scene's rest points.
  FrameProbes(const MeasureDesc& measure, const TetMesh& mesh);
  // Fills the metrics' openingM, loadN, strikerDisplacementM and absorbedEnergyJ from the state
  // after a frame and its contact forces.
  void read(const SimModel& model, const SimState& state, const AnchorRegistry& anchors,
            const std::vector<Vec3>& contactForces, FrameMetrics& m) const;

 private:
  std::vector<int> openingVertices_;  // the two probed vertices
  int loadCollider_ = -1;
  int loadAnchor_ = -1;  // a scene anchor
};

}  // namespace galsculpt
