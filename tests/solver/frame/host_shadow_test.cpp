// Host shadows (solver/frame/host_shadow.h): an unchanged array is not uploaded again; a
// changed one is; downloads come back through the shadows, two arrays behind one wait.
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
  CpuExecutor::Buffer<double> scalars;
  std::vector<double> scalarShadow;
  const std::vector<double> values = {8.0, 9.0, 10.0};
  uploadIfChanged(values, scalarShadow, scalars);
  scalars.data()[2] = 11.0;
  std::vector<Vec3> back(2);
  std::vector<double> backValues(3);
  const long waits = ex.counters().waits;
  downloadThroughShadows(ex, buffer, shadow, back, scalars, scalarShadow, backValues);
  EXPECT_EQ(ex.counters().waits, waits + 1) << "one wait for both";
  EXPECT_EQ(back[0], Vec3(-1, 2, 3));
  EXPECT_EQ(back[1], Vec3(4, 7, 6));
  EXPECT_EQ(backValues, (std::vector<double>{8.0, 9.0, 11.0}));
  EXPECT_EQ(shadow[0], -1.0) << "the shadow holds what the executor holds";
  EXPECT_EQ(scalarShadow[2], 11.0);
  EXPECT_FALSE(uploadIfChanged(back, shadow, buffer));
  EXPECT_FALSE(uploadIfChanged(backValues, scalarShadow, scalars));
}

}  // namespace
}  // namespace galsculpt
