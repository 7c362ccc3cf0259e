#include "engine/meshing/subprocess.h"

#include <gtest/gtest.h>
#include <signal.h>

#include "tests/test_util.h"

namespace galsculpt {
namespace {

TEST(Subprocess, ExitCodeAndOutput) {
  test::TempDir dir;
  const SubprocessResult r = runSubprocess({"sh", "-c", "echo hello; exit 3"}, 10.0, dir / "log");
  EXPECT_TRUE(r.started);
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_FALSE(r.succeeded());
  EXPECT_EQ(r.logTail, "hello\n");
  EXPECT_EQ(r.describe(), "exited with status 3");
}

TEST(Subprocess, CrashIsReportedNotPropagated) {
  test::TempDir dir;
  const SubprocessResult r = runSubprocess({"sh", "-c", "kill -ABRT $$"}, 10.0, dir / "log");
  EXPECT_EQ(r.signal, SIGABRT);
  EXPECT_NE(r.describe().find("crashed with signal 6"), std::string::npos) << r.describe();
}

TEST(Subprocess, TimeoutKillsTheWholeGroup) {
  test::TempDir dir;
  const SubprocessResult r = runSubprocess({"sh", "-c", "sleep 30 & sleep 30"}, 0.3, dir / "log");
  EXPECT_TRUE(r.timedOut);
  EXPECT_LT(r.seconds, 5.0);
  EXPECT_NE(r.describe().find("timed out"), std::string::npos);
}

TEST(Subprocess, MissingProgram) {
  test::TempDir dir;
  const SubprocessResult r = runSubprocess({"galsculpt-no-such-program"}, 5.0, dir / "log");
  EXPECT_FALSE(r.started);
  EXPECT_FALSE(r.succeeded());
}

}  // namespace
}  // namespace galsculpt
