// The line search of a Newton step: backtracking on the incremental potential (Armijo), a
// shortened step lengthened again while the potential keeps falling, steps refused for turning
// elements inside out, and the vertex guard (StepSettings::vertexGuard), which shortens only the
// vertices whose share of the potential rose. Trials are evaluated by the incremental potential
// (incremental_potential.h); every judgement reads the frame's scalars (frame_scalars.h) once.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "solver/frame/frame_data.h"
#include "solver/frame/frame_loop.h"
#include "solver/frame/incremental_potential.h"
#include "solver/frame/step.h"

namespace galsculpt {

template <typename Exec>
class LineSearch {
 public:
  LineSearch(Exec& ex, FrameData<Exec>& data, IncrementalPotential<Exec>& potential)
      : ex_(ex), d_(data), potential_(potential) {}

  // Whether the trial at `length` (its scalars in `read`) lowers the potential enough: Armijo
  // with `sufficient`, up to the sums' round-off.
  static bool descent(const FrameScalars& read, double length, double sufficient) {
    const double e0 = read.e0, e1 = read.e1;
    return std::isfinite(e1) && e1 <= e0 + sufficient * length * read.slope + 1e-12 * std::abs(e0);
  }

  // A shortened step at which the potential still falls at least half as steeply as the slope
  // says is doubled while the potential keeps falling, short of the refused length; the trial
  // evaluated last is the accepted one's. The quadratic fit through a refused length puts the
  // minimum far too short where the potential kinks instead of curving: a step that closes a
  // body's cracks (or opens them) rises steeply past the switch, and backtracking would take a
  // tenth of the step each iteration.
  double lengthened(SubstepOutcome& result, FrameScalars& read, double length, double refused,
                    double sufficient) {
    double best = length, bestEnergy = read.e1;
    const double inverted = read.inverted;
    while (read.e1 - read.e0 <= 0.5 * best * read.slope && 2.0 * best < refused) {
      potential_.evaluateTrial(2.0 * best);
      result.energyPasses += 1.0;
      ex_.read(d_.sc(), &read, 1);
      const bool better = !(read.bad > 0.0) && descent(read, 2.0 * best, sufficient) &&
                          read.e1 < bestEnergy && read.trialInverted <= inverted;
      if (!better) {
        potential_.evaluateTrial(best);
        result.energyPasses += 1.0;
        ex_.read(d_.sc(), &read, 1);
        return best;
      }
      best *= 2.0;
      bestEnergy = read.e1;
    }
    return best;
  }

  static constexpr double kShortestStep = 1e-8;
  // Shorter than this, a step refused only for turning elements inside out is taken anyway
  // (after the lengths 1, 1/2, 1/4 all inverted).
  static constexpr double kInversionGiveUp = 1e-2;

  // Backtracking on the step evaluated at full length (`read`: its scalars, already read):
  // shortens it (shorterStep) until the potential drops (Armijo with the line search, plain
  // decrease without) without turning more intact elements inside out. Returns the accepted
  // length, something under kShortestStep when none descends, or -1 for NaN; `read` holds the
  // scalars of the last trial.
  double search(SubstepOutcome& result, FrameScalars& read, double pcgReduction) {
    const StepSettings& s = *d_.settings;
    const double sufficient = s.lineSearch ? 1e-4 : 0.0;
    double stepLength = 1.0;
    double inverting = 0.0;  // the longest length refused only because it inverted elements
    double refused = 0.0;    // the shortest length refused so far (0: none)
    bool guarded = !s.vertexGuard(), folded = false;
    for (;; ex_.read(d_.sc(), &read, 1)) {
      if (stepLength == 1.0)
        result.linearResidualReduction =
            s.pcg() ? pcgReduction : (read.r0 > 0.0 ? std::sqrt(read.r1 / read.r0) : 0.0);
      if (read.bad > 0.0 || !std::isfinite(read.elastic)) return -1.0;
      // A null step (the linear solve had nothing to do: the gradient was already within its
      // target) moves nothing and is taken. Judged by the energy it could be refused: e0 and e1
      // are sums whose round-off (a cracked element's energy is a difference of its strains and
      // openings) exceeds 1e-12 of a nearly stress-free body's tiny potential: refused at every
      // length, it would fail the sub-step and every retry, and freeze the body.
      if (read.deltaMax == 0.0) return stepLength;
      const double e0 = read.e0, e1 = read.e1;
      // A step that turns more elements inside out is shortened (under extreme loads the energy
      // alone may descend through an inversion), down to kInversionGiveUp (below).
      const bool descends = descent(read, stepLength, sufficient);
      if (descends && read.trialInverted <= read.inverted)
        return refused > 0.0 && !folded ? lengthened(result, read, stepLength, refused, sufficient)
                                        : stepLength;
      if (descends && inverting == 0.0) inverting = stepLength;
      if (!guarded) {  // the full step failed: shorten it only where the potential rose
        guarded = true;
        const FrameScalars full = read;
        if (vertexGuard(result, read)) return 1.0;
        if (read.guardSlope < 0.0 && std::isfinite(read.e1)) {
          // Back off the guarded step as a whole: it is the step from here on.
          foldGuardIntoStep();
          inverting = 0.0;
          folded = true;
          continue;
        }
        read = full;  // back to shortening the whole full step
      }
      refused = stepLength;
      stepLength = shorterStep(stepLength, e0, e1, read);
      ++result.backtracks;
      // An element on the edge of inversion that the solution turns over (a sliver, a plastic
      // rest shape) refuses every length: rather than freezing the body, take the descending
      // step; the frame reports the elements it leaves inside out (a warning).
      if (stepLength < kInversionGiveUp && inverting > 0.0) {
        potential_.evaluateTrial(inverting);
        result.energyPasses += 1.0;
        ex_.read(d_.sc(), &read, 1);
        return inverting;
      }
      if (stepLength < kShortestStep) return stepLength;
      potential_.evaluateTrial(stepLength);
      result.energyPasses += 1.0;
    }
  }

  static constexpr int kGuardRounds = 6;
  static constexpr int kGuardLevels = FrameScalars::kGuardLevels;

  // The vertex guard (StepSettings::vertexGuard), after the full step raised the potential or
  // turned elements inside out. Each round, the vertices whose share of the potential rose the
  // most (the fewest whose rises add up to twice the excess over the accepted decrease, found
  // among thresholds excess 2^-k, or nine tenths of all rises where they add up to less) and those
  // of elements the trial turned over shorten their own steps: to the minimum of the quadratic
  // through their share at x, their slope and their share at the trial, kept within a tenth and a
  // half of their length. Only the elements around them are evaluated again. (A vertex's share may
  // rise in a good step, its neighbours' falling more: shortening every vertex whose share rose
  // would hold back large parts of a body that moves well.) True when a trial descends (Armijo on
  // the shortened step's slope) without turning more elements over: trial and its scalars (`read`)
  // are then the accepted step. False leaves the caller to back off the whole step.
  bool vertexGuard(SubstepOutcome& result, FrameScalars& read) {
    const double sufficient = d_.settings->lineSearch ? 1e-4 : 0.0;
    double* length = d_.guardLength.data();
    double* rise = d_.potentialAtTrial.data();  // the trial's shares, then their rises
    const double* atX = d_.potentialAtX.data();
    std::uint8_t* changed = d_.guardChanged.data();
    std::uint8_t* dirty = d_.guardDirty.data();
    const std::uint8_t* fixed = d_.solveFixed();  // what the step holds still
    const double* g = d_.g.data();
    const double* delta = d_.delta.data();
    const double* x = d_.x.data();
    double* trial = d_.trial.data();
    const double* invertedAtX = d_.elemInverted.data();
    const double* invertedAtTrial = d_.trialInverted.data();
    const int* vStart = d_.vertexSlotStart.data();
    const int* vSlots = d_.vertexSlots.data();
    const int* tv = d_.tetVertices.data();
    FrameScalars* sc = d_.sc();
    ex_.forEach(d_.n, [=] GALSCULPT_LAMBDA(int v) { length[v] = 1.0; });
    read.guardSlope = read.slope;  // the full step's
    for (int round = 0; round < kGuardRounds; ++round) {
      // The rises (0 where the vertex cannot move) and, in `changed`, who the trial turned over.
      potential_.vertexPotential(trial, true, d_.tmp.data(), rise);
      ex_.forEach(d_.n, [=] GALSCULPT_LAMBDA(int v) {
        bool turned = false;
        for (int i = vStart[v]; i < vStart[v + 1] && !turned; ++i)
          turned = invertedAtTrial[vSlots[i] / 4] > invertedAtX[vSlots[i] / 4];
        const bool moves = !fixed[v] && length[v] > 0.0;
        changed[v] = moves && turned;
        rise[v] = moves ? fmax(rise[v] - atX[v], 0.0) : 0.0;
      });
      const double excess =
          read.e1 - read.e0 - sufficient * read.guardSlope - 1e-12 * std::abs(read.e0);
      double threshold = std::numeric_limits<double>::infinity();  // only the turned over
      if (excess > 0.0) {
        for (int k = 0; k < kGuardLevels; ++k) {
          const double level = std::ldexp(excess, -k);
          ex_.sum(
              d_.n, [=] GALSCULPT_LAMBDA(int v) { return rise[v] > level ? rise[v] : 0.0; },
              &sc->guardLevel[k]);
        }
        ex_.sum(
            d_.n, [=] GALSCULPT_LAMBDA(int v) { return rise[v]; }, &sc->guardLevel[kGuardLevels]);
        double levels[kGuardLevels + 1];
        ex_.read(sc->guardLevel, levels, kGuardLevels + 1);
        // Twice the excess, or nine tenths of all the rises where they add up to less (a rise
        // concentrated on one element's four vertices is about the excess itself).
        const double wanted = std::min(2.0 * excess, 0.9 * levels[kGuardLevels]);
        threshold = 0.0;  // every rise, if no level gathers enough
        for (int k = 0; k < kGuardLevels; ++k) {
          if (levels[k] >= wanted) {
            threshold = std::ldexp(excess, -k);
            break;
          }
        }
      }
      ex_.forEach(d_.n, [=] GALSCULPT_LAMBDA(int v) {
        const bool turned = changed[v];
        changed[v] = 0;
        if (!turned && !(rise[v] > threshold)) return;
        double slope = 0.0;  // along this vertex's shortened step
        for (int k = 0; k < 3; ++k) slope += length[v] * g[3 * v + k] * delta[3 * v + k];
        const double curvature = rise[v] - slope;
        // Never to nothing: a vertex held still every iteration would never get there.
        double factor = 0.5;
        if (slope < 0.0 && curvature > 0.0)
          factor = fmax(0.1, fmin(0.5, -slope / (2.0 * curvature)));
        else if (!(slope < 0.0))
          factor = 0.1;  // no descent here
        length[v] *= factor;
        changed[v] = 1;
      });
      ex_.sum(
          d_.n, [=] GALSCULPT_LAMBDA(int v) { return static_cast<double>(changed[v]); },
          &sc->guardCount);
      ex_.forEach(d_.tets, [=] GALSCULPT_LAMBDA(int t) {
        dirty[t] = changed[tv[4 * t]] | changed[tv[4 * t + 1]] | changed[tv[4 * t + 2]] |
                   changed[tv[4 * t + 3]];
      });
      ex_.forEach(3 * d_.n,
                  [=] GALSCULPT_LAMBDA(int i) { trial[i] = x[i] + length[i / 3] * delta[i]; });
      ex_.sum(
          d_.tets, [=] GALSCULPT_LAMBDA(int t) { return static_cast<double>(dirty[t]); },
          &sc->guardElements);
      potential_.evaluateTrialPositions(dirty);
      ex_.sum(
          3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { return length[i / 3] * g[i] * delta[i]; },
          &sc->guardSlope);
      ex_.read(d_.sc(), &read, 1);
      ++result.backtracks;
      result.energyPasses += read.guardElements / std::max(d_.tets, 1);
      if (!(read.guardCount > 0.0) || !std::isfinite(read.e1)) return false;
      if (read.e1 <= read.e0 + sufficient * read.guardSlope + 1e-12 * std::abs(read.e0) &&
          read.trialInverted <= read.inverted)
        return true;
    }
    return false;
  }

  // The guarded step (each vertex's length times its Newton step) becomes the step: delta and
  // its slope; the trial already evaluated is its full length.
  void foldGuardIntoStep() {
    double* delta = d_.delta.data();
    const double* length = d_.guardLength.data();
    FrameScalars* sc = d_.sc();
    ex_.forEach(3 * d_.n, [=] GALSCULPT_LAMBDA(int i) { delta[i] *= length[i / 3]; });
    ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) { sc->slope = sc->guardSlope; });
  }

  // The next trial length after `length` failed: the minimum of the quadratic through e0, the
  // slope and e1, kept within a tenth and a half of `length` (a step 2^-17 too long then takes
  // about five evaluations, not seventeen halvings); half where the energy says nothing (an
  // inversion, no descent direction).
  static double shorterStep(double length, double e0, double e1, const FrameScalars& read) {
    const double slope = read.slope;
    const double curvature = e1 - e0 - slope * length;  // of the quadratic, times length^2
    if (!std::isfinite(e1) || read.trialInverted > read.inverted || !(slope < 0.0) ||
        !(curvature > 0.0))
      return 0.5 * length;
    return std::clamp(-slope * length * length / (2.0 * curvature), 0.1 * length, 0.5 * length);
  }

 private:
  Exec& ex_;
  FrameData<Exec>& d_;
  IncrementalPotential<Exec>& potential_;
};

}  // namespace galsculpt
