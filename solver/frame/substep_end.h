// How FrameSolver's sub-step ends (frame_solver.h): the residual at the accepted positions,
// the elements inside out, whether the positions are finite, the contact forces and the
// velocities. Included by frame_solver.h only, after the class.
#pragma once

#include <cmath>

#include "solver/frame/frame_solver.h"

namespace galsculpt {

// v = (x - x_n) / h at a sub-step's end.
template <typename Exec>
void formVelocities(Exec& ex, FrameData<Exec>& d, double h) {
  const double* x = d.x.data();
  const double* xn = d.xn.data();
  double* v = d.v.data();
  ex.forEach(3 * d.n, [=] GALSCULPT_LAMBDA(int i) { v[i] = (x[i] - xn[i]) / h; });
}

template <typename Exec>
void FrameSolver<Exec>::endSubstep(double h, SubstepOutcome& result) {
  // Where the accepted trial's read already holds all of it (residualAtTrials: the residual,
  // the elements inside out and whether the positions are finite, the same bits) and nothing
  // else needs a read (no colliders, one measured piece), only the velocities are formed: no
  // read of its own.
  if (fracture_) fracture_->holdSearch(false);  // a search held from a failed sub-step
  if (accepted_.fromTrial && contact_.colliders() == 0 &&
      !pieceResidual_.measures(damage_.pieces())) {
    ex_.captured(2, graphKey(h, -2), [&] { formVelocities(ex_, d_, h); });
    result.residual = relativeResidual(accepted_.trialRead);
    result.pieceResidual = result.residual;
    result.invertedElements = static_cast<int>(accepted_.trialRead.trialInverted);
    contact_.readForces(result.contactForces, contactMoments_);
    if (accepted_.trialRead.bad > 0.0 || !std::isfinite(result.elasticEnergy)) result.ok = false;
    return;
  }
  ex_.captured(1, graphKey(h, -1), [&] { finishSubstep(h); });
  const bool measured =
      pieceResidual_.launch(ex_, damage_.pieces(), d_.g.data(), d_.tmp.data(), d_.fixed.data(),
                            d_.mass.data(), model_.gravity.norm());
  // The fracture pass's search at the accepted positions, where the frame runs it next (no
  // plastic update in between), launched now so that its scalars come down with these.
  const bool searched =
      fracture_ && !plastic_.active() &&
      fracture_->launchSearch(potential_.elastic().inputs(), d_.x.data(), d_.damaged.data());
  // The scalars, the worst piece's residual, the colliders' forces and the search's scalars
  // behind one wait.
  FrameScalars read;
  double pieceResidual = -1.0;
  const DownloadSpan none{nullptr, nullptr, 0};
  ex_.downloadAll({{d_.sc(), &read, sizeof read},
                   {pieceResidual_.result(), &pieceResidual, measured ? sizeof(double) : 0},
                   contact_.forcesSpan(),
                   searched ? fracture_->searchSpan() : none});
  if (fracture_) fracture_->holdSearch(searched);
  result.residual = relativeResidual(read);
  result.pieceResidual = pieceResidual < 0.0 ? result.residual : pieceResidual;
  result.invertedElements = static_cast<int>(read.trialInverted);  // the accepted trial's
  contact_.takeForces(result.contactForces, contactMoments_);
  // Otherwise the caller restores x and v.
  if (read.bad > 0.0 || !std::isfinite(result.elasticEnergy)) result.ok = false;
}

template <typename Exec>
void FrameSolver<Exec>::finishSubstep(double h) {
  FrameScalars* sc = d_.sc();
  const double* x = d_.x.data();
  potential_.acceptedResidual();
  potential_.nonFinite(x, &sc->bad);
  contact_.sumForces(x, d_.fixed.data(), d_.mass.data(), d_.h);
  formVelocities(ex_, d_, h);
}

}  // namespace galsculpt
