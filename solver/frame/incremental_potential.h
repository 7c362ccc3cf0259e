// The incremental potential of backward Euler and its derivatives, on the executor: two lists of
// terms, the coordinate terms (coordinate_terms.h: inertia, gravity, Rayleigh damping, the soft
// anchors' springs, summed per coordinate in one launch) and the pass terms (pass_terms.h: the
// elements, elastic_term.h, and the colliders, contact_term.h); the backward-Euler gradient g and
// the Newton system H; the potential at a trial step, whole or vertex by vertex (the vertex
// guard). Its functions launch and reduce into the frame's scalars (frame_scalars.h), never
// read: the frame decides when to synchronize.
//
//   E(y) = sum_i m_i/(2h^2) |y_i - xhat_i|^2 - m_i g.y_i + 1/(2h) (alpha m_i |y_i - x_n,i|^2
//          + (y - x_n).beta K0 (y - x_n)) + k_i/2 |y_i - t_i|^2 + elastic(y) + contact(y)
// (k_i, t_i: the soft anchors' springs, held_vertices.h; zero on most vertices)
#pragma once

#include <cmath>
#include <cstdint>

#include "solver/fem/dense_kernels.h"
#include "solver/frame/contact_term.h"
#include "solver/frame/coordinate_terms.h"
#include "solver/frame/elastic_term.h"
#include "solver/frame/frame_data.h"
#include "solver/frame/local_region.h"
#include "solver/frame/pass_terms.h"
#include "solver/frame/piece_residual.h"
#include "solver/frame/plastic_state.h"
#include "solver/model/sim_model.h"

namespace galsculpt {

// The pass terms, in the order of their sums (pass_terms.h): a new term is its file and a place
// here.
template <typename Exec>
using PassTerms = PassTermList<Exec, ElasticTerm, ContactTerm>;

template <typename Exec>
class IncrementalPotential {
 public:
  IncrementalPotential(Exec& ex, const SimModel& model, FrameData<Exec>& data,
                       const PlasticState<Exec>& plastic)
      : ex_(ex), model_(model), d_(data), terms_(PassTermContext<Exec>{ex, model, data, plastic}) {}

  PassTerms<Exec>& passTerms() { return terms_; }
  // The elastic term: the element pass and its gathers (elastic_term.h).
  ElasticTerm<Exec>& elastic() { return terms_.template term<ElasticTerm<Exec>>(); }
  const ElasticTerm<Exec>& elastic() const { return terms_.template term<ElasticTerm<Exec>>(); }
  // The colliders' term: their poses and the forces they take (contact_term.h).
  ContactTerm<Exec>& contact() { return terms_.template term<ContactTerm<Exec>>(); }

  // out = beta K0 (y - x_n).
  void dampedProduct(const double* y, double* out) {
    const double* xn = d_.xn.data();
    const double* frozen = d_.frozenBlocks();
    const int* rowStart = d_.rowStart.data();
    const int* columns = d_.columns.data();
    const double beta = model_.material.dampingStiffness;
    ex_.forEach(d_.n, [=] GALSCULPT_LAMBDA(int r) {
      double acc[3] = {0.0, 0.0, 0.0};
      for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) {
        const int c = columns[k];
        const double d[3] = {y[3 * c] - xn[3 * c], y[3 * c + 1] - xn[3 * c + 1],
                             y[3 * c + 2] - xn[3 * c + 2]};
        double t[3];
        multiply3(frozen + 9 * k, d, t);
        for (int i = 0; i < 3; ++i) acc[i] += t[i];
      }
      for (int i = 0; i < 3; ++i) out[3 * r + i] = beta * acc[i];
    });
  }

  // What the coordinate terms (coordinate_terms.h) read, with βK₀(y - x_n) for the y at hand.
  CoordinateInputs coordinateInputs(const double* dampedK) const {
    return {d_.xhat.data(),
            d_.xn.data(),
            d_.mass.data(),
            d_.springK.data(),
            d_.springTarget.data(),
            dampedK,
            d_.h,
            model_.material.dampingMass,
            {model_.gravity.x(), model_.gravity.y(), model_.gravity.z()}};
  }

  // The incremental potential at y into *out: the coordinate terms at y and the pass terms'
  // energies already evaluated there (at the trial's y with `trial`, otherwise at x).
  void objective(const double* y, bool trial, const double* dampedK, double* out) {
    const CoordinateInputs c = coordinateInputs(dampedK);
    ex_.sum(
        3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { return CoordinateTerms::energy(c, i, y); }, out);
    const auto passEnergies = terms_.energies(trial);
    ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) { *out += passEnergies.sum(); });
  }

  // Each vertex's share of the incremental potential at y: its share of each pass term (a
  // quarter of each element's energy around it, its contact energy) and its own coordinate
  // terms; they sum to the potential. The pass terms must have been evaluated at y (at the
  // trial's y with `trial`, otherwise at x).
  void vertexPotential(const double* y, bool trial, const double* dampedK, double* out) {
    const CoordinateInputs c = coordinateInputs(dampedK);
    const auto shares = terms_.vertexShares(trial);
    ex_.forEach(d_.n, [=] GALSCULPT_LAMBDA(int v) {
      double sum = 0.0;
      shares.add(v, sum);
      for (int k = 0; k < 3; ++k) sum += CoordinateTerms::energy(c, 3 * v + k, y);
      out[v] = sum;
    });
  }

  // g: the coordinate terms' gradients with the pass terms' (in `grad`),
  // zero on anchored vertices.
  void backwardEulerGradient(const double* y, const double* grad, const double* dampedK,
                             double* g) {
    const CoordinateInputs c = coordinateInputs(dampedK);
    const std::uint8_t* fixed = d_.fixed.data();
    ex_.forEach(3 * d_.n, [=] GALSCULPT_LAMBDA(int i) {
      g[i] = fixed[i / 3] ? 0.0 : CoordinateTerms::gradient(c, i, y, grad[i]);
    });
  }

  // H = K + beta/h K0 + the pass terms' diagonal blocks (contact) + M (1/h^2 + alpha/h) + the
  // springs' k I, anchored rows and columns identity-scaled (and in a local iteration those
  // outside the region).
  void buildSystem(const double* y) {
    const double* kb = d_.stiffness.data();
    const double* frozen = d_.frozenBlocks();
    double* hb = d_.system.data();
    const int* blockRow = d_.blockRow.data();
    const int* columns = d_.columns.data();
    const std::uint8_t* fixed = d_.solveFixed();
    // A local iteration's solve reads the region's rows only.
    const std::uint8_t* rows = d_.local ? d_.regionVertex.data() : nullptr;
    const double* mass = d_.mass.data();
    const double h = d_.h;
    const auto passBlocks = terms_.diagonalBlocks();
    const double betaOverH = model_.material.dampingStiffness / h;
    const CoordinateInputs coords = coordinateInputs(nullptr);
    ex_.forEach(d_.blocks, [=] GALSCULPT_LAMBDA(int b) {
      const int r = blockRow[b], c = columns[b];
      if (rows && !rows[r]) return;
      double out[9];
      for (int i = 0; i < 9; ++i) out[i] = kb[9 * b + i] + betaOverH * frozen[9 * b + i];
      if (r == c) {
        if (!fixed[r]) passBlocks.add(r, y, out);
        const double m = mass[r] * CoordinateTerms::massCoefficient(coords);
        for (int i = 0; i < 3; ++i) out[4 * i] += m;
        const double own = CoordinateTerms::diagonal(coords, r);
        for (int i = 0; i < 3; ++i) out[4 * i] += own;
      }
      if (fixed[r] || fixed[c]) {
        const double diag = r == c ? mass[r] / (h * h) : 0.0;
        for (int i = 0; i < 9; ++i) out[i] = i % 4 == 0 ? diag : 0.0;
      }
      for (int i = 0; i < 9; ++i) hb[9 * b + i] = out[i];
    });
  }

  // The backward-Euler gradient at the accepted positions (g; the pass terms' forces in tmp)
  // and its sums (residualSums into residual and forceScale).
  void acceptedResidual() {
    const double* x = d_.x.data();
    dampedProduct(x, d_.dampedK.data());
    terms_.atAccepted(x, d_.tmp.data());
    backwardEulerGradient(x, d_.tmp.data(), d_.dampedK.data(), d_.g.data());
    FrameScalars* sc = d_.sc();
    residualSums(d_.g.data(), d_.tmp.data(), &sc->residual, &sc->forceScale);
  }

  // Whether each trial also forms the residual there (trialG, trialForces; trialResidual and
  // trialForceScale in the scalars): where the frame tests the residual between Newton
  // iterations, so that the accepted trial's read already holds it and the test needs no read
  // of its own (one host wait less an iteration on a device). The sums are the accepted
  // positions' (acceptedResidual) in the same order, so the test sees the same bits.
  bool residualAtTrials() const {
    const StepSettings& s = *d_.settings;
    return s.newtonIterations > 1 && (s.residualTolerance > 0.0 || s.reuseStiffness);
  }

  // |g|^2 (into `residual`) and the squared forces f on the free vertices (into `forceScale`).
  void residualSums(const double* g, const double* f, double* residual, double* forceScale) {
    const std::uint8_t* fixed = d_.fixed.data();
    ex_.sum(
        3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { return g[i] * g[i]; }, residual);
    ex_.sum(
        3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { return fixed[i / 3] ? 0.0 : f[i] * f[i]; },
        forceScale);
  }

  // The Newton step's measures: e0, the slope g.delta, |delta|_inf (deltaMax) and whether g or
  // delta holds a NaN or infinity (bad).
  void stepMeasures() {
    FrameScalars* sc = d_.sc();
    const double* x = d_.x.data();
    objective(x, false, d_.dampedK.data(), &sc->e0);
    const double* g = d_.g.data();
    const double* delta = d_.delta.data();
    ex_.sum(
        3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { return g[i] * delta[i]; }, &sc->slope);
    ex_.sum(
        3 * d_.n,
        [=] GALSCULPT_LAMBDA(int i) {
          return g[i] == g[i] && fabs(g[i]) <= 1.7e308 && delta[i] == delta[i] &&
                         fabs(delta[i]) <= 1.7e308
                     ? 0.0
                     : 1.0;
        },
        &sc->bad);
    ex_.maximum(
        3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { return fabs(delta[i]); }, &sc->deltaMax);
    // What the vertex guard compares its trials with (the pass terms hold x's energies here).
    if (d_.settings->vertexGuard())
      vertexPotential(x, false, d_.dampedK.data(), d_.potentialAtX.data());
  }

  // The pass terms' energies and the potential at x + length delta (e1), with the elements'
  // gradient there (trialGrad).
  void evaluateTrial(double length) {
    double* trial = d_.trial.data();
    const double* x = d_.x.data();
    const double* delta = d_.delta.data();
    ex_.forEach(3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { trial[i] = x[i] + length * delta[i]; });
    evaluateTrialPositions(nullptr);
  }

  // The same at the positions in trial; with `only`, just the flagged elements evaluated again
  // (the others unchanged since the last trial: the vertex guard's rounds). beta K0 (y - x_n)
  // stays in tmp (the vertex guard's shares read it); with residualAtTrials, the residual too,
  // and whether the positions are finite (what the sub-step's end tests of the accepted ones).
  void evaluateTrialPositions(const std::uint8_t* only) {
    const double* trial = d_.trial.data();
    const bool residual = residualAtTrials();
    terms_.atTrial(trial, only, residual ? d_.trialForces.data() : nullptr);
    dampedProduct(trial, d_.tmp.data());
    objective(trial, true, d_.tmp.data(), &d_.sc()->e1);
    if (!residual) return;
    backwardEulerGradient(trial, d_.trialForces.data(), d_.tmp.data(), d_.trialG.data());
    FrameScalars* sc = d_.sc();
    residualSums(d_.trialG.data(), d_.trialForces.data(), &sc->trialResidual, &sc->trialForceScale);
    nonFinite(trial, &sc->trialBad);
    if (trialPieces_ &&
        trialPieces_->launch(ex_, *trialLayout_, d_.trialG.data(), d_.trialForces.data(),
                             d_.fixed.data(), d_.mass.data(), gravity_)) {
      const double* worst = trialPieces_->result();
      ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) { sc->trialWorstPiece = *worst; });
    }
    if (!trialRegion_) return;
    // The region the next iteration would solve from these positions, its size in this read
    // (formRegionAtTrials): the seeds' `outside` from the trial's force scale, as the host forms
    // it from the read (FrameSolver::relativeResidual).
    const double tolerance = regionTolerance_, weight = regionWeight_;
    constexpr double share = LocalRegion<Exec>::kOutsideShare;
    ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) {
      const double target = tolerance * fmax(weight, sqrt(sc->trialForceScale));
      sc->regionOutside = share * share * target * target;
    });
    trialRegion_->launchChoice(d_.trialG.data());
  }

  // Where a device chooses local regions (LocalRegion), each trial that forms the residual also
  // forms the region its positions would give (launchChoice), so that the next iteration's
  // choice needs no read of its own: `region` (null: none), the sub-step's relative
  // `tolerance` and the body's weight (N).
  void formRegionAtTrials(LocalRegion<Exec>* region, double tolerance, double weight) {
    trialRegion_ = region;
    regionTolerance_ = tolerance;
    regionWeight_ = weight;
  }
  bool formsRegionAtTrials() const { return trialRegion_ != nullptr; }
  // The same for the pieces' residuals (PieceResidual, `layout` the body's pieces, built for
  // it already; null: none): the worst goes to trialWorstPiece.
  void formPiecesAtTrials(PieceResidual<Exec>* pieces, const PieceLayout* layout, double gravity) {
    trialPieces_ = pieces;
    trialLayout_ = layout;
    gravity_ = gravity;
  }
  bool formsPiecesAtTrials() const { return trialPieces_ != nullptr; }

  // *out > 0 where positions y (3n) hold a NaN or infinity: the test the sub-step's end makes of
  // the accepted positions and each trial of its own (the two must agree).
  void nonFinite(const double* y, double* out) {
    ex_.sum(
        3 * d_.n,
        [=] GALSCULPT_LAMBDA(int i) { return y[i] == y[i] && fabs(y[i]) <= 1.7e308 ? 0.0 : 1.0; },
        out);
  }

 private:
  Exec& ex_;
  const SimModel& model_;
  FrameData<Exec>& d_;
  PassTerms<Exec> terms_;
  LocalRegion<Exec>* trialRegion_ = nullptr;  // formRegionAtTrials
  double regionTolerance_ = 0.0, regionWeight_ = 0.0;
  PieceResidual<Exec>* trialPieces_ = nullptr;  // formPiecesAtTrials
  const PieceLayout* trialLayout_ = nullptr;
  double gravity_ = 0.0;
};

}  // namespace galsculpt
