#include "app/cli/cli_args.h"

#include "app/cli/command_table.h"
#include "solver/frame/parallel.h"

#include <charconv>
#include <cmath>
#include <string_view>

namespace galsculpt {

CliArgs::CliArgs(const std::vector<std::string>& args, const CommandSpec& command) {
  for (const std::string& a : args)
    if (a == "--help" || a == "-h") throw HelpRequested(commandHelp(command));
  auto fail = [&](const std::string& message) { throw UsageError(message, command.name); };
  auto flagNamed = [&](const std::string& name) -> const FlagSpec* {
    for (const FlagSpec& f : command.flags)
      if (f.name == name) return &f;
    return nullptr;
  };
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.rfind("--", 0) != 0 || a == "--") {
      positional_.push_back(a);
      continue;
    }
    std::string name = a;
    std::optional<std::string> inlineValue;
    if (const size_t eq = a.find('='); eq != std::string::npos) {
      name = a.substr(0, eq);
      inlineValue = a.substr(eq + 1);
    }
    const FlagSpec* flag = flagNamed(name);
    if (!flag) {
      std::vector<std::string> names;
      for (const FlagSpec& f : command.flags) names.push_back(f.name);
      fail("unknown option " + name + " for " + command.name + didYouMean(name, names));
    }
    if (!flag->value.empty()) {
      if (inlineValue) {
        values_[name] = *inlineValue;
      } else if (i + 1 < args.size()) {
        values_[name] = args[++i];
      } else {
        fail(name + " needs a value (" + flag->value + ")");
      }
    } else if (inlineValue) {
      fail(name + " takes no value");
    } else {
      values_[name] = "";
    }
  }
  const int operands = static_cast<int>(positional_.size());
  if (operands < command.minOperands || operands > command.maxOperands) {
    fail(operands < command.minOperands
             ? command.name + " needs " + command.operands
             : command.name + " takes " +
                   (command.maxOperands == 0 ? std::string("no operand") : command.operands) +
                   ", got '" + positional_[command.maxOperands] + "' too");
  }
  for (const FlagSpec& f : command.flags)
    if (f.required && !has(f.name)) fail(command.name + " needs " + f.name + " " + f.value);
}

std::optional<std::string> CliArgs::value(const std::string& flag) const {
  const auto it = values_.find(flag);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

namespace {

// One integer of a flag's value, in [min, max]; `expects` names what the flag takes.
int parseInt(const std::string& flag, std::string_view text, const std::string& whole, int min,
             int max, const char* expects) {
  long long x = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (ec != std::errc() || ptr != text.data() + text.size())
    throw UsageError(flag + " expects " + expects + ", got '" + whole + "'");
  if (x < min || x > max) {
    throw UsageError(flag + " must be in [" + std::to_string(min) + ", " + std::to_string(max) +
                     "], got " + std::string(text));
  }
  return static_cast<int>(x);
}

}  // namespace

int CliArgs::intValue(const std::string& flag, int fallback, int min, int max) const {
  const auto v = value(flag);
  if (!v) return fallback;
  return parseInt(flag, *v, *v, min, max, "an integer");
}

std::vector<int> CliArgs::intListValue(const std::string& flag, const std::vector<int>& fallback,
                                       int min, int max) const {
  const auto v = value(flag);
  if (!v) return fallback;
  std::vector<int> list;
  size_t begin = 0;
  while (true) {
    const size_t end = std::min(v->find(',', begin), v->size());
    list.push_back(parseInt(flag, std::string_view(*v).substr(begin, end - begin), *v, min, max,
                            "an integer or a comma-separated list of them"));
    if (end == v->size()) return list;
    begin = end + 1;
  }
}

double CliArgs::doubleValue(const std::string& flag, double fallback, double min,
                            double max) const {
  const auto v = value(flag);
  if (!v) return fallback;
  double x = 0;
  const auto [ptr, ec] = std::from_chars(v->data(), v->data() + v->size(), x);
  if (ec != std::errc() || ptr != v->data() + v->size() || !std::isfinite(x)) {
    throw UsageError(flag + " expects a number, got '" + *v + "'");
  }
  if (x < min || x > max) throw UsageError(flag + " is out of range: " + *v);
  return x;
}

std::pair<int, int> CliArgs::sizeValue(const std::string& flag,
                                       std::pair<int, int> fallback) const {
  const auto v = value(flag);
  if (!v) return fallback;
  const size_t x = v->find('x');
  int w = 0, h = 0;
  if (x != std::string::npos) {
    const auto r1 = std::from_chars(v->data(), v->data() + x, w);
    const auto r2 = std::from_chars(v->data() + x + 1, v->data() + v->size(), h);
    if (r1.ec == std::errc() && r2.ec == std::errc() && r1.ptr == v->data() + x &&
        r2.ptr == v->data() + v->size() && w >= 16 && h >= 16 && w <= 8192 && h <= 8192) {
      return {w, h};
    }
  }
  throw UsageError(flag + " expects WIDTHxHEIGHT between 16 and 8192, got '" + *v + "'");
}

std::optional<BackendRequest> backendOption(const CliArgs& args) {
  return namedOption(args, "--backend", enumFromName<BackendRequest>,
                     "auto, cpu, cuda or device-like");
}

SolverOverrides solverOverrides(const CliArgs& args) {
  SolverOverrides overrides;
  if (const auto list = args.value("--solver-option")) {
    try {
      overrides = parseSolverOptionList(*list);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--solver-option: ") + e.what());
    }
  }
  if (const auto backend = backendOption(args))
    overrides.emplace_back("backend", enumName(*backend));
  return overrides;
}

void applyThreadsOption(const CliArgs& args) {
  if (args.has("--threads")) setThreadCount(args.intValue("--threads", 1, 1, 1024));
}

}  // namespace galsculpt
