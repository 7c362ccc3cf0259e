// Host shadows of executor buffers: what the device holds, kept on the host, so that a state's
// array is uploaded only when it differs (a backend may step several states: tests, undo
// snapshots) and downloaded through the executor's pinned staging.
#pragma once

#include <cstring>
#include <vector>

namespace galsculpt {

// Uploads `src` (an array of doubles or of structs of doubles) into `dst` when it differs from
// `shadow`, which then holds it; whether it did.
template <typename Buffer, typename V>
bool uploadIfChanged(const std::vector<V>& src, std::vector<double>& shadow, Buffer& dst) {
  static_assert(sizeof(V) % sizeof(double) == 0, "an array of doubles");
  const size_t n = src.size() * (sizeof(V) / sizeof(double));
  if (shadow.size() == n &&
      std::memcmp(shadow.data(), static_cast<const void*>(src.data()), n * sizeof(double)) == 0)
    return false;
  shadow.resize(n);
  std::memcpy(shadow.data(), static_cast<const void*>(src.data()), n * sizeof(double));
  dst.upload(shadow);
  return true;
}

// Downloads `src` into `dst` (sized already) through `shadow`, which then holds it.
template <typename Exec, typename Buffer, typename V>
void downloadThroughShadow(const Exec& ex, const Buffer& src, std::vector<double>& shadow,
                           std::vector<V>& dst) {
  static_assert(sizeof(V) % sizeof(double) == 0, "an array of doubles");
  shadow.resize(dst.size() * (sizeof(V) / sizeof(double)));
  ex.download(src.data(), shadow.data(), shadow.size());
  std::memcpy(static_cast<void*>(dst.data()), shadow.data(), shadow.size() * sizeof(double));
}

}  // namespace galsculpt
