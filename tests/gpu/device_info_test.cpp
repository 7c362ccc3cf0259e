#include "gpu/device_info.h"

#include <gtest/gtest.h>

namespace galsculpt::gpu {
namespace {

// Runs everywhere: without a GPU the query must say so with a reason, never crash or throw.
TEST(DeviceInfo, QueryNeverThrowsAndExplainsAbsence) {
  const DeviceInfo info = queryDevice();
  if (info.available) {
    EXPECT_FALSE(info.name.empty());
    EXPECT_GE(info.computeMajor, 7);
    EXPECT_GT(info.memoryBytes, 0u);
  } else {
    EXPECT_FALSE(info.reason.empty());
  }
}

}  // namespace
}  // namespace galsculpt::gpu
