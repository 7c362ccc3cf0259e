// Runs the command line in-process for tests: exit code, standard output and standard error.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "app/cli/cli.h"

namespace galsculpt::test {

struct CliRun {
  int code;
  std::string out, err;
};

inline CliRun runCliCapture(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  const int code = runCli(args, out, err);
  return {code, out.str(), err.str()};
}

}  // namespace galsculpt::test
