// The graph-based fracture pass (paper section 3.1, Algorithm 1), on the finest level: its
// parameters and per-mesh data here; the pass itself is part of the frame
// (solver/frame/frame_solver.h, fracturePass), the same on every executor.
//
// After each sub-step every element's stress is projected on its six edges (edgeNormalStress:
// n^T sigma n, Cauchy stress, current edge direction). An edge's stress is the largest over the
// elements around it (the paper's per-element test: any element can break the edge). An edge
// whose stress passes its threshold is damaged for good; the damaged edge then degrades the
// energy of every element around it (tet_element.h), from the next sub-step on.
//
// Options, both off by default:
// - Non-local averaging over a kernel of radius R_d: the stress compared with the threshold is
//   the weighted mean of the undamaged edges' stresses whose rest midpoints lie within R_d,
//   with weights (1 - d^2/R_d^2)^2. Larger R_d: smoother stress, more diffuse cracks. The mean
//   never exceeds its largest term, so only edges near an edge over the smallest threshold are
//   averaged: the pass costs nothing extra while nothing is close to breaking.
// - Randomized thresholds: threshold * (1 + jitter * u), u uniform in [-1, 1] from a hash of
//   (seed, edge index): the same on every run and for any thread count.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "solver/model/sim_model.h"

namespace galsculpt {

struct FractureSettings {
  double threshold = 0.0;        // Pa; edges whose normal stress passes it break
  double kernelRadius = 0.0;     // m; 0: local
  double thresholdJitter = 0.0;  // relative, in [0, 1)
  std::uint32_t seed = 1;
  // Pa; > 0: an edge also breaks when compressed beyond it (crushing, shear lips). 0: never;
  // the paper's criterion is tension only.
  double compressiveThreshold = 0.0;
};

// What the pass needs, built once per mesh: per-edge thresholds, the element slots around each
// edge, and a uniform grid of rest edge midpoints for the kernel.
struct FractureField {
  FractureSettings settings;
  std::vector<double> threshold;  // (nEdges)
  double minThreshold = 0.0;
  std::vector<int> slotStart, slots;                            // edge -> 6 * tet + local edge, CSR
  std::vector<Vec3> midpoint;                                   // (nEdges) rest midpoints
  double cellSize = 0.0;                                        // kernel grid
  std::unordered_map<std::int64_t, std::pair<int, int>> cells;  // cell key -> range in cellEdges
  std::vector<int> cellEdges;
};

// The kernel grid: the cell of a point, and a cell's key (21 bits per axis; the mesh spans far
// fewer cells than 2^20 in any direction).
inline std::array<std::int64_t, 3> fractureCell(const Vec3& p, double cell) {
  const auto c = [&](double v) { return static_cast<std::int64_t>(std::floor(v / cell)); };
  return {c(p.x()), c(p.y()), c(p.z())};
}
inline std::int64_t fractureCellKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  const std::int64_t mask = (1 << 21) - 1;
  return ((x + (1 << 20)) & mask) << 42 | ((y + (1 << 20)) & mask) << 21 | ((z + (1 << 20)) & mask);
}

// Throws std::invalid_argument for a non-positive threshold or a jitter outside [0, 1).
FractureField buildFractureField(const SimModel& model, const FractureSettings& settings);

struct FractureReport {
  int newlyDamaged = 0;
  double maxStressRatio = 0.0;  // largest edge stress / its threshold among undamaged edges
};

}  // namespace galsculpt
