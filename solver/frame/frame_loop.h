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

struct SubstepOutcome {
  bool ok = true;
  bool converged = false;
  int iterations = 0;
  int cgIterations = 0;
  int backtracks = 0;
  double energyPasses = 0.0;     // StepReport::energyPasses
  double keptStiffnesses = 0.0;  // StepReport::keptStiffnesses
  int invertedElements = 0;      // intact elements inside out at the accepted positions
  double residual = 0.0;
  double pieceResidual = 0.0;  // StepReport::pieceResidual
  double energy = 0.0;
  double msElements = 0.0, msSolve = 0.0;
  double linearResidualReduction = 0.0;
  std::vector<Vec3> contactForces;
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
        report.msElements += r.msElements;
        report.msSolve += r.msSolve;
        ops.restore(saved, true);
        continue;
      }
    }
    redo = 0;
    report.contactForces = r.contactForces;
    report.linearResidualReduction = r.linearResidualReduction;
    report.newtonIterations += r.iterations;
    report.cgIterations += r.cgIterations;
    report.converged = report.converged && r.converged;
    report.backtracks += r.backtracks;
    report.energyPasses += r.energyPasses;
    report.keptStiffnesses += r.keptStiffnesses;
    report.invertedElements = r.invertedElements;
    report.residual = r.residual;
    report.pieceResidual = r.pieceResidual;
    report.elasticEnergy = r.energy;
    report.msElements += r.msElements;
    report.msSolve += r.msSolve;
  }
  report.msTotal = msSince(start);
  return report;
}

}  // namespace galsculpt
