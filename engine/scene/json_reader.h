// Strict, path-aware reading of JSON documents (scenes, scripts, projects).
//
// Every error names the file and the JSON path of the offending value, e.g.
// `scenes/x.json: $.material.poisson_ratio: must be below 0.5, got 0.7`. Unknown keys are errors:
// a typo must not silently fall back to a default.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace galsculpt {

// Bounds on what scenes and scripts may say, far beyond any sculpting or lab scene and far below
// where the arithmetic overflows (a coordinate of 1e300 squared is infinite).
inline constexpr double kMaxCoordinate = 1e6;    // m: positions, offsets, blade ends
inline constexpr double kMaxSpeed = 1e4;         // m/s
inline constexpr double kMaxAngularSpeed = 1e5;  // rad/s
inline constexpr double kMaxAcceleration = 1e5;  // m/s^2: about 10,000 g

// [x, y, z], every digit kept (what the readers' vec3 reads back exactly).
nlohmann::json vec3Json(const Eigen::Vector3d& v);

// Documents nesting deeper than this are refused before parsing (no scene, script or project
// nests more than a handful of levels).
inline constexpr int kMaxJsonDepth = 256;

// The first place where arrays and objects nest deeper than kMaxJsonDepth (outside strings), or
// npos. Recursive parsers (nlohmann's value destructor, assimp's glTF reader) would otherwise
// recurse once a level: a file of a few hundred thousand brackets overflows the stack.
size_t jsonTooDeepAt(std::string_view text);

// Parses a file; syntax errors become InputError "file:line: JSON syntax error: ...", numbers
// beyond a double's range and nesting deeper than kMaxJsonDepth are refused with file and line.
nlohmann::json parseJsonFile(const std::filesystem::path& path);
// The same for text that starts at line `firstLine` of `file` (a project's header).
nlohmann::json parseJsonText(const std::string& text, const std::string& file, int firstLine = 1);

class JsonObject {
 public:
  JsonObject(const nlohmann::json& value, std::string path, std::string file);

  bool has(const std::string& key) const { return value_.contains(key); }
  double number(const std::string& key, double fallback, double min, double max);
  double requiredNumber(const std::string& key, double min, double max);
  int integer(const std::string& key, int fallback, int min, int max);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key, const std::string& fallback,
                     const std::vector<std::string>& allowed = {});
  // Each component finite and within +-maxAbs (an error naming the key and the bound).
  Eigen::Vector3d vec3(const std::string& key, const Eigen::Vector3d& fallback,
                       double maxAbs = std::numeric_limits<double>::infinity());
  JsonObject object(const std::string& key);
  // Elements of an array member (empty when absent).
  std::vector<nlohmann::json> array(const std::string& key);
  std::string childPath(const std::string& key) const { return path_ + "." + key; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  const nlohmann::json& raw(const std::string& key);

  // Throws for every key that was never asked for.
  void rejectUnknownKeys() const;
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

 private:
  const nlohmann::json& value_;
  std::string path_;
  std::string file_;
  std::set<std::string> seen_;
};

}  // namespace galsculpt
