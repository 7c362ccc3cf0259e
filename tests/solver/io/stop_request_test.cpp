#include "solver/io/stop_request.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace galsculpt {
namespace {

// A signal the handlers catch only records the stop: the process goes on, and the loops that
// poll it throw Interrupted with the signal.
TEST(StopRequest, ASignalIsRecordedAndThrownWhereTheLoopPolls) {
  const pid_t pid = fork();
  if (pid == 0) {  // a child: the handlers stay out of the rest of the test binary
    installStopHandlers();
    if (stopRequested()) _exit(10);
    raise(SIGTERM);
    if (stopSignal() != SIGTERM) _exit(11);
    try {
      throwIfStopRequested();
      _exit(12);
    } catch (const Interrupted& e) {
      if (e.signal() != SIGTERM || std::string(e.what()) != "stopped by SIGTERM") _exit(13);
    }
    raise(SIGINT);  // a second signal ends the process at once, by that signal
    _exit(14);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "exit " << WEXITSTATUS(status);
  EXPECT_EQ(WTERMSIG(status), SIGINT);
}

TEST(StopRequest, TestsCanAskAndClear) {
  EXPECT_NO_THROW(throwIfStopRequested());
  requestStopForTesting(SIGINT);
  EXPECT_THROW(throwIfStopRequested(), Interrupted);
  EXPECT_EQ(signalName(stopSignal()), "SIGINT");
  requestStopForTesting(0);
  EXPECT_FALSE(stopRequested());
  EXPECT_EQ(signalName(SIGHUP), "signal " + std::to_string(SIGHUP));
}

// An embedding's poll (Python's signals): asked while no stop is recorded, its answer recorded
// until cleared, and asked no more once a stop stands.
int pollCalls = 0;
int pollAnswer = 0;
int poll() {
  ++pollCalls;
  return pollAnswer;
}

TEST(StopRequest, AnEmbeddingsPollIsAskedAndItsStopKeptUntilCleared) {
  setStopPoller(poll);
  EXPECT_FALSE(stopRequested());
  EXPECT_EQ(pollCalls, 1);
  pollAnswer = SIGINT;
  EXPECT_THROW(throwIfStopRequested(), Interrupted);
  pollAnswer = 0;
  EXPECT_EQ(stopSignal(), SIGINT) << "recorded";
  EXPECT_EQ(pollCalls, 2) << "not asked again while a stop stands";
  setStopPoller(nullptr);
  clearStopRequest();
  EXPECT_FALSE(stopRequested());
  EXPECT_EQ(pollCalls, 2) << "no poll once unset";
}

}  // namespace
}  // namespace galsculpt
