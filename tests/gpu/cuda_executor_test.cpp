// The CUDA executor's own machinery on a GPU (skipped, with the reason, where there is none).
#include <gtest/gtest.h>

#include "gpu/executor_check.h"

namespace galsculpt::gpu {
namespace {

// A loop whose test the device makes (loopOnDevice: a graph with a while node): it stops where
// its flag says, or at its cap, without a host wait, and its kernels are those of the passes
// made (the body's and the test's), counted after the fact. Launched twice: recorded, replayed.
TEST(CudaExecutor, ADeviceLoopStopsWhereItsFlagSaysWithoutAWait) {
  const LoopCheck five = checkDeviceLoop(5, 100);
  if (!five.ran) GTEST_SKIP() << "no usable GPU: " << five.reason;
  EXPECT_EQ(five.lastPasses, 5.0);
  EXPECT_EQ(five.waits, 1) << "the read of the count, nothing in the loop";
  EXPECT_EQ(five.graphs, 2);
  EXPECT_EQ(five.kernels, 2 * (2 + 2 * 5))
      << "each launch: the start, the entry's test, 5 passes of 2 kernels";
  const LoopCheck capped = checkDeviceLoop(50, 7);
  ASSERT_TRUE(capped.ran) << capped.reason;
  EXPECT_EQ(capped.lastPasses, 7.0);
  const LoopCheck none = checkDeviceLoop(5, 100, false);
  ASSERT_TRUE(none.ran) << none.reason;
  EXPECT_EQ(none.lastPasses, 0.0) << "the flag is tested before the first pass";
  EXPECT_EQ(none.kernels, 4) << "the start and the entry's test, twice";
}

}  // namespace
}  // namespace galsculpt::gpu
