#include "solver/io/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "solver/io/input_error.h"
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

// Projects and autosaves also reach the disk before the rename (fsync, which a test cannot
// observe without a crash); the promises of the atomic write hold for them the same.
TEST(AtomicFile, DurableWritesKeepTheAtomicPromises) {
  test::TempDir dir;
  writeFileDurably(dir / "a.txt", [](std::ostream& out) { out << "first"; });
  writeFileDurably(dir / "a.txt", [](std::ostream& out) { out << "second"; });
  EXPECT_EQ(readWholeFile(dir / "a.txt"), "second");
  EXPECT_THROW(writeFileDurably(dir / "a.txt",
                                [](std::ostream& out) {
                                  out << "half";
                                  throw std::runtime_error("disk on fire");
                                }),
               std::runtime_error);
  EXPECT_EQ(readWholeFile(dir / "a.txt"), "second");
  fs::create_directories(dir / "occupied" / "child");
  EXPECT_THROW_WITH(writeFileDurably(dir / "occupied", [](std::ostream& out) { out << "x"; }),
                    OutputError, "cannot write");
  EXPECT_EQ(filesIn(dir.path()), 2u) << "no temporary file is left behind";
  EXPECT_THROW_WITH(writeFileDurably(dir / "nope" / "a.txt", [](std::ostream&) {}), OutputError,
                    "does not exist");
}

TEST(AtomicFile, MissingFolderIsAClearError) {
  test::TempDir dir;
  EXPECT_THROW_WITH(writeFileAtomically(dir / "nope" / "a.txt", [](std::ostream&) {}), OutputError,
                    "does not exist");
}

TEST(AtomicFile, ReadingAMissingFileNamesIt) {
  EXPECT_THROW_WITH(readWholeFile("/nonexistent/galsculpt.txt"), InputError,
                    "/nonexistent/galsculpt.txt: file not found");
}

// /dev/zero as an input was read until memory ran out (std::bad_alloc); a folder, a device or a
// pipe is refused before anything is read.
TEST(AtomicFile, OnlyRegularFilesAreRead) {
  test::TempDir dir;
  EXPECT_THROW_WITH(readWholeFile("/dev/zero"), InputError,
                    "/dev/zero: is a character device, not a regular file");
  EXPECT_THROW_WITH(readWholeFile(dir.path()), InputError, "is a folder, not a regular file");
}

// Each kind is named, before anything opens it: a pipe with no writer would block the reader.
TEST(AtomicFile, RequireRegularFileNamesWhatThePathIs) {
  test::TempDir dir;
  test::writeText(dir / "plain.txt", "x");
  EXPECT_NO_THROW(requireRegularFile(dir / "plain.txt"));
  EXPECT_TRUE(isRegularFile(dir / "plain.txt"));
  fs::create_symlink(dir / "plain.txt", dir / "link.txt");
  EXPECT_NO_THROW(requireRegularFile(dir / "link.txt")) << "a link to a file is that file";
  ASSERT_EQ(mkfifo((dir / "pipe").c_str(), 0600), 0);
  EXPECT_THROW_WITH(requireRegularFile(dir / "pipe"), InputError,
                    "pipe: is a named pipe (FIFO), not a regular file");
  EXPECT_FALSE(isRegularFile(dir / "pipe"));
  fs::create_symlink(dir / "b", dir / "a");
  fs::create_symlink(dir / "a", dir / "b");
  EXPECT_THROW_WITH(requireRegularFile(dir / "a"), InputError, "a: is a loop of symbolic links");
  EXPECT_FALSE(isRegularFile(dir / "a"));
  EXPECT_THROW_WITH(requireRegularFile(dir / "missing"), InputError, "missing: file not found");
  EXPECT_THROW_WITH(requireRegularFile(dir.path()), InputError, "is a folder, not a regular file");
  EXPECT_THROW_WITH(requireRegularFile("/dev/null"), InputError,
                    "/dev/null: is a character device, not a regular file");
  // Only that something is there: any kind, or why it cannot be told.
  EXPECT_NO_THROW(requirePathExists(dir / "pipe"));
  EXPECT_NO_THROW(requirePathExists(dir.path()));
  EXPECT_THROW_WITH(requirePathExists(dir / "missing"), InputError, "missing: no such file");
  EXPECT_THROW_WITH(requirePathExists(dir / "a"), InputError, "a: is a loop of symbolic links");
}

// A set is written whole: a failing member leaves the previous set untouched and no temporary;
// members carry the set's stamp; temporaries of dead writers are cleaned by the next write.
TEST(AtomicFile, FileSetsAreCommittedWholeAndStamped) {
  test::TempDir dir;
  test::writeText(dir / "m.a", "old a");
  test::writeText(dir / "m.b", "old b");
  {
    FileSet set;
    set.add(dir / "m.a", [&](std::ostream& out) { out << "new a\n" << set.stampLine(); });
    EXPECT_THROW(set.add(dir / "m.b", [](std::ostream&) { throw OutputError("disk full"); }),
                 OutputError);
  }  // not committed
  EXPECT_EQ(test::readText(dir / "m.a"), "old a");
  EXPECT_EQ(test::readText(dir / "m.b"), "old b");
  test::writeText(dir / ".m.a.tmp999999999", "left by a killed writer");  // no such process
  test::writeText(dir / "m.stale", "x");
  FileSet set;
  set.add(dir / "m.a", [&](std::ostream& out) { out << "new a\n" << set.stampLine(); });
  set.add(dir / "m.b", [&](std::ostream& out) { out << "new b\n" << set.stampLine(); });
  set.remove(dir / "m.stale");
  set.commit();
  EXPECT_EQ(findSetStamp(test::readText(dir / "m.a")), set.stamp());
  EXPECT_EQ(findSetStamp(test::readText(dir / "m.b")), set.stamp());
  EXPECT_EQ(set.stamp().size(), 16u);
  EXPECT_FALSE(fs::exists(dir / "m.stale"));
  EXPECT_FALSE(fs::exists(dir / ".m.a.tmp999999999")) << "a dead writer's temporary is cleaned";
  size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 2u);
  EXPECT_EQ(findSetStamp("no stamp here"), "");
  FileSet other;
  EXPECT_NE(other.stamp(), set.stamp());
}

// The last member of a set cannot be renamed into place (a full disk, a folder gone): the members
// already placed go back, so the folder holds the old set, and the message has the real error.
TEST(AtomicFile, AFailedRenameMidSetPutsTheOldSetBack) {
  test::TempDir dir;
  for (const char* m : {"m.a", "m.b", "m.c"}) test::writeText(dir / m, std::string("old ") + m);
  FileSet::setRenameForTesting([](const fs::path& from, const fs::path& to, std::error_code& ec) {
    if (to.filename() == "m.c" && from.filename().string().find(".tmp") != std::string::npos)
      ec = std::make_error_code(std::errc::no_space_on_device);
    else
      fs::rename(from, to, ec);
  });
  {
    FileSet set;
    for (const char* m : {"m.a", "m.b", "m.c"})
      set.add(dir / m, [&](std::ostream& out) { out << "new\n" << set.stampLine(); });
    EXPECT_THROW_WITH(set.commit(), OutputError,
                      "m.c: No space left on device; the old set is unchanged");
  }
  FileSet::setRenameForTesting(nullptr);
  for (const char* m : {"m.a", "m.b", "m.c"})
    EXPECT_EQ(test::readText(dir / m), std::string("old ") + m) << m;
  size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 3u) << "no temporary and no member moved aside is left";

  // A folder in a member's place: refused before anything moves.
  fs::create_directories(dir / "m.b.folder" / "x");
  fs::remove(dir / "m.b");
  fs::rename(dir / "m.b.folder", dir / "m.b");
  FileSet set;
  for (const char* m : {"m.a", "m.b"})
    set.add(dir / m, [&](std::ostream& out) { out << "new\n" << set.stampLine(); });
  EXPECT_THROW_WITH(set.commit(), OutputError, "m.b: a folder is in its place");
  EXPECT_EQ(test::readText(dir / "m.a"), "old m.a");
}

}  // namespace
}  // namespace galsculpt
