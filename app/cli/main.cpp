#include <signal.h>

#include <iostream>
#include <string>
#include <vector>

#include "app/cli/cli.h"

int main(int argc, char** argv) {
  // Past a file size limit (ulimit -f) a write fails with EFBIG and is reported like a full
  // disk, instead of the signal ending the process mid-write.
  signal(SIGXFSZ, SIG_IGN);
  std::vector<std::string> args(argv + 1, argv + argc);
  return galsculpt::runCli(args, std::cout, std::cerr);
}
