// The pieces counted once per damage change (solver/frame/piece_tracker.h): what the tracker
// hands back is the census and layout of the damage it was given, kept while the key is the
// same and made again when it changes.
#include <gtest/gtest.h>

#include "solver/frame/piece_tracker.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

MaterialParams rubber() {
  return {MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e5, 0.45), 1000.0, {}};
}

TEST(PieceTracker, CountsOncePerKeyAndAgainWhenItChanges) {
  const SimModel m = buildSimModel(test::gridBar(8, 2, 2, 0.01), rubber());
  SimState s = initialState(m);
  PieceTracker tracker;
  EXPECT_EQ(tracker.census(m, s.damaged, 1).pieces, 1);
  const PieceLayout& whole = tracker.layout(m, s.damaged, 1);
  EXPECT_EQ(whole.pieces(), 1);
  const std::uint64_t wholeRevision = whole.revision;
  cutAt(m, s, 0.025);
  // The same key: the damage is taken to be the same (nothing is counted again).
  EXPECT_EQ(tracker.census(m, s.damaged, 1).pieces, 1);
  EXPECT_EQ(tracker.layout(m, s.damaged, 1).revision, wholeRevision);
  // A new key: the cut's two pieces, the layout's revision new, as pieceLayout makes them.
  EXPECT_EQ(tracker.census(m, s.damaged, 2).pieces, 2);
  const PieceLayout& cut = tracker.layout(m, s.damaged, 2);
  EXPECT_NE(cut.revision, wholeRevision);
  const PieceLayout direct = pieceLayout(m, s.damaged);
  EXPECT_EQ(cut.pieceStart, direct.pieceStart);
  EXPECT_EQ(cut.pieceVertices, direct.pieceVertices);
  EXPECT_EQ(cut.sharedTets, direct.sharedTets);
  EXPECT_EQ(cut.couplingSlot, direct.couplingSlot);
}

}  // namespace
}  // namespace galsculpt
