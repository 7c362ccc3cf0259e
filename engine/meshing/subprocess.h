// Runs an external program (TetGen) in its own process group with a wall-clock limit.
//
// The child's stdout and stderr go to a log file. A crash (signal) or a timeout in the child is
// reported in the result, never propagated: the caller decides what to tell the user.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace galsculpt {

struct SubprocessResult {
  bool started = false;   // false when the program could not be executed (not found)
  bool timedOut = false;  // killed after the time limit
  int exitCode = -1;      // when it exited normally
  int signal = 0;         // when a signal ended it (SIGABRT for a TetGen assertion)
  double seconds = 0.0;
  std::string logTail;  // the last lines it printed

  bool succeeded() const { return started && !timedOut && signal == 0 && exitCode == 0; }
  // "exited with status 3", "crashed with signal 6 (Aborted)", "timed out after 60 s", ...
  std::string describe() const;
};

SubprocessResult runSubprocess(const std::vector<std::string>& argv, double timeoutSeconds,
                               const std::filesystem::path& logFile);

}  // namespace galsculpt
