// GALSCULPT_WAIT_SITES=1: the CPU executors count where the host waits for the device
// (scalar reads, downloads, a factorization's status) by source line, and prints the table to
// standard error when the process ends (`wait sites: N waits`, then count and file:line, most
// first; bench prints a table per measurement). Run with `--backend device-like`, what a device
// path still waits for is then found without a GPU.
#pragma once

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <source_location>
#include <string>
#include <utility>
#include <vector>

namespace galsculpt::detail {

class WaitSites {
 public:
  static WaitSites& instance() {
    static WaitSites sites;
    return sites;
  }
  bool enabled() const { return enabled_; }
  void add(const std::source_location& site) {
    std::string where = site.file_name();
    const size_t root = where.rfind("/solver/");
    if (root != std::string::npos) where = where.substr(root + 1);
    where += ":" + std::to_string(site.line());
    const std::lock_guard<std::mutex> lock(mutex_);
    ++counts_[where];
  }
  ~WaitSites() { report(); }
  // Prints the table and starts again (bench's measurements end with _exit, without
  // destructors: each reports its own).
  void report() {
    if (!enabled_ || counts_.empty()) return;
    std::vector<std::pair<long, std::string>> rows;
    long total = 0;
    for (const auto& [where, count] : counts_) {
      rows.emplace_back(count, where);
      total += count;
    }
    std::sort(rows.rbegin(), rows.rend());
    std::fprintf(stderr, "wait sites: %ld waits\n", total);
    for (const auto& [count, where] : rows)
      std::fprintf(stderr, "%10ld  %s\n", count, where.c_str());
    counts_.clear();
  }

 private:
  WaitSites() {
    const char* on = std::getenv("GALSCULPT_WAIT_SITES");
    enabled_ = on && std::string(on) == "1";
  }
  bool enabled_ = false;
  std::mutex mutex_;
  std::map<std::string, long> counts_;
};

}  // namespace galsculpt::detail
