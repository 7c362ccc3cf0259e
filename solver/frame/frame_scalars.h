// The scalars a frame's kernels hand back to the host: one struct in executor memory, written by
// reductions and single-item launches, read whole once per Newton iteration, per trial of the
// line search and at a sub-step's end (one host synchronization each), or in part (the vertex
// guard's levels, the null step's |g|^2).
#pragma once

namespace galsculpt {

struct FrameScalars {
  static constexpr int kGuardLevels = 24;  // the vertex guard's thresholds: the excess times 2^-k

  double elastic = 0.0, contact = 0.0;            // energies at x
  double trialElastic = 0.0, trialContact = 0.0;  // energies at the trial
  double e0 = 0.0, e1 = 0.0;                      // the incremental potential at x, at the trial
  double slope = 0.0;                             // g . delta along the Newton step
  double deltaMax = 0.0;                          // |delta|_inf
  double bad = 0.0;                               // > 0: a NaN or infinity in the step or x
  double residual = 0.0;                          // |g|^2 at the accepted positions
  double forceScale = 0.0;  // |f|^2 of the elastic and contact forces on free vertices
  // The same two at the last trial, where the frame tests residuals between Newton iterations
  // (IncrementalPotential::residualAtTrials): an accepted trial's are the accepted positions'.
  double trialResidual = 0.0, trialForceScale = 0.0;
  double trialBad = 0.0;  // there too: > 0 where the trial's positions hold a NaN or infinity
  double trialWorstPiece = -1.0;  // and the worst piece's (a device's: formPiecesAtTrials)
  double r0 = 0.0, r1 = 0.0;      // |b|^2 and |b - A delta|^2 around the V-cycles' solve
  // PCG's |r| / |b| and iterations in the Newton step's solve (LinearSolve::takeSolve).
  double pcgReduction = 0.0, pcgIterations = 0.0;
  // A device's dense factorization of the coarsest level failed (not positive definite): its
  // status, which the host did not wait for, rides the Newton iteration's read
  // (LinearSolve::coarseFactorFailed).
  double coarseFailed = 0.0;
  double inverted = 0.0, trialInverted = 0.0;  // intact elements inside out at x, at the trial
  double kept = 0.0;                           // elements whose stiffness the pass kept
  double switched = 0.0;  // damaged elements whose open cracks differ from the stiffness's
  // The vertex guard's round: the guarded step's slope, the elements evaluated again, the
  // vertices shortened, and per level the rises above it (the last: every rise).
  double guardSlope = 0.0, guardElements = 0.0, guardCount = 0.0;
  double guardLevel[kGuardLevels + 1] = {};
  // The local iteration's region (local_region.h): its vertices, and the body's free vertices;
  // the seeds' threshold on |g_v|^2, and whether a |g_v|^2 was not finite (a device's choice).
  double regionVertices = 0.0, freeVertices = 0.0;
  double regionSeed = 0.0, regionBad = 0.0;
  double regionOutside = 0.0;  // the |g_v|^2 the seeds may leave outside, summed (a device's)
};

}  // namespace galsculpt
