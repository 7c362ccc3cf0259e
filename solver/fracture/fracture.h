// The graph-based fracture pass (paper section 3.1, Algorithm 1), on the finest level: its
// parameters and per-mesh data here; the pass itself is a part of the frame
// (solver/frame/fracture_pass.h), the same on every executor.
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
// - A fracture energy G_c (crack band): thresholds scaled by sqrt(l_ch / h) with the local mesh
//   size h and l_ch = 2 E G_c / threshold^2, so that a broken edge releases G_c per unit of crack
//   area; a sharp crack then runs at the stress intensity sqrt(4 pi E G_c) (about K_Ic) on any
//   mesh, where a fixed threshold makes a finer mesh break earlier.
// - A strain criterion (not in the paper): an edge also breaks, or with no stress threshold
//   only breaks, when its engineering strain passes a limit. A ductile body yields long before
//   its stress can pass a tearing threshold except where it is confined (the hydrostatic
//   tension under a rigid grip or ahead of a notch, which plastic flow does not relieve), so a
//   stress criterion tears it there; its edges' stretch grows where it actually flows.
#pragma once

#include "solver/model/sim_model.h"

namespace galsculpt {

// Throws std::invalid_argument for neither a positive stress nor a positive strain threshold,
// a negative one, or a jitter outside [0, 1).
FractureField buildFractureField(const SimModel& model, const FractureSettings& settings);

// The mesh size at each edge: the edge length of the regular tet with the mean rest volume of
// the tets around it.
std::vector<double> edgeMeshSize(const SimModel& model);
// Each edge's threshold factor sqrt(l_ch / h) for settings.fractureEnergy > 0; empty otherwise.
std::vector<double> fractureSizeScale(const SimModel& model, const FractureSettings& settings);

struct FractureReport {
  int newlyDamaged = 0;  // every edge the pass broke, those of cracked sections included
  // The largest criticality among undamaged edges: edge stress / its threshold, or with a
  // strain criterion edge strain / its limit where that is larger.
  double maxStressRatio = 0.0;
};

}  // namespace galsculpt
