#include "solver/io/text_lines.h"

#include <charconv>
#include <cmath>
#include <cstdlib>

#include "solver/io/input_error.h"

namespace galsculpt {

namespace {
bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

std::string printable(std::string_view token) {
  std::string out;
  for (char c : token.substr(0, 32)) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 32 && u < 127) {
      out += c;
    } else {
      out += "\\x";
      const char* hex = "0123456789abcdef";
      out += hex[u >> 4];
      out += hex[u & 15];
    }
  }
  if (token.size() > 32) out += "...";
  return out;
}
}  // namespace

TextLines::TextLines(std::string file, std::string_view buffer, char commentChar)
    : file_(std::move(file)) {
  int lineNumber = 0;
  size_t pos = 0;
  while (pos < buffer.size()) {
    size_t end = buffer.find('\n', pos);
    if (end == std::string_view::npos) end = buffer.size();
    std::string_view line = buffer.substr(pos, end - pos);
    pos = end + 1;
    ++lineNumber;
    if (commentChar != 0) {
      const size_t hash = line.find(commentChar);
      if (hash != std::string_view::npos) line = line.substr(0, hash);
    }
    TextLine parsed;
    parsed.number = lineNumber;
    size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && isSpace(line[i])) ++i;
      size_t j = i;
      while (j < line.size() && !isSpace(line[j])) ++j;
      if (j > i) parsed.tokens.push_back(line.substr(i, j - i));
      i = j;
    }
    if (!parsed.tokens.empty()) lines_.push_back(std::move(parsed));
  }
  lastLine_ = lineNumber;
}

const TextLine& TextLines::next(const std::string& expecting) {
  if (atEnd()) fail(lastLine_, "unexpected end of file, expected " + expecting);
  return lines_[next_++];
}

void TextLines::fail(int line, const std::string& message) const {
  throw InputError(file_, line, message);
}

long long TextLines::parseInt(const TextLine& line, size_t token, const char* what) const {
  if (token >= line.tokens.size()) {
    fail(line.number, std::string("missing ") + what + " (expected at least " +
                          std::to_string(token + 1) + " values, got " +
                          std::to_string(line.tokens.size()) + ")");
  }
  const std::string_view t = line.tokens[token];
  long long value = 0;
  const char* begin = t.data();
  if (!t.empty() && t[0] == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, t.data() + t.size(), value);
  if (ec != std::errc() || ptr != t.data() + t.size()) {
    fail(line.number,
         std::string("expected ") + what + " (an integer), got '" + printable(t) + "'");
  }
  return value;
}

double TextLines::parseDouble(const TextLine& line, size_t token, const char* what) const {
  if (token >= line.tokens.size()) {
    fail(line.number, std::string("missing ") + what + " (expected at least " +
                          std::to_string(token + 1) + " values, got " +
                          std::to_string(line.tokens.size()) + ")");
  }
  const std::string_view t = line.tokens[token];
  double value = 0;
  const char* begin = t.data();
  if (!t.empty() && t[0] == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, t.data() + t.size(), value);
  if (ec == std::errc::result_out_of_range && ptr == t.data() + t.size()) {
    // Out of range either way: too large is an error, too small rounds to zero (or a
    // subnormal) as strtod does, since 1e-400 is a well-formed number for 0.
    const double rounded = std::strtod(std::string(begin, ptr).c_str(), nullptr);
    if (!std::isfinite(rounded))
      fail(line.number,
           std::string(what) + " is beyond the range of a double: '" + printable(t) + "'");
    return rounded;
  }
  if (ec == std::errc() && !std::isfinite(value)) {
    fail(line.number, std::string(what) + " is not finite: '" + printable(t) + "'");
  }
  if (ec != std::errc() || ptr != t.data() + t.size()) {
    fail(line.number, std::string("expected ") + what + " (a number), got '" + printable(t) + "'");
  }
  return value;
}

}  // namespace galsculpt
