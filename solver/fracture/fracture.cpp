#include "solver/fracture/fracture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "solver/fem/plasticity.h"

namespace galsculpt {

namespace {

// SplitMix64: a well-mixed hash of (seed, edge) for reproducible random thresholds.
double uniformSigned(std::uint32_t seed, std::uint64_t edge) {
  std::uint64_t z = (static_cast<std::uint64_t>(seed) << 32 ^ edge) + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return 2.0 * (static_cast<double>(z >> 11) * 0x1.0p-53) - 1.0;
}

// Per element: n^T sigma n on its six edges, written to slots 6 t + k.
std::vector<double> elementEdgeStresses(const SimModel& model, const SimState& state,
                                        bool compressionResists) {
  std::vector<double> out(6 * static_cast<size_t>(model.numTets()));
#pragma omp parallel for schedule(static)
  for (int t = 0; t < model.numTets(); ++t) {
    const Tet& tet = model.mesh.tets[t];
    const TetPoints p{state.x[tet[0]], state.x[tet[1]], state.x[tet[2]], state.x[tet[3]]};
    const EdgeDamage d = tetDamage(model, state.damaged, t, compressionResists);
    const bool plastic = !state.plasticInverse.empty() && !state.plasticInverse[t].isIdentity(0.0);
    const std::array<double, 6> s =
        plastic ? edgeNormalStress(model.material.model, model.material.lame,
                                   plasticRest(model.rest[t], state.plasticInverse[t]), p, d)
                : edgeNormalStress(model.material.model, model.material.lame, model.rest[t], p, d);
    for (int k = 0; k < 6; ++k) out[6 * t + k] = s[k];
  }
  return out;
}

// The largest tension over the elements around each edge, and (when asked) the largest
// compression, as a negative number.
std::vector<double> localEdgeStress(const SimModel& model, const FractureField& field,
                                    const SimState& state, bool compressionResists,
                                    std::vector<double>* compression = nullptr) {
  const std::vector<double> slot = elementEdgeStresses(model, state, compressionResists);
  std::vector<double> out(model.numEdges(), 0.0);
  if (compression) compression->assign(model.numEdges(), 0.0);
#pragma omp parallel for schedule(static)
  for (int e = 0; e < model.numEdges(); ++e) {
    if (state.damaged[e]) continue;
    double hi = -std::numeric_limits<double>::infinity();
    double lo = std::numeric_limits<double>::infinity();
    for (int k = field.slotStart[e]; k < field.slotStart[e + 1]; ++k) {
      hi = std::max(hi, slot[field.slots[k]]);
      lo = std::min(lo, slot[field.slots[k]]);
    }
    out[e] = std::isfinite(hi) ? hi : 0.0;
    if (compression) (*compression)[e] = std::isfinite(lo) ? lo : 0.0;
  }
  return out;
}

template <typename Visit>
void forEdgesNear(const FractureField& field, const Vec3& p, Visit visit) {
  const double r = field.settings.kernelRadius;
  const auto c = fractureCell(p, field.cellSize);
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dz = -1; dz <= 1; ++dz) {
        const auto it = field.cells.find(fractureCellKey(c[0] + dx, c[1] + dy, c[2] + dz));
        if (it == field.cells.end()) continue;
        for (int i = it->second.first; i < it->second.second; ++i) {
          const int f = field.cellEdges[i];
          const double d2 = (field.midpoint[f] - p).squaredNorm();
          if (d2 < r * r) visit(f, d2);
        }
      }
    }
  }
}

double kernelMean(const FractureField& field, const std::vector<double>& local,
                  const std::vector<std::uint8_t>& damaged, int e) {
  const double r2 = field.settings.kernelRadius * field.settings.kernelRadius;
  double sum = 0.0, weights = 0.0;
  forEdgesNear(field, field.midpoint[e], [&](int f, double d2) {
    if (damaged[f]) return;
    const double w = (1.0 - d2 / r2) * (1.0 - d2 / r2);
    sum += w * local[f];
    weights += w;
  });
  return weights > 0.0 ? sum / weights : local[e];
}

}  // namespace

FractureField buildFractureField(const SimModel& model, const FractureSettings& settings) {
  if (!(settings.threshold > 0.0))
    throw std::invalid_argument("fracture threshold must be positive");
  if (!(settings.thresholdJitter >= 0.0 && settings.thresholdJitter < 1.0))
    throw std::invalid_argument("fracture threshold jitter must lie in [0, 1)");
  if (!(settings.kernelRadius >= 0.0)) throw std::invalid_argument("kernel radius must be >= 0");
  if (!(settings.compressiveThreshold >= 0.0))
    throw std::invalid_argument("compressive threshold must be >= 0");
  FractureField f;
  f.settings = settings;
  const int nEdges = model.numEdges();
  f.threshold.resize(nEdges);
  f.minThreshold = settings.threshold;
  for (int e = 0; e < nEdges; ++e) {
    f.threshold[e] =
        settings.threshold * (1.0 + settings.thresholdJitter * uniformSigned(settings.seed, e));
    f.minThreshold = std::min(f.minThreshold, f.threshold[e]);
  }
  f.slotStart.assign(nEdges + 1, 0);
  for (const auto& te : model.tetEdges) {
    for (int e : te) ++f.slotStart[e + 1];
  }
  for (int e = 0; e < nEdges; ++e) f.slotStart[e + 1] += f.slotStart[e];
  f.slots.resize(f.slotStart.back());
  std::vector<int> fill(f.slotStart.begin(), f.slotStart.end() - 1);
  for (int t = 0; t < model.numTets(); ++t) {
    for (int k = 0; k < 6; ++k) f.slots[fill[model.tetEdges[t][k]]++] = 6 * t + k;
  }
  f.midpoint.resize(nEdges);
  for (int e = 0; e < nEdges; ++e)
    f.midpoint[e] =
        0.5 * (model.mesh.vertices[model.edges[e][0]] + model.mesh.vertices[model.edges[e][1]]);
  if (settings.kernelRadius > 0.0) {
    f.cellSize = settings.kernelRadius;
    std::vector<std::pair<std::int64_t, int>> keyed(nEdges);
    for (int e = 0; e < nEdges; ++e) {
      const auto c = fractureCell(f.midpoint[e], f.cellSize);
      keyed[e] = {fractureCellKey(c[0], c[1], c[2]), e};
    }
    std::sort(keyed.begin(), keyed.end());
    f.cellEdges.resize(nEdges);
    for (int i = 0; i < nEdges; ++i) {
      f.cellEdges[i] = keyed[i].second;
      auto [it, inserted] = f.cells.try_emplace(keyed[i].first, i, i + 1);
      if (!inserted) it->second.second = i + 1;
    }
  }
  return f;
}

std::vector<double> fractureEdgeStress(const SimModel& model, const FractureField& field,
                                       const SimState& state, bool compressionResists) {
  const std::vector<double> local = localEdgeStress(model, field, state, compressionResists);
  if (field.settings.kernelRadius <= 0.0) return local;
  std::vector<double> out(local.size(), 0.0);
#pragma omp parallel for schedule(static)
  for (int e = 0; e < model.numEdges(); ++e) {
    if (!state.damaged[e]) out[e] = kernelMean(field, local, state.damaged, e);
  }
  return out;
}

FractureReport fracturePass(const SimModel& model, const FractureField& field, SimState& state,
                            bool compressionResists) {
  FractureReport report;
  const bool crushes = field.settings.compressiveThreshold > 0.0;
  std::vector<double> compression;
  const std::vector<double> local =
      localEdgeStress(model, field, state, compressionResists, crushes ? &compression : nullptr);
  const int nEdges = model.numEdges();
  std::vector<char> breaks(nEdges, 0);
  if (crushes) {
    // Crushing is local (no kernel): the scale of the compressive threshold, not its
    // randomness, decides it.
    for (int e = 0; e < nEdges; ++e) {
      if (!state.damaged[e] && -compression[e] > field.settings.compressiveThreshold) breaks[e] = 1;
    }
  }
  if (field.settings.kernelRadius <= 0.0) {
    for (int e = 0; e < nEdges; ++e) {
      if (state.damaged[e]) continue;
      report.maxStressRatio = std::max(report.maxStressRatio, local[e] / field.threshold[e]);
      breaks[e] |= local[e] > field.threshold[e];
    }
  } else {
    // Only edges within R_d of an edge over the smallest threshold can average above theirs.
    std::vector<char> candidate(nEdges, 0);
    for (int e = 0; e < nEdges; ++e) {
      if (state.damaged[e] || local[e] <= field.minThreshold) continue;
      forEdgesNear(field, field.midpoint[e], [&](int f, double) { candidate[f] = 1; });
    }
    std::vector<int> list;
    for (int e = 0; e < nEdges; ++e) {
      if (candidate[e] && !state.damaged[e]) list.push_back(e);
    }
    std::vector<double> mean(list.size());
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < list.size(); ++i)
      mean[i] = kernelMean(field, local, state.damaged, list[i]);
    for (size_t i = 0; i < list.size(); ++i) {
      const int e = list[i];
      report.maxStressRatio = std::max(report.maxStressRatio, mean[i] / field.threshold[e]);
      breaks[e] |= mean[i] > field.threshold[e];
    }
    if (list.empty()) {
      for (int e = 0; e < nEdges; ++e) {
        if (!state.damaged[e])
          report.maxStressRatio = std::max(report.maxStressRatio, local[e] / field.threshold[e]);
      }
    }
  }
  for (int e = 0; e < nEdges; ++e) {
    if (breaks[e]) {
      state.damaged[e] = 1;
      ++report.newlyDamaged;
    }
  }
  if (report.newlyDamaged > 0) ++state.damageRevision;
  return report;
}

}  // namespace galsculpt
