// The fracture pass (docs/physics.md, "Fracture"): each undamaged edge's stress, the element
// maximum of n^T sigma n over the elements around it, or its weighted mean within the kernel
// radius where the field has one; crushing under compression; the strain criterion; and which
// edges break, the most critical first when the field asks for it. The frame owns the damage:
// it marks what findBreaks() found (markBroken) and keeps its host copy and revisions.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "solver/fem/dense_kernels.h"
#include "solver/fracture/fracture.h"
#include "solver/frame/download_span.h"
#include "solver/frame/element_pass.h"
#include "solver/model/sim_model.h"

namespace galsculpt {

template <typename Exec>
class FracturePass {
 public:
  // What the pass's kernels hand back: the largest stress ratio, the most critical edge's
  // criticality, and a count (edges that break; edges with a kernel mean).
  struct Scalars {
    double ratio = 0.0, critical = 0.0, count = 0.0;
  };
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;
  template <typename T>
  using Mirror = typename Exec::template Mirror<T>;

  // Mirrors the model's fracture field (which must be enabled) and sets up the pass's scratch.
  FracturePass(const Exec& ex, const SimModel& model)
      : ex_(ex), model_(model), tets_(model.numTets()), edges_(model.numEdges()) {
    const FractureField& field = model.fracture;
    scalars_.resize(1);
    edgeSlotStart_.mirror(field.slotStart);
    edgeSlots_.mirror(field.slots);
    threshold_.mirror(field.threshold);
    strainLimit_.mirror(field.strainLimit);
    restLength_.mirror(field.restLength);
    edgeEnds_.mirror(model_.edges.empty() ? nullptr : model_.edges[0].data(),
                     field.strainLimit.empty() ? 0 : 2 * model_.edges.size());
    midpoint_.mirror(field.midpoint.empty() ? nullptr : field.midpoint[0].data(),
                     3 * field.midpoint.size());
    cellBegin_.mirror(field.cellBegin);
    cellEnd_.mirror(field.cellEnd);
    cellEdges_.mirror(field.cellEdges);
    edgeCell_.mirror(field.edgeCell);
    cellNeighbors_.mirror(field.cellNeighbors);
    cellHot_.resize(field.cells());
    slotStress_.resize(6 * static_cast<size_t>(tets_));
    for (Buffer<double>* b : {&localStress_, &compression_, &mean_, &stretch_}) b->resize(edges_);
    breaks_.resize(edges_);
    hot_.resize(edges_);
    clearUnusedCriteria();
  }

  // What a criterion the scene does not use reads, set once rather than on every pass: no
  // strain criterion, no strain ratio; no stress criterion, zero stress ratios. (Public, as
  // every function below: nvcc refuses extended lambdas in private member functions and in
  // constructors.)
  void clearUnusedCriteria() {
    const FractureField& field = model_.fracture;
    double* stretch = stretch_.data();
    double* ratio = mean_.data();
    double* local = localStress_.data();
    double* compression = compression_.data();
    const bool strain = !field.strainLimit.empty(), stress = field.settings.threshold > 0.0;
    ex_.forEach(edges_, [=] GALSCULPT_LAMBDA(int e) {
      if (!strain) stretch[e] = -kInf;
      if (!stress) ratio[e] = local[e] = compression[e] = 0.0;
    });
  }

  // Which undamaged edges break at positions `x` (evaluate, then the most critical first):
  // how many, and the largest criticality (FractureReport). Nothing is damaged yet. Where
  // launchSearch() ran for these positions and its scalars came down with another read
  // (heldSearch), those are the answer: no read of its own.
  FractureReport findBreaks(const ElementInputs& in, const double* x, const std::uint8_t* damaged) {
    if (searchHeld_) {
      searchHeld_ = false;
      return reportOf(held_);
    }
    const FractureSettings& settings = model_.fracture.settings;
    if (settings.criticalFraction > 0.0) {
      evaluate(in, x, damaged, false);
      // The most critical breaks first (fracture_field.h).
      std::uint8_t* breaks = breaks_.data();
      const double* ratio = mean_.data();
      Scalars* sc = scalars_.data();
      const double* stretch = stretch_.data();
      const double* compression = compression_.data();
      const double crush = settings.crushRatio();
      const double* threshold = threshold_.data();
      auto criticality = [=] GALSCULPT_LAMBDA(int e) {
        const double crushed = crush > 0.0 ? -compression[e] / (crush * threshold[e]) : 0.0;
        return breaks[e] ? fmax(fmax(ratio[e], crushed), stretch[e]) : -kInf;
      };
      ex_.maximum(edges_, criticality, &sc->critical);
      double most = 0.0;
      ex_.read(&sc->critical, &most, 1);
      const double below = settings.criticalFraction * most;
      ex_.forEach(edges_, [=] GALSCULPT_LAMBDA(int e) {
        if (breaks[e] && !(criticality(e) >= below)) breaks[e] = 0;
      });
      sums();
    } else {
      launchSearch(in, x, damaged);
    }
    Scalars read;
    ex_.read(scalars_.data(), &read, 1);
    return reportOf(read);
  }

  // findBreaks()'s launches without its read, where it needs none in between (no critical
  // fraction): false otherwise. The caller brings the scalars down with its own read
  // (searchSpan) and hands them over (holdSearch) for the next findBreaks().
  bool launchSearch(const ElementInputs& in, const double* x, const std::uint8_t* damaged) {
    if (model_.fracture.settings.criticalFraction > 0.0) return false;
    evaluate(in, x, damaged, false);
    sums();
    return true;
  }
  DownloadSpan searchSpan() { return {scalars_.data(), &held_, sizeof(Scalars)}; }
  void holdSearch(bool held) { searchHeld_ = held; }

  static FractureReport reportOf(const Scalars& read) {
    FractureReport report;
    report.maxStressRatio = std::max(0.0, read.ratio);
    report.newlyDamaged = static_cast<int>(read.count);
    return report;
  }

  // The largest ratio and the breaks' count into the scalars.
  void sums() {
    const std::uint8_t* breaks = breaks_.data();
    const double* ratio = mean_.data();
    const double* stretch = stretch_.data();
    Scalars* sc = scalars_.data();
    ex_.maximum(
        edges_, [=] GALSCULPT_LAMBDA(int e) { return fmax(ratio[e], stretch[e]); }, &sc->ratio);
    ex_.sum(
        edges_, [=] GALSCULPT_LAMBDA(int e) { return breaks[e] ? 1.0 : 0.0; }, &sc->count);
  }

  // Damages for good the edges findBreaks() found.
  void markBroken(std::uint8_t* damaged) {
    const std::uint8_t* breaks = breaks_.data();
    ex_.forEach(edges_, [=] GALSCULPT_LAMBDA(int e) {
      if (breaks[e]) damaged[e] = 1;
    });
  }

  // Per edge, its stress over its threshold as the last evaluate() left it (-inf where it was
  // skipped).
  const double* stressRatio() const { return mean_.data(); }

  // Per edge: its stress over its threshold (`mean_`; -inf where no edge near it is close to
  // breaking, unless `everyEdge`) and whether it breaks (`breaks_`).
  void evaluate(const ElementInputs& in, const double* x, const std::uint8_t* damaged,
                bool everyEdge) {
    const FractureField& field = model_.fracture;
    const int edges = edges_;
    if (!(field.settings.threshold > 0.0)) {  // strain alone: no element stress to project
      std::uint8_t* breaks = breaks_.data();
      ex_.forEach(edges, [=] GALSCULPT_LAMBDA(int e) { breaks[e] = 0; });
      edgeStrain(x, damaged);  // the stress ratios stay the zeros the constructor set
      return;
    }
    // Element edge stresses into slots 6 t + k.
    double* slot = slotStress_.data();
    const ElementModel element{in, model_.material.model, model_.material.elementLame(),
                               model_.material.compressionResists};
    launchEdgeNormalStress(ex_, element, tets_, x, slot);
    const int* slotStart = edgeSlotStart_.data();
    const int* slots = edgeSlots_.data();
    double* local = localStress_.data();
    double* compression = compression_.data();
    ex_.forEach(edges, [=] GALSCULPT_LAMBDA(int e) {
      local[e] = 0.0;
      compression[e] = 0.0;
      if (damaged[e]) return;
      double hi = -kInf, lo = kInf;
      for (int k = slotStart[e]; k < slotStart[e + 1]; ++k) {
        hi = fmax(hi, slot[slots[k]]);
        lo = fmin(lo, slot[slots[k]]);
      }
      local[e] = fabs(hi) <= 1.7e308 ? hi : 0.0;
      compression[e] = fabs(lo) <= 1.7e308 ? lo : 0.0;
    });
    const double* threshold = threshold_.data();
    std::uint8_t* breaks = breaks_.data();
    double* ratio = mean_.data();
    // Crushing scales per edge as the tensile threshold does (fracture_field.h).
    const double crush = field.settings.crushRatio();
    if (field.settings.kernelRadius <= 0.0) {
      ex_.forEach(edges, [=] GALSCULPT_LAMBDA(int e) {
        breaks[e] = 0;
        ratio[e] = -kInf;
        if (damaged[e]) return;
        breaks[e] =
            (crush > 0.0 && -compression[e] > crush * threshold[e]) || local[e] > threshold[e];
        ratio[e] = local[e] / threshold[e];
      });
    } else {
      kernelMeanStress(damaged, everyEdge);
    }
    edgeStrain(x, damaged);
  }

  // The strain criterion (fracture.h): each undamaged edge's engineering strain over its limit
  // (`stretch_`, -inf without the criterion), and it breaks past 1. Local: the edge's own
  // stretch already averages the strain along it.
  void edgeStrain(const double* x, const std::uint8_t* damaged) {
    if (model_.fracture.strainLimit.empty()) return;  // -inf throughout (the constructor)
    double* stretch = stretch_.data();
    const int* ends = edgeEnds_.data();
    const double* limit = strainLimit_.data();
    const double* length = restLength_.data();
    std::uint8_t* breaks = breaks_.data();
    ex_.forEach(edges_, [=] GALSCULPT_LAMBDA(int e) {
      stretch[e] = -kInf;
      if (damaged[e]) return;
      const double* a = x + 3 * ends[2 * e];
      const double* b = x + 3 * ends[2 * e + 1];
      const double d0 = b[0] - a[0], d1 = b[1] - a[1], d2 = b[2] - a[2];
      stretch[e] = (sqrt(d0 * d0 + d1 * d1 + d2 * d2) / length[e] - 1.0) / limit[e];
      if (stretch[e] > 1.0) breaks[e] = 1;
    });
  }

  // The non-local criterion: each edge's stress is the weighted mean over the undamaged edges
  // within the kernel radius (fracture.h). Only edges with an edge over the smallest threshold
  // within reach can average above theirs; the others are skipped unless `everyEdge`.
  void kernelMeanStress(const std::uint8_t* damaged, bool everyEdge) {
    const FractureField& field = model_.fracture;
    const int edges = edges_;
    const double* local = localStress_.data();
    const double* compression = compression_.data();
    const double* threshold = threshold_.data();
    std::uint8_t* breaks = breaks_.data();
    double* ratio = mean_.data();
    const double crush = field.settings.crushRatio();
    Scalars* sc = scalars_.data();
    // Only edges within R_d of an edge over the smallest threshold can average above theirs.
    const double minThreshold = field.minThreshold;
    std::uint8_t* hot = hot_.data();
    ex_.forEach(edges,
                [=] GALSCULPT_LAMBDA(int e) { hot[e] = !damaged[e] && local[e] > minThreshold; });
    const double radius = field.settings.kernelRadius;
    const double* mid = midpoint_.data();
    const int* cellBegin = cellBegin_.data();
    const int* cellEnd = cellEnd_.data();
    const int* cellEdges = cellEdges_.data();
    const int* edgeCell = edgeCell_.data();
    const int* neighbors = cellNeighbors_.data();
    std::uint8_t* cellHot = cellHot_.data();
    ex_.forEach(model_.fracture.cells(), [=] GALSCULPT_LAMBDA(int c) {
      std::uint8_t any = 0;
      for (int i = cellBegin[c]; i < cellEnd[c]; ++i) any |= hot[cellEdges[i]];
      cellHot[c] = any;
    });
    ex_.forEach(edges, [=] GALSCULPT_LAMBDA(int e) {
      breaks[e] = !damaged[e] && crush > 0.0 && -compression[e] > crush * threshold[e];
      ratio[e] = -kInf;
      if (damaged[e]) return;
      const int* around = neighbors + 27 * edgeCell[e];
      bool near = false;
      for (int k = 0; k < 27; ++k) near = near || (around[k] >= 0 && cellHot[around[k]]);
      if (!near && !everyEdge) return;  // nothing near it can break it: common and cheap
      bool candidate = false;
      double sum = 0.0, weights = 0.0;
      const double r2 = radius * radius;
      for (int k = 0; k < 27; ++k) {
        const int c = around[k];
        if (c < 0) continue;
        for (int i = cellBegin[c]; i < cellEnd[c]; ++i) {
          const int f = cellEdges[i];
          double d2 = 0.0;
          for (int j = 0; j < 3; ++j)
            d2 += (mid[3 * f + j] - mid[3 * e + j]) * (mid[3 * f + j] - mid[3 * e + j]);
          if (!(d2 < r2)) continue;
          candidate = candidate || hot[f];
          if (damaged[f]) continue;
          const double w = (1.0 - d2 / r2) * (1.0 - d2 / r2);
          sum += w * local[f];
          weights += w;
        }
      }
      if (!candidate && !everyEdge) return;
      const double mean = weights > 0.0 ? sum / weights : local[e];
      ratio[e] = mean / threshold[e];
      breaks[e] = breaks[e] || mean > threshold[e];
    });
    // Without any candidate the ratio is the local one (the pass reports the largest ratio).
    ex_.sum(
        edges, [=] GALSCULPT_LAMBDA(int e) { return ratio[e] > -1.7e308 ? 1.0 : 0.0; }, &sc->count);
    ex_.forEach(edges, [=] GALSCULPT_LAMBDA(int e) {
      if (sc->count == 0.0 && !damaged[e]) ratio[e] = local[e] / threshold[e];
    });
  }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  const Exec& ex_;
  const SimModel& model_;
  int tets_ = 0, edges_ = 0;
  Mirror<int> edgeSlotStart_, edgeSlots_, cellBegin_, cellEnd_, cellEdges_, edgeCell_,
      cellNeighbors_;
  Mirror<double> threshold_, midpoint_, strainLimit_, restLength_;
  Mirror<int> edgeEnds_;  // (2 nEdges) strain criterion only
  Buffer<double> slotStress_, localStress_, compression_, mean_, stretch_;
  Buffer<Scalars> scalars_;
  Scalars held_{};           // a search's scalars, read with another read (searchSpan)
  bool searchHeld_ = false;  // and to be taken by the next findBreaks()
  Buffer<std::uint8_t> breaks_, hot_, cellHot_;
};

}  // namespace galsculpt
