#include "json_reader.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solver/atomic_file.h"
#include "solver/input_error.h"

namespace galsculpt {

nlohmann::json vec3Json(const Eigen::Vector3d& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

nlohmann::json parseJsonFile(const std::filesystem::path& path) {
  const std::string text = readWholeFile(path);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    const size_t offset = std::min<size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    const int line = 1 + static_cast<int>(std::count(
                             text.begin(), text.begin() + static_cast<long>(offset), '\n'));
    std::string what = e.what();
    const size_t colon = what.find("parse error");
    if (colon != std::string::npos) what = what.substr(colon);
    throw InputError(path.string(), line, "JSON syntax error: " + what);
  }
}

JsonObject::JsonObject(const nlohmann::json& value, std::string path, std::string file)
    : value_(value), path_(std::move(path)), file_(std::move(file)) {
  if (!value_.is_object()) {
    throw InputError(file_, 0,
                     path_ + ": expected an object, got " + std::string(value_.type_name()));
  }
}

void JsonObject::fail(const std::string& key, const std::string& message) const {
  throw InputError(file_, 0, (key.empty() ? path_ : childPath(key)) + ": " + message);
}

const nlohmann::json& JsonObject::raw(const std::string& key) {
  seen_.insert(key);
  return value_.at(key);
}

namespace {
std::string show(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace

double JsonObject::number(const std::string& key, double fallback, double min, double max) {
  if (!has(key)) return fallback;
  return requiredNumber(key, min, max);
}

double JsonObject::requiredNumber(const std::string& key, double min, double max) {
  if (!has(key)) fail(key, "is required");
  const nlohmann::json& v = raw(key);
  if (!v.is_number()) fail(key, std::string("expected a number, got ") + v.type_name());
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(key, "must be finite");
  if (x < min) fail(key, "must be at least " + show(min) + ", got " + show(x));
  if (x > max) fail(key, "must be at most " + show(max) + ", got " + show(x));
  return x;
}

int JsonObject::integer(const std::string& key, int fallback, int min, int max) {
  if (!has(key)) return fallback;
  const nlohmann::json& v = raw(key);
  if (!v.is_number_integer()) fail(key, std::string("expected an integer, got ") + v.type_name());
  const long long x = v.get<long long>();
  if (x < min) fail(key, "must be at least " + std::to_string(min) + ", got " + std::to_string(x));
  if (x > max) fail(key, "must be at most " + std::to_string(max) + ", got " + std::to_string(x));
  return static_cast<int>(x);
}

bool JsonObject::boolean(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  const nlohmann::json& v = raw(key);
  if (!v.is_boolean()) fail(key, std::string("expected true or false, got ") + v.type_name());
  return v.get<bool>();
}

std::string JsonObject::string(const std::string& key, const std::string& fallback,
                               const std::vector<std::string>& allowed) {
  if (!has(key)) return fallback;
  const nlohmann::json& v = raw(key);
  if (!v.is_string()) fail(key, std::string("expected a string, got ") + v.type_name());
  std::string s = v.get<std::string>();
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), s) == allowed.end()) {
    std::string list;
    for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
    fail(key, "unknown value '" + s + "' (expected one of: " + list + ")");
  }
  return s;
}

Eigen::Vector3d JsonObject::vec3(const std::string& key, const Eigen::Vector3d& fallback) {
  if (!has(key)) return fallback;
  const nlohmann::json& v = raw(key);
  if (!v.is_array() || v.size() != 3) fail(key, "expected an array of 3 numbers");
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number()) fail(key, "expected an array of 3 numbers");
    out[i] = v[i].get<double>();
    if (!std::isfinite(out[i])) fail(key, "must be finite");
  }
  return out;
}

JsonObject JsonObject::object(const std::string& key) {
  return JsonObject(raw(key), childPath(key), file_);
}

std::vector<nlohmann::json> JsonObject::array(const std::string& key) {
  if (!has(key)) return {};
  const nlohmann::json& v = raw(key);
  if (!v.is_array()) fail(key, std::string("expected an array, got ") + v.type_name());
  return std::vector<nlohmann::json>(v.begin(), v.end());
}

void JsonObject::rejectUnknownKeys() const {
  for (auto it = value_.begin(); it != value_.end(); ++it) {
    if (!seen_.count(it.key())) fail(it.key(), "unknown key");
  }
}

}  // namespace galsculpt
