// The commands of `galsculpt`, each declared once: its words, operands, flags (with what each
// takes and means) and a line of what it does. The parser (CliArgs) reads a command's flags from
// here, `galsculpt CMD --help` prints them from here, and the top-level help lists them all, so
// what is parsed and what is documented cannot part.
#pragma once

#include <string>
#include <vector>

namespace galsculpt {

struct FlagSpec {
  std::string name;   // "--frames"
  std::string value;  // what it takes ("N"); empty: a switch
  std::string help;   // one line or two
  bool required = false;
};

struct CommandSpec {
  std::string name;      // "run", "mesh import"
  std::string operands;  // "SCENE", "IN OUT"
  int minOperands = 0, maxOperands = 0;
  std::string summary;  // what it does, a line or two
  std::vector<FlagSpec> flags;
};

// Every command, in the order the help lists them.
const std::vector<CommandSpec>& commandTable();
// The command named ("run", "mesh import"); std::invalid_argument for no such command.
const CommandSpec& commandSpec(const std::string& name);

// "galsculpt run SCENE --frames N --out DIR [--solver reference] ...": required flags bare,
// the others in brackets.
std::string commandUsage(const CommandSpec& command);
// A usage line wrapped at `width` columns, breaking only before an option ("--x" or "[--x ...]")
// and indenting the lines after the first by `indent` spaces.
std::string wrapUsage(const std::string& usage, size_t width, size_t indent);
// The usage, the summary and every flag with its meaning: `galsculpt CMD --help`.
std::string commandHelp(const CommandSpec& command);
// `galsculpt --help`: every command with its usage and summary, the exit codes.
std::string topLevelHelp();

// The command a group's words name ("mesh" with args {"import", ...}: "mesh import"): args[0] a
// subcommand of the table; -h/--help or none: HelpRequested listing the group's commands; another
// word: UsageError naming the nearest.
std::string subcommandOf(const std::string& group, const std::vector<std::string>& args);

// The name among `candidates` nearest `word` by edit distance, when near enough to be a slip
// (at most a third of its letters, at least one), else empty: "did you mean ...?".
std::string nearestName(const std::string& word, const std::vector<std::string>& candidates);
// " (did you mean NAME?)" with nearestName's answer, or empty: the tail of an "unknown" message.
std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace galsculpt
