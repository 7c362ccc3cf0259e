// GALSCULPT_CUDA_PROFILE=1: the CUDA executor waits for every launch, times it with device events
// and adds the time to the lambda it ran (each lambda is its own type, named after the function
// that holds it), and prints the table to stderr when the executor ends. A profile where no
// profiler runs (the lent machines have no nsys): the frame runs far slower, graphs are off, and
// what the table does not hold of a frame's time is the host's.
#pragma once

#include <cuda_runtime.h>
#include <cxxabi.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace galsculpt::gpu {

class LaunchProfile {
 public:
  static bool requested() {
    const char* env = std::getenv("GALSCULPT_CUDA_PROFILE");
    return env && std::string(env) == "1";
  }
  LaunchProfile() {
    cudaEventCreate(&start_);
    cudaEventCreate(&stop_);
  }
  LaunchProfile(const LaunchProfile&) = delete;
  LaunchProfile& operator=(const LaunchProfile&) = delete;
  ~LaunchProfile() {
    print();
    cudaEventDestroy(start_);
    cudaEventDestroy(stop_);
  }
  void begin(cudaStream_t stream) { cudaEventRecord(start_, stream); }
  // Waits for the launch; `kind`: "launch" or "reduce", `mangled`: typeid(F).name().
  void end(cudaStream_t stream, const char* kind, const char* mangled, int items) {
    cudaEventRecord(stop_, stream);
    cudaEventSynchronize(stop_);
    float ms = 0.0f;
    cudaEventElapsedTime(&ms, start_, stop_);
    Entry& e = entries_[std::string(kind) + " " + mangled];
    ++e.count;
    e.ms += ms;
    e.items += items;
  }

 private:
  struct Entry {
    long count = 0;
    double ms = 0.0;
    double items = 0.0;
  };
  static std::string readable(const std::string& key) {
    const size_t space = key.find(' ');
    int status = 0;
    char* name = abi::__cxa_demangle(key.c_str() + space + 1, nullptr, nullptr, &status);
    std::string text = key.substr(0, space) + " " + (status == 0 ? name : key.substr(space + 1));
    std::free(name);
    // The executor's type repeats in every name; what tells the lambdas apart is at the end.
    for (const std::string noise : {"galsculpt::", "gpu::CudaExecutor"}) {
      for (size_t at; (at = text.find(noise)) != std::string::npos;) text.erase(at, noise.size());
    }
    return text.size() > 170 ? text.substr(0, 60) + " ... " + text.substr(text.size() - 105) : text;
  }
  void print() const {
    std::vector<std::pair<std::string, Entry>> rows(entries_.begin(), entries_.end());
    std::sort(rows.begin(), rows.end(),
              [](const auto& a, const auto& b) { return a.second.ms > b.second.ms; });
    double total = 0.0;
    long launches = 0;
    for (const auto& [key, e] : rows) {
      total += e.ms;
      launches += e.count;
    }
    std::fprintf(stderr, "launch profile: %ld launches, %.3f ms on the device\n", launches, total);
    std::fprintf(stderr, "%10s %8s %10s %10s  %s\n", "ms", "count", "us each", "items", "lambda");
    for (size_t i = 0; i < rows.size() && i < 40; ++i) {
      const Entry& e = rows[i].second;
      std::fprintf(stderr, "%10.3f %8ld %10.2f %10.0f  %s\n", e.ms, e.count,
                   1000.0 * e.ms / e.count, e.items / e.count, readable(rows[i].first).c_str());
    }
  }
  cudaEvent_t start_ = nullptr, stop_ = nullptr;
  std::map<std::string, Entry> entries_;
};

}  // namespace galsculpt::gpu
