#include "engine/session/recovery.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include "engine/scene/scene_mesh.h"
#include "engine/session/project_file.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

TEST(RecoveryStore, OffersOnlyFilesOfProcessesThatAreGone) {
  test::TempDir dir;
  RecoveryStore store(dir / "recovery");
  EXPECT_TRUE(store.orphans().empty()) << "no folder yet: nothing to recover";
  const SceneDescription scene =
      loadScene(fs::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json");
  SculptSession session(scene, loadSceneMesh(scene));
  session.step();
  store.save(session, std::nullopt);
  ASSERT_TRUE(fs::exists(store.ownFile()));
  EXPECT_TRUE(store.orphans().empty()) << "this process is alive: its file is not an orphan";

  // A file left by a process that no longer runs (a pid no process has).
  long dead = 4000000;
  while (kill(static_cast<pid_t>(dead), 0) == 0 || errno == EPERM) ++dead;
  const fs::path crashed = dir / "recovery" / ("recovery-" + std::to_string(dead) + ".gsproj");
  fs::copy_file(store.ownFile(), crashed);
  test::writeText(dir / "recovery" / "notes.txt", "not a recovery file");
  const std::vector<fs::path> orphans = store.orphans();
  ASSERT_EQ(orphans.size(), 1u);
  EXPECT_EQ(orphans[0], crashed);
  const Project recovered = readProject(orphans[0]);
  EXPECT_EQ(recovered.state.frame, 1) << "the autosaved state comes back";

  store.remove(crashed);
  store.remove(store.ownFile());
  EXPECT_FALSE(fs::exists(store.ownFile()));
  EXPECT_TRUE(store.orphans().empty());
}

// Something not a regular file under a recovery file's name (a pipe blocked the window's start
// when the offer read it) is not offered.
TEST(RecoveryStore, OffersNoSpecialFiles) {
  test::TempDir dir;
  fs::create_directories(dir / "recovery");
  long dead = 4000000;
  while (kill(static_cast<pid_t>(dead), 0) == 0 || errno == EPERM) ++dead;
  const std::string name = "recovery-" + std::to_string(dead) + ".gsproj";
  ASSERT_EQ(mkfifo((dir / "recovery" / name).c_str(), 0600), 0);
  fs::create_directories(dir / "recovery" / ("recovery-" + std::to_string(dead + 1) + ".gsproj"));
  RecoveryStore store(dir / "recovery");
  EXPECT_TRUE(store.orphans().empty());
}

}  // namespace
}  // namespace galsculpt
