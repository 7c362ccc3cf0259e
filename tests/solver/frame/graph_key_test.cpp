// The key of a captured section (solver/frame/graph_key.h): every setting a captured step reads
// changes it, and so does the order of what it mixes.
#include "solver/frame/graph_key.h"

#include <gtest/gtest.h>

#include <vector>

namespace galsculpt {
namespace {

TEST(GraphKey, EverySettingACapturedStepReadsChangesTheKey) {
  const StepSettings base;
  const auto key = [](const StepSettings& s) { return GraphKey().mixSettings(s).value(); };
  EXPECT_EQ(key(base), key(base));
  std::vector<StepSettings> changed(8, base);
  changed[0].newtonIterations += 1;
  changed[1].fineSweeps += 1;
  changed[2].cycles += 1;
  changed[3].coarseIterations += 1;
  changed[4].smoother = Smoother::Jacobi;
  changed[5].pcgTolerance = 1e-3;  // (the device's smoother under PCG)
  changed[6].stiffnessTolerance += 1e-3;
  changed[7].reuseStiffness = !base.reuseStiffness;
  for (size_t i = 0; i < changed.size(); ++i) EXPECT_NE(key(changed[i]), key(base)) << i;
  EXPECT_NE(GraphKey().mixDouble(0.01).value(), GraphKey().mixDouble(0.02).value());
  EXPECT_NE(GraphKey().mix(1).mix(2).value(), GraphKey().mix(2).mix(1).value());
}

// A captured section's key is the launch key (solver/fem/launch_key.h) of what it mixes, the
// key a device loop uses: one hash for every recording.
TEST(GraphKey, IsTheLaunchKeyOfWhatItMixes) {
  const double value = 0.5;
  EXPECT_EQ(GraphKey().mix(7).mixDouble(value).mixPointer(&value).value(),
            LaunchKey().mix(7).mixDouble(value).mixPointer(&value).value());
  EXPECT_NE(LaunchKey().value(), LaunchKey().mix(0).value()) << "a word mixed is a word more";
}

// A plain struct's bytes, word by word (what a device loop's key mixes of a launch's argument):
// the same bytes the same key, a field changed another, the tail past the last word too.
TEST(LaunchKey, MixesAStructsBytesWordByWord) {
  struct Arguments {
    const int* pointer;
    double value;
    int count;
    char tail[3];
  };
  const int storage[2] = {1, 2};
  Arguments a{storage, 2.5, 7, {'a', 'b', 'c'}};
  Arguments b = a;
  EXPECT_EQ(LaunchKey().mixBytes(a).value(), LaunchKey().mixBytes(b).value());
  b.pointer = storage + 1;
  EXPECT_NE(LaunchKey().mixBytes(a).value(), LaunchKey().mixBytes(b).value());
  b = a;
  b.tail[2] = 'd';
  EXPECT_NE(LaunchKey().mixBytes(a).value(), LaunchKey().mixBytes(b).value());
}

}  // namespace
}  // namespace galsculpt
