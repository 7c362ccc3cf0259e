// How FrameSolver's sub-step starts (frame_solver.h): x_n, v_n and the inertial target from the
// state, the held vertices on their paths, the pieces' accelerated start, what a device's trials
// form besides the residual, and the prediction dropped when it turns an element inside out.
// Included by frame_solver.h only, after the class.
#pragma once

#include "solver/frame/frame_solver.h"

namespace galsculpt {

template <typename Exec>
void FrameSolver<Exec>::beginSubstep(double h) {
  d_.h = h;
  // A device forms the next local region and the pieces' residuals at each trial, so that the
  // choices after an iteration need no read of their own.
  const StepSettings& s = *d_.settings;
  const bool atTrials = !Exec::kHostMemory && potential_.residualAtTrials();
  const bool regionAtTrials = atTrials && s.localNewton && s.multigrid();
  potential_.formRegionAtTrials(regionAtTrials ? &region_ : nullptr, s.residualTolerance, weight());
  const bool piecesAtTrials =
      atTrials && s.convergePieces && pieceResidual_.measures(damage_.pieces());
  potential_.formPiecesAtTrials(piecesAtTrials ? &pieceResidual_ : nullptr, &damage_.pieces(),
                                model_.gravity.norm());
  pieceTargetCap_ = std::numeric_limits<double>::infinity();
  linear_.resetIterations();
  held_.prepare(*anchors_, time_ + h);
  contact_.place(colliderStates_, time_ + h, h);
  double* x = d_.x.data();
  double* v = d_.v.data();
  double* xn = d_.xn.data();
  double* vn = d_.vn.data();
  double* xhat = d_.xhat.data();
  ex_.forEach(3 * d_.n, [=] GALSCULPT_LAMBDA(int i) {
    xn[i] = x[i];
    vn[i] = v[i];
    xhat[i] = x[i] + h * v[i];
  });
  const bool gradientAtXn = gradientAtX_;
  gradientAtX_ = false;  // x moves on from x_n below
  // Not where a brush or an anchor has just let go: the prediction would carry the vertices it
  // moved on past where it let them go, and plastic clay stops there (its flow is in the
  // energy: a start deep in the flow region makes Newton unload it across the yield kink).
  predicted_ = d_.settings->predictedStart && !letGo_;
  letGo_ = false;
  if (predicted_) {
    ex_.copy(x, xhat, 3 * d_.n);
    if (d_.settings->acceleratedStart) startPiecesAccelerated(h, gradientAtXn);
  }
  // Stiffnesses are kept within a sub-step only: a frame's result must follow from the state
  // alone (a reopened project runs on identically), and rest shapes change between sub-steps.
  if (d_.settings->stiffnessTolerance > 0.0) {
    double* keptF = d_.stiffnessF.data();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    ex_.forEach(d_.tets, [=] GALSCULPT_LAMBDA(int t) { keptF[9 * t] = nan; });
  }
  held_.place();
  d_.frozenIsK = true;
}

template <typename Exec>
void FrameSolver<Exec>::startPiecesAccelerated(double h, bool gradientAtXn) {
  const ElementModel element{potential_.elastic().inputs(), model_.material.model,
                             model_.material.elementLame(), model_.material.compressionResists};
  const typename AcceleratedStart<Exec>::SubstepInputs inputs{
      d_.anchorCount > 0,
      d_.fixed.data(),
      d_.removed.data(),
      d_.xn.data(),
      d_.xhat.data(),
      d_.vn.data(),
      d_.mass.data(),
      contact_.poses(),
      contact_.colliders(),
      h,
      model_.material.dampingMass,
      {model_.gravity.x(), model_.gravity.y(), model_.gravity.z()}};
  // Copied on the host executor only: its element kernel is compiled without contracted
  // multiply-adds, so the copy is the evaluation bit for bit and a frame still follows from
  // the state alone. nvcc contracts them as each kernel's inlining allows, so on the GPU the
  // two could differ in their last bits; there the elements are evaluated, in parallel.
  const bool copy = gradientAtXn && Exec::kHostMemory;
  accelerated_.start(ex_, model_, damage_.pieces(), inputs, element,
                     copy ? d_.elemGrad.data() : nullptr, d_.x.data());
}

template <typename Exec>
bool FrameSolver<Exec>::dropInvertingPrediction(const FrameScalars& read) {
  if (!predicted_) return false;
  predicted_ = false;
  if (!(read.inverted > 0.0)) return false;
  ex_.copy(d_.x.data(), d_.xn.data(), 3 * d_.n);
  held_.place();
  return true;
}

}  // namespace galsculpt
