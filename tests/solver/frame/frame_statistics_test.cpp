#include "solver/frame/frame_statistics.h"

#include <gtest/gtest.h>

namespace galsculpt {
namespace {

FrameStatistics substep(int iterations, double residual, bool converged, double ms) {
  FrameStatistics s;
  s.newtonIterations = iterations;
  s.cgIterations = 2 * iterations;
  s.residual = residual;
  s.pieceResidual = 2.0 * residual;
  s.converged = converged;
  s.msElements = ms;
  s.msSolve = 2.0 * ms;
  s.invertedElements = iterations;
  // The frame loop's own figures: a sub-step's never reach the frame.
  s.retries = 9;
  s.msFracture = 9.0;
  s.newlyDamaged = 9;
  return s;
}

// Each figure by its rule: counts add, the residual is the last sub-step's, the frame has
// converged only if every sub-step has, and the frame loop's own figures are left to it.
TEST(FrameStatistics, SubstepsCombineByTheirRules) {
  FrameStatistics frame;
  frame.addSubstep(substep(3, 0.5, true, 1.0));
  frame.addSubstep(substep(4, 0.25, false, 2.0));
  frame.addSubstep(substep(1, 0.125, true, 4.0));
  EXPECT_EQ(frame.newtonIterations, 8);
  EXPECT_EQ(frame.cgIterations, 16);
  EXPECT_EQ(frame.residual, 0.125);
  EXPECT_EQ(frame.pieceResidual, 0.25);
  EXPECT_EQ(frame.invertedElements, 1);
  EXPECT_FALSE(frame.converged);
  EXPECT_EQ(frame.msElements, 7.0);
  EXPECT_EQ(frame.msSolve, 14.0);
  EXPECT_EQ(frame.retries, 0);
  EXPECT_EQ(frame.msFracture, 0.0);
  EXPECT_EQ(frame.newlyDamaged, 0);
}

// A sub-step solved again after new damage: its time was spent, its iterations are redone.
TEST(FrameStatistics, ARedoneSubstepAddsOnlyItsTimes) {
  FrameStatistics frame;
  frame.addTimes(substep(5, 0.5, false, 3.0));
  EXPECT_EQ(frame.msElements, 3.0);
  EXPECT_EQ(frame.msSolve, 6.0);
  EXPECT_EQ(frame.newtonIterations, 0);
  EXPECT_EQ(frame.residual, 0.0);
  EXPECT_TRUE(frame.converged);
}

}  // namespace
}  // namespace galsculpt
