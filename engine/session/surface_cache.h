// A simulation's visualization surface (surface_builder.h), brought up to date when it is asked
// for after the positions or the damage changed, and shown without the debris the debris rule
// removed. Every reader (the window, exports, the metrics' inverted pieces) goes through it, so
// the surface is built once per state whoever asks first.
#pragma once

#include <cstdint>

#include "engine/session/body_pieces.h"
#include "engine/surface/surface_builder.h"

namespace galsculpt {

class SurfaceCache {
 public:
  explicit SurfaceCache(const SimModel& model) : builder_(model) {}

  // The surface at `state` as of `frame` (positions change only with the frame, the damage
  // with its revision: a second call for the same state reuses the surface); `stats`
  // (optional) gets what the update cost, zeros when nothing was to do.
  const VisualSurface& get(const SimModel& model, const SimState& state, int frame,
                           const BodyPieces& pieces, SurfaceUpdateStats* stats = nullptr);
  // The positions changed without a frame (a restore, a stopped frame).
  void invalidate() { frame_ = -1; }
  // What the last update cost, whoever asked for it.
  const SurfaceUpdateStats& lastUpdate() const { return lastUpdate_; }
  // The builder as of the last get (every removed piece included): exports build on it.
  const SurfaceBuilder& builder() const { return builder_; }

 private:
  SurfaceBuilder builder_;
  int frame_ = -1;  // the state the surface was last brought up to
  std::uint64_t revision_ = 0;
  SurfaceUpdateStats lastUpdate_;
  VisualSurface shown_;  // without removed debris (when there is any)
};

}  // namespace galsculpt
