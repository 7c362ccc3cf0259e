#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdlib>

#include <iostream>
#include <string>
#include <vector>

#include "app/cli/cli.h"
#include "solver/io/stop_request.h"

namespace {

// Under an address-space limit (ulimit -v), OpenBLAS's worker threads, started when the library
// loads, retry forever to map their 128 MB buffers: a worker spins a core for the whole run and
// the process hangs at exit joining it. The library reads its thread count only as it loads, so
// the process runs itself again with one BLAS thread (no workers) before doing anything else.
void withOneBlasThreadUnderAnAddressLimit(char** argv) {
  rlimit address{};
  if (getrlimit(RLIMIT_AS, &address) != 0 || address.rlim_cur == RLIM_INFINITY) return;
  if (std::getenv("OPENBLAS_NUM_THREADS") != nullptr) return;
  setenv("OPENBLAS_NUM_THREADS", "1", 1);
  execv("/proc/self/exe", argv);  // returns only if it failed: then go on as we are
}

}  // namespace

int main(int argc, char** argv) {
  withOneBlasThreadUnderAnAddressLimit(argv);
  // Past a file size limit (ulimit -f) a write fails with EFBIG and is reported like a full
  // disk, instead of the signal ending the process mid-write.
  signal(SIGXFSZ, SIG_IGN);
  // Ctrl-C and SIGTERM end the command between two of its steps, cleanly (stop_request.h).
  galsculpt::installStopHandlers();
  std::vector<std::string> args(argv + 1, argv + argc);
  const int code = galsculpt::runCli(args, std::cout, std::cerr);
  if (const int stop = galsculpt::stopSignal()) {
    // Ended by the signal, as a shell and a parent process expect, once everything is clean.
    std::cout.flush();
    std::cerr.flush();
    signal(stop, SIG_DFL);
    raise(stop);
  }
  return code;
}
