#include "solver/atomic_file.h"

#include <gtest/gtest.h>

#include "solver/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

size_t filesIn(const fs::path& dir) {
  size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

TEST(AtomicFile, WritesAndReplaces) {
  test::TempDir dir;
  writeFileAtomically(dir / "a.txt", [](std::ostream& out) { out << "first"; });
  writeFileAtomically(dir / "a.txt", [](std::ostream& out) { out << "second"; });
  EXPECT_EQ(readWholeFile(dir / "a.txt"), "second");
  EXPECT_EQ(filesIn(dir.path()), 1u) << "no temporary file is left behind";
}

TEST(AtomicFile, FailureInsideTheWriterKeepsTheOldFile) {
  test::TempDir dir;
  writeFileAtomically(dir / "a.txt", [](std::ostream& out) { out << "old"; });
  EXPECT_THROW(writeFileAtomically(dir / "a.txt",
                                   [](std::ostream& out) {
                                     out << "half a fi";
                                     throw std::runtime_error("disk on fire");
                                   }),
               std::runtime_error);
  EXPECT_EQ(readWholeFile(dir / "a.txt"), "old");
  EXPECT_EQ(filesIn(dir.path()), 1u);
}

TEST(AtomicFile, RenameFailureIsReportedAndCleanedUp) {
  test::TempDir dir;
  fs::create_directories(dir / "occupied" / "child");  // a non-empty folder cannot be replaced
  EXPECT_THROW_WITH(writeFileAtomically(dir / "occupied", [](std::ostream& out) { out << "x"; }),
                    OutputError, "cannot write");
  EXPECT_TRUE(fs::is_directory(dir / "occupied" / "child"));
  EXPECT_EQ(filesIn(dir.path()), 1u);
}

TEST(AtomicFile, MissingFolderIsAClearError) {
  test::TempDir dir;
  EXPECT_THROW_WITH(writeFileAtomically(dir / "nope" / "a.txt", [](std::ostream&) {}), OutputError,
                    "does not exist");
}

TEST(AtomicFile, ReadingAMissingFileNamesIt) {
  EXPECT_THROW_WITH(readWholeFile("/nonexistent/galsculpt.txt"), InputError,
                    "/nonexistent/galsculpt.txt: cannot open");
}

}  // namespace
}  // namespace galsculpt
