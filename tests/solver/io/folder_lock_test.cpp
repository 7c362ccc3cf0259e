#include "solver/io/folder_lock.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <optional>

#include "solver/io/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

// A held folder refuses a second lock (a second open file, as another process's would be) and
// names the holder; released, it leaves no file and can be taken again.
TEST(FolderLock, OneHolderAtATimeAndNothingLeftAfter) {
  test::TempDir dir;
  std::optional<FolderLock> first(std::in_place, dir.path());
  const fs::path file = dir / FolderLock::kFileName;
  EXPECT_EQ(test::readText(file), std::to_string(getpid()));
  try {
    FolderLock second(dir.path());
    ADD_FAILURE() << "a second writer got the folder";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("another galsculpt (pid " + std::to_string(getpid()) +
                                         ") is writing there"),
              std::string::npos)
        << e.what();
  }
  first.reset();
  EXPECT_FALSE(fs::exists(file));
  EXPECT_NO_THROW(FolderLock again(dir.path()));
  EXPECT_THROW(FolderLock(dir / "missing"), OutputError) << "no folder: a clear error";
}

}  // namespace
}  // namespace galsculpt
