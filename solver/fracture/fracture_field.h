// The fracture pass's per-mesh data (fracture.h builds it; SimModel::fracture holds it), as flat
// arrays the executors read as they are.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

struct FractureSettings {
  // Pa; edges whose normal stress passes it break. 0: no stress criterion (strainThreshold
  // must then be > 0).
  double threshold = 0.0;
  double kernelRadius = 0.0;     // m; 0: local
  double thresholdJitter = 0.0;  // relative, in [0, 1)
  std::uint32_t seed = 1;
  // > 0: an edge also breaks when its engineering strain |x_b - x_a| / L - 1 passes it (a
  // ductile criterion, not in the paper: plastic flow, not stress, tears a ductile body).
  // Scaled per edge as the tensile threshold is (jitter, fracture energy). 0: never.
  double strainThreshold = 0.0;
  // Pa; > 0: an edge also breaks when compressed beyond it (crushing, shear lips). 0: never;
  // the paper's criterion is tension only. Scaled per edge as its tensile threshold is
  // (jitter, fracture energy): an edge crushes beyond compressiveThreshold * threshold[e] /
  // threshold.
  double compressiveThreshold = 0.0;
  // J/m^2; > 0: the fracture energy G_c (crack band). An edge where the mesh size is h breaks
  // at threshold * sqrt(l_ch / h), l_ch = 2 E G_c / threshold^2, so that breaking it releases
  // G_c per unit of crack area whatever the mesh size (docs/physics.md). 0: every edge at
  // `threshold` (the paper).
  double fractureEnergy = 0.0;
  // In (0, 1]: of the edges past their threshold in one pass, only those whose criticality (the
  // larger of stress / threshold and compression / compressive threshold) is within this
  // fraction of the largest break; the others wait for the re-solve with the new damage
  // (StepSettings::fractureIterations) or the next sub-step, so a crack advances from its most
  // critical edges and unloads the rest instead of everything past the threshold breaking at
  // once. 0: every edge past its threshold breaks (the paper's pass).
  double criticalFraction = 0.0;
  // In (0, 1]: sections cracked through part (cracked_sections.h): after a pass that broke
  // edges, the intact edges still linking parts whose undamaged elements share no face break
  // too, parts counted from this fraction of the body's rest volume. 0: stress alone breaks
  // edges (the paper).
  double partingFraction = 0.0;

  // The crushing threshold as a multiple of the tensile one (0: no crushing), by which every
  // edge's tensile threshold scales to its crushing threshold.
  double crushRatio() const { return threshold > 0.0 ? compressiveThreshold / threshold : 0.0; }
};

// Edges of no criterion: their threshold (Pa) where only strain breaks edges, their strain
// limit where only stress does. Finite, so that ratios stay 0, not NaN.
inline constexpr double kNeverBreaks = 1e300;

// Per-edge thresholds, the element slots around each edge, and a uniform grid of rest edge
// midpoints for the kernel. The grid's cells are numbered in key order, each with the numbers of
// the 27 cells around it (-1 where there is none, dz fastest), so a thread finds an edge's
// neighbourhood without a search and can skip it when no cell near it holds an edge over the
// smallest threshold.
struct FractureField {
  bool enabled = false;  // false: no fracture pass (and no cost)
  FractureSettings settings;
  std::vector<double> threshold;      // (nEdges) Pa; kNeverBreaks without a stress criterion
  double minThreshold = 0.0;          // Pa
  std::vector<double> strainLimit;    // (nEdges) strainThreshold > 0 only
  std::vector<double> restLength;     // (nEdges) strainThreshold > 0 only
  std::vector<int> slotStart, slots;  // edge -> 6 * tet + local edge, CSR
  // tetFaceNeighbours of the mesh, for sections cracked through (partingFraction > 0 only).
  std::vector<std::array<int, 4>> tetNeighbours;
  std::vector<Vec3> midpoint;           // (nEdges) rest midpoints
  double cellSize = 0.0;                // kernel grid (kernelRadius > 0 only)
  std::vector<int> cellBegin, cellEnd;  // (cells) range of each cell in cellEdges
  std::vector<int> cellEdges;           // edges sorted by cell
  std::vector<int> edgeCell;            // (nEdges) the cell of each edge's midpoint
  std::vector<int> cellNeighbors;       // (27 cells)
  int cells() const { return static_cast<int>(cellBegin.size()); }
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

}  // namespace galsculpt
