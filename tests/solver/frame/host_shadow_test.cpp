// Host shadows (solver/frame/host_shadow.h): an unchanged array is not uploaded again; a
// changed one is; a download comes back through the shadow.
#include <gtest/gtest.h>

#include "solver/frame/cpu_executor.h"
#include "solver/frame/host_shadow.h"
#include "solver/mesh/tet_mesh.h"

namespace galsculpt {
namespace {

TEST(HostShadow, UploadsOnlyWhatChangedAndDownloadsThroughIt) {
  CpuExecutor ex;
  CpuExecutor::Buffer<double> buffer;
  std::vector<double> shadow;
  std::vector<Vec3> x = {Vec3(1, 2, 3), Vec3(4, 5, 6)};
  EXPECT_TRUE(uploadIfChanged(x, shadow, buffer));
  ASSERT_EQ(buffer.size(), 6u);
  EXPECT_EQ(buffer.data()[4], 5.0);
  EXPECT_FALSE(uploadIfChanged(x, shadow, buffer)) << "the same content";
  x[1].y() = 7.0;
  EXPECT_TRUE(uploadIfChanged(x, shadow, buffer));
  EXPECT_EQ(buffer.data()[4], 7.0);
  buffer.data()[0] = -1.0;  // what a frame did on the executor
  std::vector<Vec3> back(2);
  downloadThroughShadow(ex, buffer, shadow, back);
  EXPECT_EQ(back[0], Vec3(-1, 2, 3));
  EXPECT_EQ(back[1], Vec3(4, 7, 6));
  EXPECT_EQ(shadow[0], -1.0) << "the shadow holds what the executor holds";
  EXPECT_FALSE(uploadIfChanged(back, shadow, buffer));
}

}  // namespace
}  // namespace galsculpt
