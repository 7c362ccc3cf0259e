// The frame's damage (solver/frame/frame_damage.h): it follows a state by revision and by
// content (a backend may be handed several states under one revision), writes back only where
// the revision differs, and takes a fracture pass's breaks from the executor.
#include "solver/frame/frame_damage.h"

#include <gtest/gtest.h>

#include "solver/frame/cpu_executor.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

MaterialParams rubber() {
  return {MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e5, 0.45), 1000.0, {}};
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
