// The pieces counted once per damage change (solver/frame/piece_tracker.h) and the frame's
// damage (solver/frame/frame_damage.h): what they hand back is the census and layout of the
// damage they were given, kept while the key is the same and made again when it changes; the
// frame's damage follows a state by revision and by content, and a fracture pass's breaks.
#include <gtest/gtest.h>

#include "solver/frame/cpu_executor.h"
#include "solver/frame/frame_damage.h"
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

TEST(FrameDamage, FollowsTheStateByRevisionAndByContent) {
  const SimModel m = buildSimModel(test::gridBar(8, 2, 2, 0.01), rubber());
  SimState s = initialState(m);
  FrameData<CpuExecutor> data(m);
  FrameDamage<CpuExecutor> damage(m, data);
  EXPECT_TRUE(damage.syncIn(s));
  EXPECT_FALSE(damage.syncIn(s)) << "the same revision and content";
  const std::uint64_t changes = damage.changes();
  ++s.damageRevision;
  EXPECT_TRUE(damage.syncIn(s)) << "a new revision";
  EXPECT_EQ(damage.changes(), changes) << "the content did not change";
  // Another state under the same revision with other damage (an undo snapshot): taken.
  SimState other = s;
  cutAt(m, other, 0.025);
  other.damageRevision = s.damageRevision;
  EXPECT_TRUE(damage.syncIn(other));
  EXPECT_EQ(damage.changes(), changes + 1);
  EXPECT_EQ(damage.pieces().pieces(), 2);
  std::vector<std::uint8_t> onDevice(m.numEdges());
  data.damaged.download(onDevice.data(), onDevice.size());
  EXPECT_EQ(onDevice, other.damaged);
  // Written back only where the revision differs.
  SimState out = s;
  damage.syncOut(out);
  EXPECT_EQ(out.damaged, s.damaged);
}

TEST(FrameDamage, TakesTheBreaksMarkedOnTheExecutor) {
  const SimModel m = buildSimModel(test::gridBar(8, 2, 2, 0.01), rubber());
  SimState s = initialState(m);
  FrameData<CpuExecutor> data(m);
  FrameDamage<CpuExecutor> damage(m, data);
  damage.syncIn(s);
  SimState cut = s;
  cutAt(m, cut, 0.045);
  data.damaged.upload(cut.damaged);  // what a fracture pass marks
  const std::uint64_t revision = damage.revision(), changes = damage.changes();
  EXPECT_EQ(damage.takeBreaks(), 0) << "a clean cut parts nothing more";
  EXPECT_EQ(damage.host(), cut.damaged);
  EXPECT_EQ(damage.revision(), revision + 1);
  EXPECT_EQ(damage.changes(), changes + 1);
  EXPECT_EQ(damage.pieces().pieces(), 2);
  SimState out = s;
  damage.syncOut(out);
  EXPECT_EQ(out.damaged, cut.damaged);
  EXPECT_EQ(out.damageRevision, revision + 1);
}

}  // namespace
}  // namespace galsculpt
