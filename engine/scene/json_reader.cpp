#include "engine/scene/json_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>

#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"

namespace galsculpt {

nlohmann::json vec3Json(const Eigen::Vector3d& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

namespace {

int lineAt(const std::string& text, size_t offset) {
  offset = std::min(offset, text.size());
  return 1 +
         static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(offset), '\n'));
}

// Where the n-th key (a string followed by ':') of a well-formed document starts.
size_t nthKeyAt(const std::string& text, size_t n) {
  size_t count = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '"') continue;
    const size_t start = i;
    for (++i; i < text.size() && text[i] != '"'; ++i) {
      if (text[i] == '\\') ++i;
    }
    size_t j = i + 1;
    while (j < text.size() && std::isspace(static_cast<unsigned char>(text[j]))) ++j;
    if (j < text.size() && text[j] == ':' && count++ == n) return start;
  }
  return text.size();
}

}  // namespace

size_t jsonTooDeepAt(std::string_view text) {
  int depth = 0;
  bool inString = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        inString = false;
      }
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string::npos;
}

nlohmann::json parseJsonText(const std::string& text, const std::string& file, int firstLine) {
  if (const size_t at = jsonTooDeepAt(text); at != std::string::npos)
    throw InputError(file, firstLine - 1 + lineAt(text, at),
                     "JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  // A key given twice in one object would silently keep the last value: refused. Checked by a
  // SAX handler around the library's DOM builder: its callback parser scans the enclosing array
  // at every object's end (quadratic: a million-move stroke took minutes).
  struct DuplicateKey {
    std::string key;
    size_t ordinal;  // among all keys of the document, from 0
  };
  using Json = nlohmann::json;
  struct KeyCheckingBuilder : nlohmann::detail::json_sax_dom_parser<Json> {
    using Base = nlohmann::detail::json_sax_dom_parser<Json>;
    explicit KeyCheckingBuilder(Json& result) : Base(result, true) {}
    std::vector<std::set<std::string>> open;  // the keys seen in each open object
    size_t keys = 0;
    bool start_object(std::size_t n) {
      open.emplace_back();
      return Base::start_object(n);
    }
    bool end_object() {
      open.pop_back();
      return Base::end_object();
    }
    bool key(Json::string_t& k) {
      if (!open.back().insert(k).second) throw DuplicateKey{k, keys};
      ++keys;
      return Base::key(k);
    }
  };
  try {
    Json result;
    KeyCheckingBuilder builder(result);
    Json::sax_parse(text, &builder);
    return result;
  } catch (const DuplicateKey& d) {
    throw InputError(
        file, firstLine - 1 + lineAt(text, nthKeyAt(text, d.ordinal)),
        "JSON: the key " + nlohmann::json(d.key).dump() + " is given twice in one object");
  } catch (const nlohmann::json::parse_error& e) {
    const size_t offset = e.byte > 0 ? e.byte - 1 : 0;
    std::string what = e.what();
    const size_t colon = what.find("parse error");
    if (colon != std::string::npos) what = what.substr(colon);
    throw InputError(file, firstLine - 1 + lineAt(text, offset), "JSON syntax error: " + what);
  } catch (const nlohmann::json::exception& e) {
    // A number beyond the range of a double (1e999): the library names the literal but not
    // where it is.
    std::string what = e.what();
    const size_t open = what.find('\''), close = what.rfind('\'');
    int line = 0;
    if (open != std::string::npos && close > open) {
      const size_t at = text.find(what.substr(open + 1, close - open - 1));
      if (at != std::string::npos) line = firstLine - 1 + lineAt(text, at);
      what =
          "the number " + what.substr(open, close - open + 1) + " is beyond the range of a double";
    }
    throw InputError(file, line, "JSON: " + what);
  }
}

nlohmann::json parseJsonFile(const std::filesystem::path& path) {
  return parseJsonText(readWholeFile(path), path.string());
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
  if (!has(key)) fail(key, "is required");
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
  // Unsigned values above the signed range would read back negative.
  if (v.is_number_unsigned() && v.get<unsigned long long>() > static_cast<unsigned long long>(max))
    fail(key, "must be at most " + std::to_string(max) + ", got " +
                  std::to_string(v.get<unsigned long long>()));
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

Eigen::Vector3d JsonObject::vec3(const std::string& key, const Eigen::Vector3d& fallback,
                                 double maxAbs) {
  if (!has(key)) return fallback;
  const nlohmann::json& v = raw(key);
  if (!v.is_array() || v.size() != 3) fail(key, "expected an array of 3 numbers");
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number()) fail(key, "expected an array of 3 numbers");
    out[i] = v[i].get<double>();
    if (!std::isfinite(out[i])) fail(key, "must be finite");
    if (std::abs(out[i]) > maxAbs)
      fail(key, "components must be within +-" + show(maxAbs) + ", got " + show(out[i]));
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
