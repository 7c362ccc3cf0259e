#include "solver/io/appending_file.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>

#include "solver/io/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

TEST(AppendingFile, RecordsReachTheFileAsTheyAreAppended) {
  test::TempDir dir;
  const fs::path path = dir / "rows.csv";
  test::writeText(path, "an old file\nwith two lines\n");
  AppendingFile file(path);
  EXPECT_EQ(test::readText(path), "") << "an old file is emptied";
  file.append("a,b\n");
  EXPECT_EQ(test::readText(path), "a,b\n") << "before close: a kill now keeps the record";
  file.append("1,2\n");
  file.close();
  EXPECT_EQ(test::readText(path), "a,b\n1,2\n");
  EXPECT_THROW(file.append("3,4\n"), OutputError);
  EXPECT_THROW(AppendingFile(dir / "missing" / "rows.csv"), OutputError);
  EXPECT_THROW(AppendingFile(dir.path()), OutputError) << "a folder in its place";
}

// A disk that fills mid-record (a file size limit, as in the hostile suite): the partial record
// is cut off, the error names the path and the system's reason, the whole records stay.
TEST(AppendingFile, AFailedRecordIsCutOffAndTheWholeOnesStay) {
  test::TempDir dir;
  const fs::path path = dir / "rows.csv";
  const pid_t pid = fork();
  if (pid == 0) {
    signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{100, 100};
    if (setrlimit(RLIMIT_FSIZE, &limit) != 0) _exit(10);
    AppendingFile file(path);
    const std::string record(30, 'x');
    for (int i = 0; i < 3; ++i) file.append(record + "\n");  // 93 bytes
    try {
      file.append(record + "\n");
      _exit(11);
    } catch (const OutputError& e) {
      const std::string what = e.what();
      if (what.find(path.string()) == std::string::npos) _exit(12);
      if (what.find("File too large") == std::string::npos) _exit(13);
    }
    _exit(0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(fs::file_size(path), 93u) << "three whole records, no part of the fourth";
}

}  // namespace
}  // namespace galsculpt
