// The galsculpt command line: `galsculpt [COMMAND] ...`, dispatched to the subcommands.
//
// Exit codes are a contract for scripts (docs/cli.md):
//   0 success, 1 failure while working (meshing, rendering), 2 usage error,
//   3 bad input (file and line in the message), 4 an output could not be written.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace galsculpt {

enum ExitCode { kExitOk = 0, kExitFailure = 1, kExitUsage = 2, kExitBadInput = 3, kExitOutput = 4 };

// `args` excludes the program name.
int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// Subcommands (args after the command word).
int meshCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int sceneCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int openCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int benchCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int runCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int playCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int renderCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// assets/ of the source tree or of an install; $GALSCULPT_ASSETS overrides.
std::string assetDirectory();
std::string defaultScenePath();

}  // namespace galsculpt
