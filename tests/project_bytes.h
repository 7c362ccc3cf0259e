// Editing a saved project's bytes in tests: its JSON header, keeping the length line right.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>

namespace galsculpt::test {

inline std::string withProjectHeader(const std::string& project,
                                     const std::function<void(nlohmann::json&)>& edit) {
  const size_t line1 = project.find('\n'), line2 = project.find('\n', line1 + 1);
  const size_t length = std::stoull(project.substr(line1 + 1, line2 - line1 - 1));
  nlohmann::json h = nlohmann::json::parse(project.substr(line2 + 1, length));
  edit(h);
  const std::string header = h.dump();
  return project.substr(0, line1 + 1) + std::to_string(header.size()) + "\n" + header +
         project.substr(line2 + 1 + length);
}

}  // namespace galsculpt::test
