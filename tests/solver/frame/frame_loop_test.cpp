// The frame loop (frame_loop.h) over a scripted stand-in for the frame: sub-steps rolled back
// and halved after a failure, a frame given up after maxRetries, the plastic and fracture
// passes after each accepted sub-step, and a sub-step solved again while its fracture pass
// breaks edges.
#include "solver/frame/frame_loop.h"

#include <gtest/gtest.h>

#include <deque>
#include <vector>

namespace galsculpt {
namespace {

// Each sub-step's outcome and each fracture pass's breaks come from queues; what the loop asks
// is logged.
struct ScriptedFrame {
  struct Saved {
    double time;
  };
  double t = 0.0;
  std::deque<bool> substepOk;  // empty: ok
  std::deque<int> breaks;      // the fracture passes' new damage; empty: none
  bool plasticBody = false;
  bool fracturing = false;
  std::vector<double> steps;  // h of every sub-step asked for
  int restores = 0, keptDamageRestores = 0, plasticUpdates = 0;

  Saved save() const { return {t}; }
  void restore(const Saved& s, bool keepDamage) {
    t = s.time;
    ++restores;
    keptDamageRestores += keepDamage;
  }
  SubstepOutcome substep(double h) {
    steps.push_back(h);
    SubstepOutcome r;
    r.ok = substepOk.empty() ? true : substepOk.front();
    if (!substepOk.empty()) substepOk.pop_front();
    r.newtonIterations = 2;
    r.residual = h;
    r.converged = true;
    r.msElements = 1.0;
    t += h;
    return r;
  }
  int plasticUpdate() {
    ++plasticUpdates;
    return 3;
  }
  bool plastic() const { return plasticBody; }
  bool fractures() const { return fracturing; }
  FractureReport fracturePass() {
    FractureReport f;
    if (!breaks.empty()) {
      f.newlyDamaged = breaks.front();
      breaks.pop_front();
    }
    f.maxStressRatio = 0.5;
    return f;
  }
  double time() const { return t; }
  void setTime(double time) { t = time; }
};

StepSettings settings(int substeps) {
  StepSettings s;
  s.dt = 0.01;
  s.substeps = substeps;
  return s;
}

TEST(FrameLoop, SubstepsCoverTheFrameAndTheirFiguresAddUp) {
  ScriptedFrame f;
  f.plasticBody = true;
  const StepReport r = runFrame(f, settings(4));
  EXPECT_EQ(f.steps.size(), 4u);
  EXPECT_NEAR(f.t, 0.01, 1e-15);
  EXPECT_EQ(r.newtonIterations, 8);
  EXPECT_DOUBLE_EQ(r.residual, 0.0025) << "the last sub-step's";
  EXPECT_EQ(r.plasticElements, 12);
  EXPECT_EQ(f.plasticUpdates, 4);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.retries, 0);
}

// A failed sub-step is rolled back and the rest of the frame taken in halves.
TEST(FrameLoop, AFailedSubstepIsRolledBackAndHalved) {
  ScriptedFrame f;
  f.substepOk = {false, true, true};
  const StepReport r = runFrame(f, settings(1));
  EXPECT_EQ(f.steps, (std::vector<double>{0.01, 0.005, 0.005}));
  EXPECT_EQ(r.retries, 1);
  EXPECT_EQ(f.restores, 1);
  EXPECT_EQ(f.keptDamageRestores, 0);
  EXPECT_EQ(r.newtonIterations, 4) << "the failed sub-step's iterations are not counted";
  EXPECT_NEAR(f.t, 0.01, 1e-15);
  EXPECT_TRUE(r.converged);
}

// Past maxRetries the frame keeps its state, counts the warning and lets time move on.
TEST(FrameLoop, AFrameThatKeepsFailingIsGivenUpNotHung) {
  ScriptedFrame f;
  f.substepOk = std::deque<bool>(10, false);
  StepSettings s = settings(1);
  s.maxRetries = 2;
  const StepReport r = runFrame(f, s);
  EXPECT_EQ(f.steps.size(), 3u);
  EXPECT_EQ(r.retries, 3);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(f.t, 0.01);
}

// While the fracture pass breaks edges the sub-step is solved again from its start with the
// damage kept, up to fractureIterations solves; only the time of a redone solve counts.
TEST(FrameLoop, ASubstepIsSolvedAgainWhileItsFracturePassBreaksEdges) {
  ScriptedFrame f;
  f.fracturing = true;
  f.breaks = {5, 2, 1};
  StepSettings s = settings(1);
  s.fractureIterations = 3;
  const StepReport r = runFrame(f, s);
  EXPECT_EQ(f.steps.size(), 3u);
  EXPECT_EQ(f.keptDamageRestores, 2);
  EXPECT_EQ(r.fractureRedos, 2);
  EXPECT_EQ(r.newlyDamaged, 8);
  EXPECT_EQ(r.newtonIterations, 2) << "the accepted solve's";
  EXPECT_EQ(r.msElements, 3.0) << "every solve's time";
  EXPECT_EQ(r.maxStressRatio, 0.5);
}

}  // namespace
}  // namespace galsculpt
