// The CUDA executor's own machinery on a GPU (skipped, with the reason, where there is none).
#include <gtest/gtest.h>

#include "gpu/executor_check.h"

namespace galsculpt::gpu {
namespace {

// A loop whose test the device makes, with programs off (loopOnDevice: a graph with a while
// node): it stops where its flag says, or at its cap, without a host wait, and its kernels are
// those of the passes made (the body's and the test's), counted after the fact. Launched twice:
// recorded, replayed.
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

// The same loop in a device program: both launches and their loops are one kernel, and its
// barriers are the phases passed (each launch: the start, the entry, 5 passes of the body and
// the test), as the device-like executor counts them.
TEST(CudaExecutor, ADeviceProgramLoopsInsideOneKernel) {
  const LoopCheck five = checkDeviceLoop(5, 100, true, true);
  if (!five.ran) GTEST_SKIP() << "no usable GPU: " << five.reason;
  if (!five.programs) GTEST_SKIP() << "this GPU cannot launch cooperatively";
  EXPECT_EQ(five.lastPasses, 5.0);
  EXPECT_EQ(five.waits, 1);
  EXPECT_EQ(five.kernels, 1);
  EXPECT_EQ(five.barriers, 2 * (2 + 2 * 5));
  const LoopCheck capped = checkDeviceLoop(50, 7, true, true);
  ASSERT_TRUE(capped.ran) << capped.reason;
  EXPECT_EQ(capped.lastPasses, 7.0);
  const LoopCheck none = checkDeviceLoop(5, 100, false, true);
  ASSERT_TRUE(none.ran) << none.reason;
  EXPECT_EQ(none.lastPasses, 0.0) << "the flag is tested before the first pass";
  EXPECT_EQ(none.barriers, 4);
}

// A device program gives the bits of a kernel per launch: sums and maxima over sizes around
// the block and grid edges (the same partition of the items), a copy, and a loop whose passes
// reduce and decide; all of it one kernel.
TEST(CudaExecutor, ADeviceProgramGivesTheBitsOfAKernelPerLaunch) {
  const ProgramCheck check = checkDeviceProgram();
  if (!check.ran) GTEST_SKIP() << "no usable GPU: " << check.reason;
  if (!check.programs) GTEST_SKIP() << "this GPU cannot launch cooperatively";
  ASSERT_EQ(check.fused.size(), check.separate.size());
  for (size_t k = 0; k < check.fused.size(); ++k)
    EXPECT_EQ(check.fused[k], check.separate[k]) << "result " << k;
  EXPECT_EQ(check.fused[21], 9.0) << "the loop's passes";
  EXPECT_EQ(check.fusedKernels, 1);
  EXPECT_GT(check.separateKernels, 30);
  EXPECT_EQ(check.fusedBarriers, 1 + 3 * 2 * 5 + 1 + 1 + 1 + 9 * (2 + 1 + 1));
}

}  // namespace
}  // namespace galsculpt::gpu
