// What a frame reports of its solve, one row per figure: the same struct is filled by each
// sub-step (the Newton solver, frame_solver.h), summed over the frame by each figure's rule
// (frame_loop.h), handed back as the StepReport and printed by the engine's metrics
// (engine/session/simulation.h: FrameMetrics extends it; its CSV columns name the fields).
//
// Adding a figure: its row below, where it is measured, and its metrics column if it has one.
#pragma once

namespace galsculpt {

// How a sub-step's figure enters its frame's:
//   Sum    added;
//   Time   added, also for a sub-step solved again after new damage (its time was spent);
//   Last   the last accepted sub-step's;
//   All    true only if every sub-step's is;
//   Frame  the frame loop's own (retries, plasticity, fracture, the frame's total).
enum class FrameStatisticRule { Sum, Time, Last, All, Frame };

// X(type, member, initial value, rule, meaning)
#define GALSCULPT_FRAME_STATISTICS(X)                                                              \
  X(int, newtonIterations, 0, Sum, "Newton iterations of the frame's sub-steps")                   \
  X(double, residual, 0.0, Last, "|grad E| at the new positions, free DOFs, over the force scale") \
  X(double, pieceResidual, 0.0, Last,                                                              \
    "the largest such residual of a piece of more than 10 vertices over its own force scale "      \
    "(piece_residual.h): what the body's norm can hide in a body in pieces; the body's while "     \
    "fewer than two pieces are that large")                                                        \
  X(double, elasticEnergy, 0.0, Last, "elastic energy, J")                                         \
  X(int, retries, 0, Frame, "sub-steps rolled back and halved (warnings)")                         \
  X(int, backtracks, 0, Sum, "Newton steps shortened because the full step raised the energy")     \
  X(double, energyPasses, 0.0, Sum,                                                                \
    "energy evaluations of shortened steps in whole-body passes (a vertex-guard round over a "     \
    "tenth of the elements counts 0.1)")                                                           \
  X(double, keptStiffnesses, 0.0, Sum,                                                             \
    "element stiffnesses kept rather than evaluated (StepSettings::stiffnessTolerance)")           \
  X(double, msElements, 0.0, Time, "ms in the element passes (with the colliders' pass)")          \
  X(double, msSolve, 0.0, Time, "ms in the linear solves")                                         \
  X(double, msPlastic, 0.0, Frame, "ms in the plastic return")                                     \
  X(double, msTotal, 0.0, Frame, "ms of the whole frame")                                          \
  X(int, plasticElements, 0, Frame, "elements that flowed this frame")                             \
  X(double, linearResidualReduction, 0.0, Last,                                                    \
    "|r_final| / |r_initial| of the last linear solve")                                            \
  X(int, newlyDamaged, 0, Frame, "edges the fracture pass broke this frame")                       \
  X(double, maxStressRatio, 0.0, Frame, "largest edge stress over its threshold (last pass)")      \
  X(double, msFracture, 0.0, Frame, "ms in the fracture pass")                                     \
  X(int, fractureRedos, 0, Frame, "sub-steps solved again after new damage")                       \
  X(bool, converged, true, All,                                                                    \
    "every sub-step ended with its residual within residualTolerance (with none, Newton's "        \
    "step-length test met)")                                                                       \
  X(int, cgIterations, 0, Sum, "PCG iterations of the frame's linear solves")                      \
  X(int, localIterations, 0, Sum,                                                                  \
    "Newton iterations that solved only where the residual was (StepSettings::localNewton)")       \
  X(int, invertedElements, 0, Last,                                                                \
    "intact elements inside out at the frame's end (a warning): the line search refuses steps "    \
    "that invert more of them unless no descending step avoids it")                                \
  X(int, launches, 0, Frame,                                                                       \
    "kernels a device backend ran for the frame: a device program each (the launches between "     \
    "two host waits), or a kernel a launch with programs off (device_counters.h; 0 on the CPU "    \
    "backend)")                                                                                    \
  X(int, syncs, 0, Frame, "times the host waited for the device: scalar reads, downloads")         \
  X(int, graphs, 0, Frame, "graph launches (the CUDA backend with device programs off)")           \
  X(int, barriers, 0, Frame,                                                                       \
    "grid-wide barriers inside the device programs (a phase each: device_counters.h)")             \
  X(double, hostToDeviceBytes, 0.0, Frame, "bytes copied host to device")                          \
  X(double, deviceToHostBytes, 0.0, Frame, "bytes copied device to host")

struct FrameStatistics {
#define GALSCULPT_STATISTIC_MEMBER(T, member, initial, rule, meaning) T member = initial;
  GALSCULPT_FRAME_STATISTICS(GALSCULPT_STATISTIC_MEMBER)
#undef GALSCULPT_STATISTIC_MEMBER

  // A sub-step's figures into the frame's, each by its rule.
  void addSubstep(const FrameStatistics& s) {
#define GALSCULPT_STATISTIC_ADD(T, member, initial, rule, meaning) \
  combine<FrameStatisticRule::rule>(member, s.member, false);
    GALSCULPT_FRAME_STATISTICS(GALSCULPT_STATISTIC_ADD)
#undef GALSCULPT_STATISTIC_ADD
  }
  // Only the times of a sub-step that is solved again (the Time rows).
  void addTimes(const FrameStatistics& s) {
#define GALSCULPT_STATISTIC_TIME(T, member, initial, rule, meaning) \
  combine<FrameStatisticRule::rule>(member, s.member, true);
    GALSCULPT_FRAME_STATISTICS(GALSCULPT_STATISTIC_TIME)
#undef GALSCULPT_STATISTIC_TIME
  }

 private:
  template <FrameStatisticRule R, typename T>
  static void combine(T& frame, const T& substep, bool timesOnly) {
    if constexpr (R == FrameStatisticRule::Time) {
      frame += substep;
    } else if (!timesOnly) {
      if constexpr (R == FrameStatisticRule::Sum) frame += substep;
      if constexpr (R == FrameStatisticRule::Last) frame = substep;
      if constexpr (R == FrameStatisticRule::All) frame = frame && substep;
    }
  }
};

}  // namespace galsculpt
