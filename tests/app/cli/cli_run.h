// Runs the command line in-process for tests: exit code, standard output and standard error.
#pragma once

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli/cli.h"

namespace galsculpt::test {

// The default scene, which most of the command line's tests run.
inline const std::filesystem::path kDefaultSceneFile =
    std::filesystem::path(GALSCULPT_SOURCE_DIR) / "assets" / "scenes" / "default.json";

struct CliRun {
  int code;
  std::string out, err;
};

inline CliRun runCliCapture(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  const int code = runCli(args, out, err);
  return {code, out.str(), err.str()};
}

// The command line's tests call it `run`.
inline CliRun run(const std::vector<std::string>& args) {
  return runCliCapture(args);
}

}  // namespace galsculpt::test
