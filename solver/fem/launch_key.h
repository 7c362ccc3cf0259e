// The key of launches a device records once and replays (a CUDA graph, a device loop): a hash of
// everything they bake in (sizes, device pointers, host-side choices, settings), so that a
// recording is replayed only while none of it changed. FNV-1a over 64-bit words.
#pragma once

#include <cstdint>
#include <cstring>

namespace galsculpt {

class LaunchKey {
 public:
  LaunchKey& mix(std::uint64_t v) {
    key_ = (key_ ^ v) * 1099511628211ull;
    return *this;
  }
  LaunchKey& mixDouble(double d) {
    std::uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    return mix(bits);
  }
  LaunchKey& mixPointer(const void* p) { return mix(reinterpret_cast<std::uintptr_t>(p)); }
  // A plain struct's bytes (a launch's argument of pointers and sizes), word by word.
  template <typename T>
  LaunchKey& mixBytes(const T& value) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    for (size_t at = 0; at < sizeof(T); at += sizeof(std::uint64_t)) {
      std::uint64_t word = 0;
      std::memcpy(&word, bytes + at, sizeof(T) - at < sizeof word ? sizeof(T) - at : sizeof word);
      mix(word);
    }
    return *this;
  }
  std::uint64_t value() const { return key_; }

 private:
  std::uint64_t key_ = 1469598103934665603ull;
};

}  // namespace galsculpt
