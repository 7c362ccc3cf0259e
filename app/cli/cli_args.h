// Minimal command-line parsing for the galsculpt subcommands: positionals plus --flags, each
// flag declared by the command (unknown flags are usage errors, never ignored).
#pragma once

#include "engine/scene/scene.h"
#include "engine/scene/solver_options_json.h"

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace galsculpt {

// Thrown for a malformed command line; the CLI prints it with the usage and exits 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  // `command`: the command whose line it is ("mesh import"), for its usage.
  UsageError(const std::string& message, std::string command)
      : std::runtime_error(message), command_(std::move(command)) {}
  const std::string& command() const { return command_; }

 private:
  std::string command_;
};

// `galsculpt CMD --help` (or -h): the CLI prints the text to standard output and exits 0.
class HelpRequested : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CommandSpec;

class CliArgs {
 public:
  // The command's line parsed by its table entry (app/cli/command_table.h): its flags (those
  // with a value: --tets 1000 or --tets=1000), its operand count and its required flags. -h or
  // --help anywhere: HelpRequested with the command's help. An unknown flag names the nearest
  // one.
  CliArgs(const std::vector<std::string>& args, const CommandSpec& command);

  const std::vector<std::string>& positional() const { return positional_; }
  bool has(const std::string& flag) const { return values_.count(flag) > 0; }
  std::optional<std::string> value(const std::string& flag) const;
  int intValue(const std::string& flag, int fallback, int min, int max) const;
  double doubleValue(const std::string& flag, double fallback, double min, double max) const;
  // "3" or "3,40,80": integers, each in [min, max]
  std::vector<int> intListValue(const std::string& flag, const std::vector<int>& fallback, int min,
                                int max) const;
  // "WxH"
  std::pair<int, int> sizeValue(const std::string& flag, std::pair<int, int> fallback) const;

 private:
  std::vector<std::string> positional_;
  std::map<std::string, std::string> values_;
};

// An option whose value is one of an enum's names: empty when absent, the value named, or a
// UsageError that lists `choices` ("auto, cpu or cuda") for another name.
template <typename E>
std::optional<E> namedOption(const CliArgs& args, const std::string& flag,
                             std::optional<E> (*fromName)(const std::string&),
                             const std::string& choices) {
  const auto v = args.value(flag);
  if (!v) return std::nullopt;
  const std::optional<E> value = fromName(*v);
  if (!value) throw UsageError(flag + " must be " + choices + ", got '" + *v + "'");
  return value;
}

// --backend auto|cpu|cuda|device-like (run, play, bench, open): empty when absent, UsageError otherwise.
std::optional<BackendRequest> backendOption(const CliArgs& args);

// --solver-option KEY=VALUE[,KEY=VALUE...] and --backend (run, play, bench, open): the solver
// keys they set over the scene's (engine/scene/solver_options_json.h); --backend wins. A
// malformed list or an unknown key is a UsageError; a value out of range fails when applied.
SolverOverrides solverOverrides(const CliArgs& args);

// --threads N (run, play, bench, open): the CPU's thread count for this process, when given
// (solver/frame/parallel.h; otherwise GALSCULPT_THREADS, OMP_NUM_THREADS or the cores).
void applyThreadsOption(const CliArgs& args);

}  // namespace galsculpt
