#include <signal.h>

#include <iostream>
#include <string>
#include <vector>

#include "app/cli/cli.h"
#include "solver/io/stop_request.h"

int main(int argc, char** argv) {
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
