#include "engine/session/surface_cache.h"

namespace galsculpt {

const VisualSurface& SurfaceCache::get(const SimModel& model, const SimState& state, int frame,
                                       const BodyPieces& pieces, SurfaceUpdateStats* stats) {
  if (frame_ != frame || revision_ != state.damageRevision) {
    const SurfaceUpdateStats s = builder_.update(model, state);
    frame_ = frame;
    revision_ = state.damageRevision;
    lastUpdate_ = s;
    if (stats) *stats = s;
    if (pieces.removesSome()) shown_ = pieces.withoutRemoved(builder_.surface());
  } else if (stats) {
    *stats = SurfaceUpdateStats{};
  }
  return pieces.removesSome() ? shown_ : builder_.surface();
}

}  // namespace galsculpt
