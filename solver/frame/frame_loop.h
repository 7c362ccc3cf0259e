// The frame loop of backward Euler, written once for every backend: sub-steps of dt, each
// rolled back and retried with half the step after a NaN or a failed descent (counted as a
// warning), the plastic return and the fracture pass after each accepted sub-step, and re-solves
// of a sub-step while its fracture pass keeps breaking edges (fractureIterations).
//
// `Ops` is the frame's (frame_solver.h, on either executor):
//   Saved save();                          the state to come back to
//   void restore(const Saved&, bool keepDamage);
//   SubstepOutcome substep(double h);      one backward-Euler sub-step; advances time
//   int plasticUpdate();                   elements that flowed (called when plastic)
//   bool plastic() const;
//   bool fractures() const;                whether the model's fracture field is enabled
//   FractureReport fracturePass();         called when it is
//   double time() const;  void setTime(double);
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

#include "solver/frame/step.h"
#include "solver/frame/timing.h"

namespace galsculpt {

// One sub-step's figures (FrameStatistics: its Newton iterations, residual, ...); `ok` false
// when it failed (NaN, no descent) and is rolled back; `stopped` when a stop was asked for
// (stop_request.h) between two of its Newton iterations.
struct SubstepOutcome : StepReport {
  bool ok = true;
  bool stopped = false;
};

template <typename Ops>
StepReport runFrame(Ops& ops, const StepSettings& settings) {
  const auto start = Clock::now();
  StepReport report;
  const double frameEnd = ops.time() + settings.dt;
  int pieces = std::max(1, settings.substeps);
  double h = settings.dt / pieces;
  int redo = 0;  // fracture re-solves of the current sub-step
  while (ops.time() < frameEnd - 1e-12 * settings.dt) {
    h = std::min(h, frameEnd - ops.time());
    const auto saved = ops.save();
    const SubstepOutcome r = ops.substep(h);
    if (r.stopped) {
      // Asked to stop: the sub-step is rolled back and the frame left unfinished; the caller
      // brings back the state of the frame's start (Simulation::advance).
      ops.restore(saved, false);
      report.stopped = true;
      break;
    }
    if (!r.ok) {
      ops.restore(saved, false);
      if (report.retries >= settings.maxRetries) {
        // Give up on this frame: keep the state as it was, count the warning, and let time move
        // on so that the caller is never stuck.
        ops.setTime(frameEnd);
        ++report.retries;
        report.converged = false;
        break;
      }
      ++report.retries;
      h *= 0.5;
      continue;
    }
    if (ops.plastic()) {
      const auto t0 = Clock::now();
      report.plasticElements += ops.plasticUpdate();
      report.msPlastic += msSince(t0);
    }
    if (ops.fractures()) {
      const auto t0 = Clock::now();
      const FractureReport fr = ops.fracturePass();
      report.newlyDamaged += fr.newlyDamaged;
      report.maxStressRatio = fr.maxStressRatio;
      report.msFracture += msSince(t0);
      if (fr.newlyDamaged > 0 && redo + 1 < settings.fractureIterations) {
        // Let the crack run within the sub-step: solve it again from its start with the new
        // damage (kept), until no edge breaks or the iterations are spent.
        ++redo;
        ++report.fractureRedos;
        report.addTimes(r);
        ops.restore(saved, true);
        continue;
      }
    }
    redo = 0;
    report.contactForces = r.contactForces;
    report.addSubstep(r);
  }
  report.msTotal = msSince(start);
  return report;
}

}  // namespace galsculpt
