// Errors raised on bad input (meshes, scenes, scripts) and failed outputs.
//
// Every message a user sees names where the problem is: `file:line: message` for text formats,
// `file: $.json.path: message` for JSON. Physics code never throws these; they are for I/O.
#pragma once

#include <stdexcept>
#include <string>

namespace galsculpt {

// Malformed or unsupported input. what() is the full, user-facing message.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
  // "file:line: message"; line <= 0 omits the line.
  InputError(const std::string& file, int line, const std::string& message)
      : std::runtime_error(line > 0 ? file + ":" + std::to_string(line) + ": " + message
                                    : file + ": " + message) {}
};

// An output that could not be written. The previous file at that path, if any, is intact.
class OutputError : public std::runtime_error {
 public:
  explicit OutputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace galsculpt
