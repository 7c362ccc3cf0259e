#include "engine/scene/solver_options_json.h"

#include <stdexcept>
#include <type_traits>

#include "solver/io/input_error.h"

namespace galsculpt {

namespace {

template <NamedEnum E>
std::vector<std::string> namesList(E value) {
  std::vector<std::string> names;
  for (const EnumName<E>& n : namesOf(value)) names.push_back(n.name);
  return names;
}

// The option's value in `o`, or `fallback` where the key is absent.
template <typename T>
T readOption(JsonObject& o, const OptionField<T>& f, const T& fallback) {
  if constexpr (std::is_same_v<T, bool>) {
    return o.boolean(f.key, fallback);
  } else if constexpr (std::is_same_v<T, int>) {
    return o.integer(f.key, fallback, static_cast<int>(f.min), static_cast<int>(f.max));
  } else if constexpr (std::is_same_v<T, double>) {
    return o.number(f.key, fallback, f.min, f.max);
  } else if constexpr (std::is_same_v<T, std::string>) {
    std::string value = o.string(f.key, fallback);
    if (f.check) {
      try {
        f.check(value);
      } catch (const std::invalid_argument& e) {
        o.fail(f.key, e.what());
      }
    }
    return value;
  } else {
    return *enumFromName<T>(o.string(f.key, enumName(fallback), namesList(fallback)));
  }
}

template <typename T>
nlohmann::json optionJson(const T& value) {
  if constexpr (NamedEnum<T>)
    return enumName(value);
  else
    return value;
}

}  // namespace

SolverOptions readSolverOptions(JsonObject o) {
  const std::string preset =
      o.string("preset", enumName(SolverPreset::Converged), namesList(SolverPreset::Converged));
  SolverOptions options = solverPreset(*enumFromName<SolverPreset>(preset));
  forEachSolverOption(
      [&](const auto& f) { options.*f.member = readOption(o, f, options.*f.member); });
  o.rejectUnknownKeys();
  return options;
}

nlohmann::json solverOptionsJson(const SolverOptions& options) {
  nlohmann::json j = nlohmann::json::object();
  j["preset"] = enumName(options.preset);
  forEachSolverOption([&](const auto& f) { j[f.key] = optionJson(options.*f.member); });
  return j;
}

SolverOverrides parseSolverOptionList(const std::string& list) {
  SolverOverrides pairs;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t comma = std::min(list.find(',', start), list.size());
    const std::string item = list.substr(start, comma - start);
    start = comma + 1;
    const size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw std::invalid_argument("'" + item + "' is not KEY=VALUE");
    const std::string key = item.substr(0, eq), text = item.substr(eq + 1);
    bool known = key == "preset";
    forEachSolverOption([&](const auto& f) { known = known || key == f.key; });
    if (!known) {
      std::string keys = "preset";
      forEachSolverOption([&](const auto& f) { keys += std::string(", ") + f.key; });
      throw std::invalid_argument("unknown solver option '" + key + "' (options: " + keys + ")");
    }
    nlohmann::json value = nlohmann::json::parse(text, nullptr, false);
    if (value.is_discarded() || value.is_object() || value.is_array()) value = text;
    pairs.emplace_back(key, value);
  }
  return pairs;
}

SceneDescription withSolverOverrides(const SceneDescription& scene,
                                     const SolverOverrides& overrides) {
  if (overrides.empty()) return scene;
  nlohmann::json root = scene.source;
  if (!root.contains("solver") || !root["solver"].is_object())
    root["solver"] = nlohmann::json::object();
  std::string said;
  for (const auto& [key, value] : overrides) {
    root["solver"][key] = value;
    said += (said.empty() ? "" : ",") + key + "=" + value.dump();
  }
  try {
    return parseScene(root, scene.file);
  } catch (const InputError& e) {
    throw InputError("solver options " + said + ": " + e.what());
  }
}

}  // namespace galsculpt
