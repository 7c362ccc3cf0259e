#include "app/cli/run_outputs.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

TEST(RunOutputs, NamesTheFilesRunAndPlayWrite) {
  for (const char* name :
       {"metrics.csv", "final.obj", "final.glb", "final.bin", "final.png", "final.node",
        "final.damage", "final.vtk", "frame_00010.obj", "frame_00120.png", "frame_99999.gltf"})
    EXPECT_TRUE(isRunOutputName(name)) << name;
  for (const char* name :
       {"mine.txt", "final.txt", "final.obj.bak", "frame_0001.obj", "frame_0001x.obj",
        "frame_00010.csv", "finals.obj", "metrics.csv~", ".galsculpt-writer", "scene.json"})
    EXPECT_FALSE(isRunOutputName(name)) << name;
}

TEST(RunOutputs, ClearsOnlyAnEarlierRunsFiles) {
  test::TempDir dir;
  for (const char* name :
       {"final.obj", "final.png", "frame_00030.glb", "metrics.csv", "notes.txt", "final.obj.bak"})
    test::writeText(dir / name, "x");
  fs::create_directory(dir / "frame_00001.obj");  // a folder, not a file: left alone
  const std::vector<std::string> removed = clearRunOutputs(dir.path());
  EXPECT_EQ(removed,
            (std::vector<std::string>{"final.obj", "final.png", "frame_00030.glb", "metrics.csv"}));
  EXPECT_TRUE(fs::exists(dir / "notes.txt"));
  EXPECT_TRUE(fs::exists(dir / "final.obj.bak"));
  EXPECT_TRUE(fs::is_directory(dir / "frame_00001.obj"));
  EXPECT_FALSE(fs::exists(dir / "final.obj"));
  EXPECT_TRUE(clearRunOutputs(dir.path()).empty());
}

TEST(RunOutputs, DescribesFrameFilesAsARange) {
  EXPECT_EQ(describeWritten({"metrics.csv", "frame_00020.obj", "final.obj", "frame_00010.obj",
                             "frame_00010.png", "final.obj"}),
            "final.obj, metrics.csv, 2 frame_*.obj (frame_00010.obj .. frame_00020.obj), "
            "1 frame_*.png (frame_00010.png)");
}

}  // namespace
}  // namespace galsculpt
