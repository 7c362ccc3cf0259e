#include "solver/fracture/fracture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "solver/fem/isotropic_material.h"

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

// Sorts the edges by the cell of their rest midpoint and numbers the cells in key order, each
// with its 27 neighbours.
void buildKernelGrid(FractureField& f, double cellSize) {
  const int nEdges = static_cast<int>(f.midpoint.size());
  f.cellSize = cellSize;
  std::vector<std::pair<std::int64_t, int>> keyed(nEdges);
  for (int e = 0; e < nEdges; ++e) {
    const auto c = fractureCell(f.midpoint[e], cellSize);
    keyed[e] = {fractureCellKey(c[0], c[1], c[2]), e};
  }
  std::sort(keyed.begin(), keyed.end());
  f.cellEdges.resize(nEdges);
  f.edgeCell.assign(nEdges, -1);
  std::unordered_map<std::int64_t, int> index;
  for (int i = 0; i < nEdges; ++i) {
    f.cellEdges[i] = keyed[i].second;
    if (i == 0 || keyed[i].first != keyed[i - 1].first) {
      index.emplace(keyed[i].first, f.cells());
      f.cellBegin.push_back(i);
      f.cellEnd.push_back(i);
    }
    ++f.cellEnd.back();
    f.edgeCell[keyed[i].second] = f.cells() - 1;
  }
  f.cellNeighbors.assign(27 * static_cast<size_t>(f.cells()), -1);
  for (int c = 0; c < f.cells(); ++c) {
    const auto at = fractureCell(f.midpoint[f.cellEdges[f.cellBegin[c]]], cellSize);
    int k = 0;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz, ++k) {
          const auto it = index.find(fractureCellKey(at[0] + dx, at[1] + dy, at[2] + dz));
          if (it != index.end()) f.cellNeighbors[27 * c + k] = it->second;
        }
  }
}

}  // namespace

std::vector<double> edgeMeshSize(const SimModel& model) {
  std::vector<double> volume(model.numEdges(), 0.0);
  std::vector<int> count(model.numEdges(), 0);
  for (int t = 0; t < model.numTets(); ++t)
    for (int e : model.tetEdges[t]) {
      volume[e] += model.rest[t].volume;
      ++count[e];
    }
  std::vector<double> size(model.numEdges());
  for (int e = 0; e < model.numEdges(); ++e)
    size[e] = std::cbrt(6.0 * std::sqrt(2.0) * volume[e] / std::max(count[e], 1));
  return size;
}

std::vector<double> fractureSizeScale(const SimModel& model, const FractureSettings& settings) {
  if (!(settings.fractureEnergy > 0.0)) return {};
  const double youngs = youngsModulus(model.material.lame);
  if (!(youngs > 0.0)) throw std::invalid_argument("a fracture energy needs a Young's modulus");
  // The stress at break: the threshold, or for a strain criterion alone E times its strain
  // (the linear elastic crack band, docs/physics.md).
  const double atBreak =
      settings.threshold > 0.0 ? settings.threshold : youngs * settings.strainThreshold;
  const double characteristic = 2.0 * youngs * settings.fractureEnergy / (atBreak * atBreak);
  std::vector<double> scale = edgeMeshSize(model);
  for (double& s : scale) s = std::sqrt(characteristic / s);
  return scale;
}

FractureField buildFractureField(const SimModel& model, const FractureSettings& settings) {
  if (!(settings.threshold >= 0.0) || !(settings.strainThreshold >= 0.0))
    throw std::invalid_argument("fracture thresholds must be >= 0");
  if (!(settings.threshold > 0.0) && !(settings.strainThreshold > 0.0))
    throw std::invalid_argument("fracture needs a positive stress or strain threshold");
  if (!(settings.thresholdJitter >= 0.0 && settings.thresholdJitter < 1.0))
    throw std::invalid_argument("fracture threshold jitter must lie in [0, 1)");
  if (!(settings.kernelRadius >= 0.0)) throw std::invalid_argument("kernel radius must be >= 0");
  if (!(settings.criticalFraction >= 0.0 && settings.criticalFraction <= 1.0))
    throw std::invalid_argument("critical fraction must lie in [0, 1]");
  if (!(settings.partingFraction >= 0.0 && settings.partingFraction <= 1.0))
    throw std::invalid_argument("parting fraction must lie in [0, 1]");
  if (!(settings.compressiveThreshold >= 0.0))
    throw std::invalid_argument("compressive threshold must be >= 0");
  if (!(settings.fractureEnergy >= 0.0))
    throw std::invalid_argument("fracture energy must be >= 0");
  FractureField f;
  f.settings = settings;
  const int nEdges = model.numEdges();
  const std::vector<double> scale = fractureSizeScale(model, settings);
  const bool stress = settings.threshold > 0.0, strain = settings.strainThreshold > 0.0;
  f.threshold.resize(nEdges);
  if (strain) {
    f.strainLimit.resize(nEdges);
    f.restLength.resize(nEdges);
  }
  f.minThreshold = kNeverBreaks;
  for (int e = 0; e < nEdges; ++e) {
    const double factor = (scale.empty() ? 1.0 : scale[e]) *
                          (1.0 + settings.thresholdJitter * uniformSigned(settings.seed, e));
    f.threshold[e] = stress ? settings.threshold * factor : kNeverBreaks;
    f.minThreshold = std::min(f.minThreshold, f.threshold[e]);
    if (!strain) continue;
    f.strainLimit[e] = settings.strainThreshold * factor;
    f.restLength[e] =
        (model.mesh.vertices[model.edges[e][1]] - model.mesh.vertices[model.edges[e][0]]).norm();
  }
  if (nEdges == 0) f.minThreshold = stress ? settings.threshold : kNeverBreaks;
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
  if (settings.kernelRadius > 0.0) buildKernelGrid(f, settings.kernelRadius);
  if (settings.partingFraction > 0.0) f.tetNeighbours = tetFaceNeighbours(model.mesh);
  f.enabled = true;
  return f;
}

}  // namespace galsculpt
