#include "engine/meshing/subprocess.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "solver/io/stop_request.h"

namespace galsculpt {

namespace {
constexpr int kExecFailed = 127;

std::string tailOf(const std::filesystem::path& file, size_t maxChars) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string s = ss.str();
  if (s.size() > maxChars) s = "..." + s.substr(s.size() - maxChars);
  return s;
}
}  // namespace

std::string SubprocessResult::describe() const {
  std::ostringstream out;
  if (!started) {
    out << "could not be started";
  } else if (timedOut) {
    out << "timed out after " << static_cast<int>(seconds + 0.5) << " s and was stopped";
  } else if (signal != 0) {
    out << "crashed with signal " << signal << " (" << strsignal(signal) << ")";
  } else {
    out << "exited with status " << exitCode;
  }
  return out.str();
}

SubprocessResult runSubprocess(const std::vector<std::string>& argv, double timeoutSeconds,
                               const std::filesystem::path& logFile) {
  SubprocessResult result;
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();

  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) return result;
  if (pid == 0) {
    setpgid(0, 0);
    // The child ends with galsculpt, however galsculpt ends (Ctrl-C, SIGTERM, kill -9): TetGen
    // ran on for seconds after its parent was gone. If the parent is already gone, stop now.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(kExecFailed);
    const int fd = open(logFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
      close(fd);
    }
    const int devNull = open("/dev/null", O_RDONLY);
    if (devNull >= 0) dup2(devNull, STDIN_FILENO);
    execvp(args[0], args.data());
    _exit(kExecFailed);
  }
  setpgid(pid, pid);

  int status = 0;
  while (true) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (done == pid) {
      result.seconds = elapsed;
      break;
    }
    if (done < 0 && errno != EINTR) break;
    if (stopRequested()) {  // Ctrl-C or SIGTERM: the child ends first, then the caller unwinds
      kill(-pid, SIGKILL);
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      throwIfStopRequested();
    }
    if (elapsed > timeoutSeconds) {
      kill(-pid, SIGKILL);
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      result.started = true;
      result.timedOut = true;
      result.seconds = elapsed;
      result.logTail = tailOf(logFile, 2000);
      return result;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  result.started = true;
  if (WIFEXITED(status)) {
    result.exitCode = WEXITSTATUS(status);
    if (result.exitCode == kExecFailed) result.started = false;
  } else if (WIFSIGNALED(status)) {
    result.signal = WTERMSIG(status);
  }
  result.logTail = tailOf(logFile, 2000);
  return result;
}

}  // namespace galsculpt
