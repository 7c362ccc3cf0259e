// The pieces of a body's damage, counted once per change of the damage for everything that
// reads them (the debris rule, the pieces' start, the residual piece by piece in the frame; the
// piece statistics and debris of the engine's Simulation): the census (debris.h) and the layout
// of the pieces and the elements between them (accelerated_start.h), each computed on first use
// after a change and kept until the next.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/fracture/debris.h"
#include "solver/frame/accelerated_start.h"
#include "solver/model/sim_model.h"

namespace galsculpt {

class PieceTracker {
 public:
  // `damaged` is `model`'s damage of `revision`: a caller hands the same revision only with the
  // same damage (any counter of its changes will do; it is compared, never ordered).
  const PieceCensus& census(const SimModel& model, const std::vector<std::uint8_t>& damaged,
                            std::uint64_t revision);
  // The layout's own revision (PieceLayout::revision) differs for every layout this tracker
  // makes, what the layout's device copies compare.
  const PieceLayout& layout(const SimModel& model, const std::vector<std::uint8_t>& damaged,
                            std::uint64_t revision);

 private:
  PieceCensus census_;
  std::uint64_t censusFor_ = ~std::uint64_t{0};
  PieceLayout layout_;
  std::uint64_t layoutFor_ = ~std::uint64_t{0};
};

}  // namespace galsculpt
