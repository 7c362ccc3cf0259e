#include "solver/io/memory_limits.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace galsculpt {

namespace {

// The first number on the line of `file` that starts with `key`, times `scale`.
std::optional<std::uint64_t> numberAfter(const char* file, const std::string& key,
                                         std::uint64_t scale) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) != 0) continue;
    std::istringstream rest(line.substr(key.size()));
    std::uint64_t value = 0;
    if (rest >> value) return value * scale;
  }
  return std::nullopt;
}

// The whole content of a one-number file; none for "max" or an unreadable file.
std::optional<std::uint64_t> numberIn(const char* file) {
  std::ifstream in(file);
  std::uint64_t value = 0;
  if (in >> value) return value;
  return std::nullopt;
}

}  // namespace

std::optional<std::uint64_t> availableMemoryBytes() {
  std::optional<std::uint64_t> least;
  auto consider = [&least](std::optional<std::uint64_t> bytes) {
    if (bytes) least = least ? std::min(*least, *bytes) : *bytes;
  };
  consider(numberAfter("/proc/meminfo", "MemAvailable:", 1024));
  const std::optional<std::uint64_t> limit = numberIn("/sys/fs/cgroup/memory.max");
  const std::optional<std::uint64_t> used = numberIn("/sys/fs/cgroup/memory.current");
  if (limit && used) consider(*limit > *used ? *limit - *used : 0);
  rlimit address{};
  if (getrlimit(RLIMIT_AS, &address) == 0 && address.rlim_cur != RLIM_INFINITY) {
    const std::uint64_t mapped = numberAfter("/proc/self/status", "VmSize:", 1024).value_or(0);
    consider(address.rlim_cur > mapped ? address.rlim_cur - mapped : 0);
  }
  return least;
}

std::string bytesText(double bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB"};
  int unit = 0;
  while (bytes >= 1000.0 && unit < 4) {
    bytes /= 1000.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, bytes < 10.0 && unit > 0 ? "%.1f %s" : "%.0f %s", bytes,
                units[unit]);
  return text;
}

std::string availableMemoryText() {
  const std::optional<std::uint64_t> available = availableMemoryBytes();
  if (!available) return "";
  return "; about " + bytesText(static_cast<double>(*available)) + " is available";
}

void requireMemory(double bytes, const std::string& what, const std::string& hint) {
  const std::optional<std::uint64_t> available = availableMemoryBytes();
  if (!available || bytes <= static_cast<double>(*available)) return;
  throw OutOfMemory("out of memory before starting: " + what + " needs about " + bytesText(bytes) +
                    availableMemoryText() + ": " + hint);
}

}  // namespace galsculpt
