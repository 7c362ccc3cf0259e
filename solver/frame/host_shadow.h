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

// Downloads `srcA` and `srcB` into `dstA` and `dstB` (sized already) through their shadows,
// which then hold them, behind one wait (Exec::downloadAll).
template <typename Exec, typename BufferA, typename A, typename BufferB, typename B>
void downloadThroughShadows(const Exec& ex, const BufferA& srcA, std::vector<double>& shadowA,
                            std::vector<A>& dstA, const BufferB& srcB, std::vector<double>& shadowB,
                            std::vector<B>& dstB) {
  static_assert(sizeof(A) % sizeof(double) == 0 && sizeof(B) % sizeof(double) == 0,
                "arrays of doubles");
  shadowA.resize(dstA.size() * (sizeof(A) / sizeof(double)));
  shadowB.resize(dstB.size() * (sizeof(B) / sizeof(double)));
  ex.downloadAll({{srcA.data(), shadowA.data(), shadowA.size() * sizeof(double)},
                  {srcB.data(), shadowB.data(), shadowB.size() * sizeof(double)}});
  std::memcpy(static_cast<void*>(dstA.data()), shadowA.data(), shadowA.size() * sizeof(double));
  std::memcpy(static_cast<void*>(dstB.data()), shadowB.data(), shadowB.size() * sizeof(double));
}

}  // namespace galsculpt
