// The line search's step shortening (solver/frame/line_search.h); the whole search runs in the
// frame's tests (frame_solver_test.cpp, energy_guard_test.cpp, converged_frame_test.cpp).
#include "solver/frame/line_search.h"

#include <gtest/gtest.h>

#include <cmath>

#include "solver/frame/cpu_executor.h"

namespace galsculpt {
namespace {

// A failed step is shortened to the minimum of the quadratic through the energy, its slope and
// the failed trial, within a tenth and a half of the failed length; halved where the energy
// says nothing (the trial turned elements inside out, or the step is no descent direction).
TEST(LineSearch, AFailedStepShrinksToTheQuadraticsMinimum) {
  using Solver = LineSearch<CpuExecutor>;
  FrameScalars read;
  read.slope = -1.0;
  auto energy = [](double c, double length) { return -length + c * length * length; };
  EXPECT_NEAR(Solver::shorterStep(1.0, 0.0, energy(1.5, 1.0), read), 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(Solver::shorterStep(0.1, 0.0, energy(10.0, 0.1), read), 0.05, 1e-15);
  EXPECT_EQ(Solver::shorterStep(1.0, 0.0, energy(1e6, 1.0), read), 0.1) << "at most ten times";
  EXPECT_EQ(Solver::shorterStep(1.0, 0.0, energy(0.6, 1.0), read), 0.5) << "at least half";
  read.trialInverted = 1.0;
  EXPECT_EQ(Solver::shorterStep(1.0, 0.0, energy(1.5, 1.0), read), 0.5) << "inverted: halved";
  read.trialInverted = 0.0;
  read.slope = 0.5;
  EXPECT_EQ(Solver::shorterStep(1.0, 0.0, 1.0, read), 0.5) << "no descent: halved";
  EXPECT_EQ(Solver::shorterStep(1.0, 0.0, std::nan(""), read), 0.5);
}

// Armijo with the sums' round-off: a trial that rises by less than 1e-12 of e0 still descends;
// one that is not finite never does.
TEST(LineSearch, DescentIsArmijoUpToTheSumsRoundOff) {
  using Search = LineSearch<CpuExecutor>;
  FrameScalars read;
  read.e0 = 1.0;
  read.slope = -1.0;
  read.e1 = 1.0 - 1e-4 * 0.5;
  EXPECT_TRUE(Search::descent(read, 0.5, 1e-4)) << "exactly the sufficient decrease";
  read.e1 = 1.0 - 1e-4 * 0.4;
  EXPECT_FALSE(Search::descent(read, 0.5, 1e-4));
  read.e1 = 1.0 + 0.5e-12;
  EXPECT_TRUE(Search::descent(read, 0.5, 0.0)) << "within round-off of no change";
  read.e1 = 1.0 + 2e-12;
  EXPECT_FALSE(Search::descent(read, 0.5, 0.0));
  read.e1 = std::nan("");
  EXPECT_FALSE(Search::descent(read, 0.5, 0.0));
}

}  // namespace
}  // namespace galsculpt
