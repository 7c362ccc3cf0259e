#include "solver/io/memory_limits.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <string>

#include "tests/test_util.h"

namespace galsculpt {
namespace {

TEST(MemoryLimits, BytesAreSaidInDecimalUnits) {
  EXPECT_EQ(bytesText(512), "512 B");
  EXPECT_EQ(bytesText(3100), "3.1 kB");
  EXPECT_EQ(bytesText(512e6), "512 MB");
  EXPECT_EQ(bytesText(20.4e9), "20 GB");
  EXPECT_EQ(bytesText(2.5e13), "25 TB");
}

TEST(MemoryLimits, TheAddressSpaceLimitBoundsWhatIsAvailable) {
  const std::optional<std::uint64_t> before = availableMemoryBytes();
  ASSERT_TRUE(before.has_value()) << "Linux has /proc/meminfo";
  EXPECT_GT(*before, 0u);
  // ulimit -v at what is mapped now plus 64 MB: about 64 MB is left.
  const std::uint64_t mapped = test::mappedBytes();
  ASSERT_GT(mapped, 0u);
  rlimit old{};
  ASSERT_EQ(getrlimit(RLIMIT_AS, &old), 0);
  rlimit tight = old;
  tight.rlim_cur = mapped + (64u << 20);
  if (old.rlim_max != RLIM_INFINITY && tight.rlim_cur > old.rlim_max) GTEST_SKIP();
  ASSERT_EQ(setrlimit(RLIMIT_AS, &tight), 0);
  const std::optional<std::uint64_t> limited = availableMemoryBytes();
  ASSERT_EQ(setrlimit(RLIMIT_AS, &old), 0);
  ASSERT_TRUE(limited.has_value());
  EXPECT_LE(*limited, 64u << 20);
  EXPECT_GT(*limited, 32u << 20);
  EXPECT_NE(availableMemoryText().find("is available"), std::string::npos);
}

}  // namespace
}  // namespace galsculpt
