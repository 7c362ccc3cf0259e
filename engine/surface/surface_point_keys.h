// The surface builder's point keys (surface_builder.cpp, surface_placement.cpp): which point of
// the dual mesh a surface vertex is. Internal to engine/surface.
#pragma once

#include <cstdint>

namespace galsculpt::surface_keys {

// Point keys: kind in the top bits, the edge/face/tet index, and the mask of the defining
// corners that this copy holds (bit i: corner i of the support, in support order), plus one
// bit for a second sheet through the same tet centroid.
enum PointKind : std::uint64_t { kEdgePoint = 1, kFacePoint = 2, kTetPoint = 3 };

inline std::uint64_t pointKey(PointKind kind, int index, unsigned mask) {
  return (static_cast<std::uint64_t>(kind) << 60) | (static_cast<std::uint64_t>(index) << 5) | mask;
}
inline PointKind keyKind(std::uint64_t key) {
  return static_cast<PointKind>(key >> 60);
}
inline int keyIndex(std::uint64_t key) {
  return static_cast<int>((key >> 5) & ((1ull << 55) - 1));
}
// Corners held; bit 4 tells apart two copies holding the same corners (see emitTet).
inline unsigned keyMask(std::uint64_t key) {
  return static_cast<unsigned>(key & 15u);
}

}  // namespace galsculpt::surface_keys
