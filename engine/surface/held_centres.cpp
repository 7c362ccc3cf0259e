// SurfaceBuilder::heldCentres: what the export separates crack sides towards.
#include "engine/surface/surface_builder.h"

namespace galsculpt {

std::vector<Vec3> SurfaceBuilder::heldCentres(const SimState& state) const {
  const std::vector<Vec3>& positions = surface_.mesh.vertices;
  std::vector<Vec3> centres(positions.size());
  for (size_t i = 0; i < placements_.size(); ++i) {
    const Placement& p = placements_[i];
    if (p.count == 0 || p.mask == (1u << p.count) - 1) {
      centres[i] = positions[i];
      continue;
    }
    Vec3 sum = Vec3::Zero();
    int held = 0;
    for (int k = 0; k < p.count; ++k) {
      if (!(p.mask & (1u << k))) continue;
      sum += state.x[p.support[k]];
      ++held;
    }
    centres[i] = sum / held;
  }
  return centres;
}

}  // namespace galsculpt
