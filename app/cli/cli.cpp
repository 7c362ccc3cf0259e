#include "app/cli/cli.h"

#include <new>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "app/cli/cli_args.h"
#include "app/cli/command_table.h"
#include "solver/io/input_error.h"
#include "solver/io/memory_limits.h"
#include "solver/io/stop_request.h"

namespace galsculpt {

std::string assetDirectory() {
  if (const char* env = std::getenv("GALSCULPT_ASSETS"); env && *env) return env;
  return GALSCULPT_ASSET_DIR;
}

std::string defaultScenePath() {
  return (std::filesystem::path(assetDirectory()) / "scenes" / "default.json").string();
}

int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  try {
    if (args.empty()) return openCommand({defaultScenePath()}, out, err);
    const std::string& command = args[0];
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    if (command == "help" || command == "--help" || command == "-h") {
      out << topLevelHelp();
      return kExitOk;
    }
    if (command == "version" || command == "--version") {
      out << "galsculpt " << GALSCULPT_VERSION << '\n';
      return kExitOk;
    }
    if (command == "mesh") return meshCommand(rest, out, err);
    if (command == "scene") return sceneCommand(rest, out, err);
    if (command == "open") return openCommand(rest, out, err);
    if (command == "render") return renderCommand(rest, out, err);
    if (command == "run") return runCommand(rest, out, err);
    if (command == "play") return playCommand(rest, out, err);
    if (command == "bench") return benchCommand(rest, out, err);
    std::vector<std::string> commands{"help", "version"};
    for (const CommandSpec& c : commandTable()) {
      const std::string word = c.name.substr(0, c.name.find(' '));
      if (std::find(commands.begin(), commands.end(), word) == commands.end())
        commands.push_back(word);
    }
    throw UsageError("unknown command '" + command + "'" + didYouMean(command, commands));
  } catch (const HelpRequested& e) {
    out << e.what();
    return kExitOk;
  } catch (const Interrupted& e) {
    err << "galsculpt: " << e.what() << '\n';
    return 128 + e.signal();
  } catch (const UsageError& e) {
    err << "galsculpt: error: " << e.what() << '\n';
    if (e.command().empty()) {
      err << "(run 'galsculpt --help' for usage)\n";
    } else {
      err << "usage: " << commandUsage(commandSpec(e.command())) << "\n(run 'galsculpt "
          << e.command() << " --help' for what each option means)\n";
    }
    return kExitUsage;
  } catch (const InputError& e) {
    err << "galsculpt: error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const OutputError& e) {
    err << "galsculpt: error: " << e.what() << '\n';
    return kExitOutput;
  } catch (const std::bad_alloc&) {
    err << "galsculpt: error: out of memory: an allocation failed" << availableMemoryText()
        << "; a mesh of fewer tets, or more memory, would do\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    err << "galsculpt: error: " << e.what() << '\n';
    return kExitFailure;
  }
}

}  // namespace galsculpt
