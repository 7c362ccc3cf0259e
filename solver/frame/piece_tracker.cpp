#include "solver/frame/piece_tracker.h"

namespace galsculpt {

const PieceCensus& PieceTracker::census(const SimModel& model,
                                        const std::vector<std::uint8_t>& damaged,
                                        std::uint64_t revision) {
  if (censusFor_ != revision) {
    census_ = censusPieces(model, damaged);
    censusFor_ = revision;
  }
  return census_;
}

const PieceLayout& PieceTracker::layout(const SimModel& model,
                                        const std::vector<std::uint8_t>& damaged,
                                        std::uint64_t revision) {
  if (layoutFor_ != revision) {
    layout_ = pieceLayout(model, census(model, damaged, revision), damaged, layout_.revision + 1);
    layoutFor_ = revision;
  }
  return layout_;
}

}  // namespace galsculpt
