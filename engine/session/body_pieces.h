// The body's pieces as its damage left them, for the engine: which piece each vertex lies in,
// which pieces are debris (fracture.debris_fraction) and whether the debris rule removes them,
// and the volumes the metrics count over. A Simulation owns one and brings it up to date when
// the damage changes; the solver keeps its own census for the frame (piece_tracker.h).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/surface/surface_builder.h"
#include "solver/frame/piece_tracker.h"
#include "solver/model/sim_model.h"

namespace galsculpt {

class BodyPieces {
 public:
  // `debrisFraction`: pieces under this fraction of the body's rest volume are debris;
  // `removesDebris`: fracture.debris: remove (hidden from surfaces and exports).
  BodyPieces(double debrisFraction, bool removesDebris)
      : debrisFraction_(debrisFraction), removesDebris_(removesDebris) {}

  // Counts the pieces of the state's damage; nothing to do when its revision was counted last.
  void update(const SimModel& model, const SimState& state);

  int count() const { return pieces_; }
  // The number of the piece (part joined by undamaged edges) `vertex` lies in.
  int of(int vertex) const { return pieceNumber_[vertex]; }
  const std::vector<int>& ofVertices() const { return pieceNumber_; }
  // Whether `vertex` lies in debris that the debris rule removed.
  bool removed(int vertex) const { return removesDebris_ && debrisPiece_[pieceNumber_[vertex]]; }
  // Whether some debris is removed now (surfaces and exports leave it out).
  bool removesSome() const { return removesDebris_ && debrisPieces_ > 0; }
  int debrisPieces() const { return debrisPieces_; }
  double debrisMassKg() const { return debrisMass_; }
  // The rest volume the debris holds, % of the body's (every tet's, damaged or not).
  double debrisVolumePercent() const {
    return bodyRestVolume_ > 0.0 ? 100.0 * debrisRestVolume_ / bodyRestVolume_ : 0.0;
  }

  // A tet whose corners lie in different pieces is no longer material (its vertices have
  // parted): volumes count only the tets inside one piece, at rest and now alike.
  bool counted(int tet) const { return countedTets_[tet]; }
  double restVolume() const { return restVolume_; }
  double currentVolume(const SimModel& model, const std::vector<Vec3>& x) const;

  // Pieces whose closed surface (`surface`, at the current damage) encloses no positive volume;
  // removed debris is no piece to look at. 0 while the body is one piece.
  int invertedPieces(const VisualSurface& surface) const;
  // `all` less the faces of removed debris.
  VisualSurface withoutRemoved(const VisualSurface& all) const;

 private:
  double debrisFraction_;
  bool removesDebris_;
  std::uint64_t revision_ = ~0ull;
  PieceTracker tracker_;
  int pieces_ = 1;
  std::vector<int> pieceNumber_;           // each vertex's piece, numbered 0 .. pieces_ - 1
  std::vector<std::uint8_t> debrisPiece_;  // (pieces_) 1 for debris
  std::vector<std::uint8_t> countedTets_;
  int debrisPieces_ = 0;
  double debrisRestVolume_ = 0.0, debrisMass_ = 0.0;  // m^3, kg
  double bodyRestVolume_ = 0.0, restVolume_ = 0.0;    // every tet's; the counted tets'
};

}  // namespace galsculpt
