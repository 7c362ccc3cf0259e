// The accelerated start (solver/frame/accelerated_start.h): a piece that nothing holds starts
// Newton from its predicted path with its acceleration, gravity and its neighbours' push. The
// layout of pieces, the kernels against the formula, what holds a piece, and whole frames of
// pieces flying off a clamped bar against the straight-line start and the reference.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "solver/fracture/fracture.h"
#include "solver/frame/accelerated_start.h"
#include "solver/frame/cpu_backend.h"
#include "solver/frame/cpu_executor.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

using test::gridBar;

MaterialParams rubber(double youngs = 2e5) {
  return {MaterialModel::StableNeoHookean, lameFromYoungPoisson(youngs, 0.45), 1000.0, {}};
}

// Piece kernels over the layout's arrays (gradient: the elements between pieces, or null).
AcceleratedPiece pieceKernel(const PieceLayout& layout, const std::uint8_t* heldPiece,
                             const double* gradient, const std::vector<double>& xn,
                             const std::vector<double>& vn, const SimModel& m, double h,
                             double damping, const Vec3& g, double* x) {
  return {layout.pieceStart.data(),
          layout.pieceVertices.data(),
          heldPiece,
          layout.couplingStart.data(),
          layout.couplingSlot.data(),
          gradient,
          xn.data(),
          vn.data(),
          m.mass.data(),
          h,
          damping,
          {g.x(), g.y(), g.z()},
          x};
}

TEST(AcceleratedStart, PiecesAndTheElementsBetweenThem) {
  const SimModel m = buildSimModel(gridBar(4, 1, 1, 0.01), rubber());
  SimState s = initialState(m);
  const PieceLayout whole = pieceLayout(m, s.damaged);
  ASSERT_EQ(whole.pieces(), 1);
  EXPECT_EQ(whole.pieceVertices.size(), static_cast<size_t>(m.numVertices()));
  EXPECT_TRUE(whole.sharedTets.empty());
  cutAt(m, s, 0.02);
  const PieceLayout cut = pieceLayout(m, s.damaged);
  ASSERT_EQ(cut.pieces(), 2);
  auto left = [&](int v) { return m.mesh.vertices[v].x() < 0.02 + 1e-9; };
  for (int p = 0; p < 2; ++p) {
    const bool side = left(cut.pieceVertices[cut.pieceStart[p]]);
    for (int i = cut.pieceStart[p]; i < cut.pieceStart[p + 1]; ++i)
      EXPECT_EQ(left(cut.pieceVertices[i]), side);
  }
  // Shared: exactly the elements with corners on both sides of the cut.
  int shared = 0;
  for (const Tet& t : m.mesh.tets) {
    bool l = false, r = false;
    for (int a = 0; a < 4; ++a) (left(t[a]) ? l : r) = true;
    shared += l && r;
  }
  EXPECT_EQ(cut.sharedTets.size(), static_cast<size_t>(shared));
  // Every corner of a shared element is listed once, under its own piece.
  EXPECT_EQ(cut.couplingSlot.size(), 4 * cut.sharedTets.size());
  for (int p = 0; p < 2; ++p) {
    const bool side = left(cut.pieceVertices[cut.pieceStart[p]]);
    for (int i = cut.couplingStart[p]; i < cut.couplingStart[p + 1]; ++i) {
      const int slot = cut.couplingSlot[i];
      EXPECT_EQ(left(m.mesh.tets[cut.sharedTets[slot / 12]][(slot % 12) / 3]), side);
    }
  }
}

// A piece nothing holds and nothing pushes starts where gravity takes it: x_n + h (v_n + h g),
// every vertex, its spin on the straight line as before. A held piece is left where it was.
TEST(AcceleratedStart, AFreePieceStartsWhereGravityTakesIt) {
  const SimModel m = buildSimModel(gridBar(3, 2, 1, 0.02), rubber());
  const int n = m.numVertices();
  const PieceLayout layout = pieceLayout(m, {});
  const Vec3 u(0.3, -1.0, 2.0), omega(1.0, -4.0, 7.0), g(0.0, -9.81, 0.0);
  std::vector<double> xn(3 * n), vn(3 * n), x(3 * n, 0.0);
  for (int v = 0; v < n; ++v) {
    const Vec3 vel = u + omega.cross(m.mesh.vertices[v]);
    for (int k = 0; k < 3; ++k) {
      xn[3 * v + k] = m.mesh.vertices[v][k];
      vn[3 * v + k] = vel[k];
    }
  }
  const std::vector<std::uint8_t> held(2, 0);  // per piece
  const double h = 1.0 / 60.0;
  const AcceleratedPiece piece =
      pieceKernel(layout, held.data(), nullptr, xn, vn, m, h, 0.0, g, x.data());
  piece(0);
  for (int v = 0; v < n; ++v) {
    const Vec3 expected =
        m.mesh.vertices[v] + h * (u + omega.cross(m.mesh.vertices[v])) + h * h * g;
    EXPECT_LT((Vec3(x[3 * v], x[3 * v + 1], x[3 * v + 2]) - expected).norm(), 1e-15)
        << "vertex " << v;
  }
  const std::uint8_t pieceHeld[1] = {1};
  std::vector<double> untouched(3 * n, 0.0);
  AcceleratedPiece heldPiece = piece;
  heldPiece.heldPiece = pieceHeld;
  heldPiece.x = untouched.data();
  heldPiece(0);
  for (double value : untouched) EXPECT_EQ(value, 0.0);
}

// With mass damping alpha the centre's velocity is (u + h g) / (1 + h alpha): backward Euler's.
TEST(AcceleratedStart, MassDampingSlowsTheStartAsBackwardEulerDoes) {
  const SimModel m = buildSimModel(gridBar(1, 1, 1, 0.02), rubber());
  const int n = m.numVertices();
  const PieceLayout layout = pieceLayout(m, {});
  std::vector<double> xn(3 * n), vn(3 * n), x(3 * n);
  for (int v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k) {
      xn[3 * v + k] = m.mesh.vertices[v][k];
      vn[3 * v + k] = k == 0 ? 1.0 : 0.0;
    }
  const std::vector<std::uint8_t> held(2, 0);  // per piece
  const double h = 0.01, alpha = 5.0;
  const AcceleratedPiece piece = pieceKernel(layout, held.data(), nullptr, xn, vn, m, h, alpha,
                                             Vec3(0.0, -10.0, 0.0), x.data());
  piece(0);
  for (int v = 0; v < n; ++v) {
    EXPECT_NEAR(x[3 * v] - xn[3 * v], h * 1.0 / (1.0 + h * alpha), 1e-15);
    EXPECT_NEAR(x[3 * v + 1] - xn[3 * v + 1], h * (h * -10.0) / (1.0 + h * alpha), 1e-15);
  }
}

// Held: anchored (or removed) vertices and vertices a collider may reach within the sub-step.
TEST(AcceleratedStart, WhatHoldsAVertex) {
  const SimModel m = buildSimModel(gridBar(2, 1, 1, 0.01), rubber());
  const int n = m.numVertices();
  std::vector<double> xn(3 * n), vn(3 * n, 0.0);
  for (int v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k) xn[3 * v + k] = m.mesh.vertices[v][k];
  std::vector<std::uint8_t> fixed(n, 0);
  kernels::ColliderPose floor;  // the plane y = -0.005
  floor.point[1] = -0.005;
  const double h = 0.01;
  HeldVertices test{fixed.data(), xn.data(), xn.data(), vn.data(), &floor, 0, h * h * 9.81, h};
  for (int v = 0; v < n; ++v) EXPECT_EQ(test(v), 0) << "vertex " << v;
  fixed[3] = 1;
  EXPECT_EQ(test(3), 1) << "anchored";
  fixed[3] = 0;
  // The floor 5 mm below the bar's lowest vertices: out of a sub-step's reach at rest, within
  // it at 1 m/s downwards (h |v| = 1 cm).
  test.colliders = 1;
  EXPECT_EQ(test(0), 0);
  for (int v = 0; v < n; ++v) vn[3 * v + 1] = -1.0;
  EXPECT_EQ(test(0), 1) << "the floor within reach";
}

// A sub-step's inputs without colliders or mass damping, the inertial target at x_n.
AcceleratedStart<CpuExecutor>::SubstepInputs atRest(
    bool anyFixed, const std::vector<std::uint8_t>& fixed, const std::vector<std::uint8_t>& removed,
    const std::vector<double>& xn, const std::vector<double>& vn, const SimModel& m, double h,
    const std::array<double, 3>& gravity) {
  return {anyFixed,
          fixed.data(),
          removed.data(),
          xn.data(),
          xn.data(),
          vn.data(),
          m.mass.data(),
          nullptr,
          0,
          h,
          0.0,
          {gravity[0], gravity[1], gravity[2]}};
}

// The 3-cell bar cut at x = 0.01 and 0.02: pieces at x = 0 and 0.01, at 0.02, at 0.03.
SimState cutInThree(const SimModel& m) {
  SimState s = initialState(m);
  cutAt(m, s, 0.01);
  cutAt(m, s, 0.02);
  return s;
}

// A bar cut in three, its pieces pressed 0.5 mm together: a vertex held in the first piece
// holds it; the second presses on it across a closed crack and is held by the first round of
// spreading, the third by the second. A crack just at rest length (or a round-off short of it)
// is not pressing, the third
// moved 2 mm off (its crack open 20 %) is free, and removed debris holds up nothing.
TEST(AcceleratedStart, APiecePressingOnAHeldPieceIsHeld) {
  const SimModel m = buildSimModel(gridBar(3, 1, 1, 0.01), rubber());
  const SimState s = cutInThree(m);
  const PieceLayout layout = pieceLayout(m, s.damaged);
  ASSERT_EQ(layout.pieces(), 3);
  const int n = m.numVertices();
  auto pieceAt = [&](double x) {
    for (int v = 0; v < n; ++v)
      if (std::abs(m.mesh.vertices[v].x() - x) < 1e-9) return layout.pieceOf[v];
    return -1;
  };
  const int first = pieceAt(0.0), second = pieceAt(0.02), third = pieceAt(0.03);
  std::vector<double> xn(3 * n);
  auto place = [&](double squeeze, double thirdOff) {
    for (int v = 0; v < n; ++v) {
      const int p = layout.pieceOf[v];
      for (int k = 0; k < 3; ++k) xn[3 * v + k] = m.mesh.vertices[v][k];
      xn[3 * v] -= p == second ? squeeze : (p == third ? 2 * squeeze - thirdOff : 0.0);
    }
  };
  std::vector<std::uint8_t> heldVertex(n, 0), removed(n, 0);
  heldVertex[0] = 1;  // at x = 0
  const HeldPieces pieces{layout.pieceStart.data(),
                          layout.pieceVertices.data(),
                          layout.pieceOf.data(),
                          heldVertex.data(),
                          removed.data(),
                          layout.crackStart.data(),
                          layout.crackEnds.data(),
                          layout.crackRestLengthSq.data(),
                          xn.data()};
  std::vector<std::uint8_t> held(3), next(3);
  auto settle = [&](int rounds) {
    for (int p = 0; p < 3; ++p) held[p] = pieces(p);
    for (int r = 0; r < rounds; ++r) {
      for (int p = 0; p < 3; ++p) next[p] = pieces.spread(p, held.data());
      held = next;
    }
  };
  place(0.0005, 0.0);
  settle(0);
  EXPECT_EQ(held[first], 1);
  EXPECT_EQ(held[second] + held[third], 0);
  settle(1);
  EXPECT_EQ(held[second], 1) << "pressing on the held piece";
  EXPECT_EQ(held[third], 0) << "one round reaches one piece further";
  settle(2);
  EXPECT_EQ(held[third], 1);
  place(0.0, 0.0);
  settle(2);
  EXPECT_EQ(held[second] + held[third], 0) << "cracks at rest length press on nothing";
  // A few last bits short of the rest length (what a GPU's fused multiply-adds make of a crack
  // at rest) is still at rest.
  place(3e-17, 6e-17);
  settle(2);
  EXPECT_EQ(held[second] + held[third], 0) << "cracks a round-off short press on nothing";
  place(0.0005, 0.002);
  settle(2);
  EXPECT_EQ(held[second], 1);
  EXPECT_EQ(held[third], 0) << "its crack open: free";
  // Removed debris is held where it was but holds up nothing: the second piece pressing on a
  // removed first piece is free.
  for (int v = 0; v < n; ++v) removed[v] = layout.pieceOf[v] == first;
  place(0.0005, 0.0);
  settle(2);
  EXPECT_EQ(held[first], 1);
  EXPECT_EQ(held[second] + held[third], 0) << "pressing on removed debris";
}

// A sub-step's start on the CPU executor: a clamped bar cut in three, its middle piece pressed
// against the clamped one (held) and its end piece pulled away (free). Only the elements a free
// piece reads are evaluated (those between the two held pieces were, every sub-step, before),
// and only the free piece moves: by h^2 g.
TEST(AcceleratedStart, OnlyTheElementsBetweenAFreePieceAndOthersAreEvaluated) {
  const SimModel m = buildSimModel(gridBar(3, 1, 1, 0.01), rubber());
  const SimState s = cutInThree(m);
  const PieceLayout layout = pieceLayout(m, s.damaged);
  ASSERT_EQ(layout.pieces(), 3);
  const int n = m.numVertices();
  const double h = 0.01;
  std::vector<std::uint8_t> fixed(n, 0), removed(n, 0);
  std::vector<double> xn(3 * n), vn(3 * n, 0.0);
  std::vector<int> region(n);  // 0 clamped piece, 1 pressed, 2 free
  for (int v = 0; v < n; ++v) {
    const double px = m.mesh.vertices[v].x();
    region[v] = px < 0.015 ? 0 : px < 0.025 ? 1 : 2;
    fixed[v] = px < 1e-9 ? 1 : 0;
    for (int k = 0; k < 3; ++k) xn[3 * v + k] = m.mesh.vertices[v][k];
    xn[3 * v] += region[v] == 1 ? -0.0005 : region[v] == 2 ? 0.002 : 0.0;
  }
  std::vector<double> x = xn;
  CpuExecutor ex;
  AcceleratedStart<CpuExecutor> start;
  const auto in = atRest(true, fixed, removed, xn, vn, m, h, {0.0, -9.81, 0.0});
  std::vector<std::uint8_t> evaluated(m.numTets(), 0);
  std::uint8_t* mark = evaluated.data();
  const auto gradient = [mark](int t, const double*, double* g) {
    mark[t] = 1;
    for (int i = 0; i < 12; ++i) g[i] = 0.0;
  };
  start.start(ex, m, pieceLayout(m, s.damaged, s.damageRevision), in, gradient, nullptr, x.data());
  int betweenHeld = 0, touchingFree = 0;
  for (int t : layout.sharedTets) {
    bool free = false;
    for (int c = 0; c < 4; ++c) free = free || region[m.mesh.tets[t][c]] == 2;
    if (free) {
      ++touchingFree;
      EXPECT_EQ(evaluated[t], 1) << "element " << t << " touches the free piece";
    } else {
      ++betweenHeld;
      EXPECT_EQ(evaluated[t], 0) << "element " << t << " lies between held pieces";
    }
  }
  EXPECT_GT(betweenHeld, 0);
  EXPECT_GT(touchingFree, 0);
  for (int v = 0; v < n; ++v) {
    const double fall = region[v] == 2 ? h * h * 9.81 : 0.0;
    EXPECT_NEAR(x[3 * v + 1], xn[3 * v + 1] - fall, 1e-15) << "vertex " << v;
  }
}

// Pieces at rest against a held one, their cracks as the knife left them: pressing on nothing
// at x_n. Falling away from it (gravity along +x) each starts a fall's worth further; falling
// into it (-x), its start would press on the clamped piece, so it keeps the straight line, and
// then so does the piece beyond, which would press on it (a second round).
TEST(AcceleratedStart, APieceWhoseStartWouldPressOnAHeldPieceKeepsTheStraightLine) {
  const SimModel m = buildSimModel(gridBar(3, 1, 1, 0.01), rubber());
  const SimState s = cutInThree(m);
  const int n = m.numVertices();
  const double h = 0.01;
  std::vector<std::uint8_t> fixed(n, 0), removed(n, 0);
  std::vector<double> xn(3 * n), vn(3 * n, 0.0);
  for (int v = 0; v < n; ++v) {
    fixed[v] = m.mesh.vertices[v].x() < 1e-9 ? 1 : 0;
    for (int k = 0; k < 3; ++k) xn[3 * v + k] = m.mesh.vertices[v][k];
  }
  for (const double gx : {9.81, -9.81}) {
    std::vector<double> x = xn;
    CpuExecutor ex;
    AcceleratedStart<CpuExecutor> start;
    const auto in = atRest(true, fixed, removed, xn, vn, m, h, {gx, 0.0, 0.0});
    const auto noPush = [](int, const double*, double* g) {
      for (int i = 0; i < 12; ++i) g[i] = 0.0;
    };
    start.start(ex, m, pieceLayout(m, s.damaged, s.damageRevision), in, noPush, nullptr, x.data());
    for (int v = 0; v < n; ++v) {
      const bool clamped = m.mesh.vertices[v].x() < 0.015;
      const double fall = gx > 0.0 && !clamped ? h * h * gx : 0.0;
      EXPECT_NEAR(x[3 * v], xn[3 * v] + fall, 1e-15) << "vertex " << v << ", gravity " << gx;
    }
  }
}

// Where the frame still has every element's gradient at x_n (its last accepted trial), the
// elements between pieces are read from it, not evaluated, and the pieces start exactly where
// the evaluated gradients would have started them.
TEST(AcceleratedStart, GradientsTheFrameStillHasAreReadNotEvaluated) {
  const SimModel m = buildSimModel(gridBar(2, 1, 1, 0.01), rubber());
  SimState s = initialState(m);
  cutAt(m, s, 0.01);
  const int n = m.numVertices();
  std::vector<double> xn(3 * n), vn(3 * n, 0.0);
  for (int v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k) xn[3 * v + k] = m.mesh.vertices[v][k];
  const std::vector<std::uint8_t> fixed(n, 0), removed(n, 0);
  const double h = 0.01;
  const auto in = atRest(false, fixed, removed, xn, vn, m, h, {0.0, -9.81, 0.0});
  // Each element's corners pushed up unevenly (an energy gradient pointing down), by its index.
  const auto push = [](int t, int i) { return i % 3 == 1 ? -1e-4 * (1 + t % 5) * (1 + i) : 0.0; };
  int evaluated = 0;
  const auto evaluate = [&](int t, const double*, double* g) {
    ++evaluated;
    for (int i = 0; i < 12; ++i) g[i] = push(t, i);
  };
  std::vector<double> held(12 * static_cast<size_t>(m.numTets()));
  for (int t = 0; t < m.numTets(); ++t)
    for (int i = 0; i < 12; ++i) held[12 * t + i] = push(t, i);
  CpuExecutor ex;
  AcceleratedStart<CpuExecutor> start;
  std::vector<double> fromEvaluated = xn, fromHeld = xn;
  start.start(ex, m, pieceLayout(m, s.damaged, s.damageRevision), in, evaluate, nullptr,
              fromEvaluated.data());
  const int evaluations = evaluated;
  start.start(ex, m, pieceLayout(m, s.damaged, s.damageRevision), in, evaluate, held.data(),
              fromHeld.data());
  EXPECT_GT(evaluations, 0);
  EXPECT_EQ(evaluated, evaluations) << "nothing evaluated where the frame has the gradients";
  EXPECT_TRUE(fromHeld == fromEvaluated);
  double offGravity = 0.0;  // the push changed the start
  for (int v = 0; v < n; ++v)
    offGravity =
        std::max(offGravity, std::abs(fromHeld[3 * v + 1] - (xn[3 * v + 1] - h * h * 9.81)));
  EXPECT_GT(offGravity, 1e-3 * h * h * 9.81);
}

// The push of its neighbours (through the elements between them) adds to a piece's
// acceleration: held up with half its weight it falls at g / 2; pushed with three times its
// weight (a hard contact) it keeps the straight line.
TEST(AcceleratedStart, ThePushOfItsNeighboursAddsToAPiecesAcceleration) {
  const SimModel m = buildSimModel(gridBar(2, 1, 1, 0.01), rubber());
  SimState s = initialState(m);
  cutAt(m, s, 0.01);
  const PieceLayout layout = pieceLayout(m, s.damaged);
  ASSERT_EQ(layout.pieces(), 2);
  const int n = m.numVertices();
  std::vector<double> xn(3 * n), vn(3 * n, 0.0);
  for (int v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k) xn[3 * v + k] = m.mesh.vertices[v][k];
  double weight = 0.0;  // of piece 0
  for (int i = layout.pieceStart[0]; i < layout.pieceStart[1]; ++i)
    weight += 9.81 * m.mass[layout.pieceVertices[i]];
  const std::vector<std::uint8_t> held(2, 0);  // per piece
  const double h = 0.01;
  for (double push : {0.5, 3.0}) {
    // Upwards on one of piece 0's corners: the energy gradient points down.
    std::vector<double> gradient(12 * layout.sharedTets.size(), 0.0);
    gradient[layout.couplingSlot[layout.couplingStart[0]] + 1] = -push * weight;
    std::vector<double> x(3 * n, -1.0);
    const AcceleratedPiece piece = pieceKernel(layout, held.data(), gradient.data(), xn, vn, m, h,
                                               0.0, Vec3(0.0, -9.81, 0.0), x.data());
    piece(0);
    for (int i = layout.pieceStart[0]; i < layout.pieceStart[1]; ++i) {
      const int v = layout.pieceVertices[i];
      if (push < kMostPush)
        EXPECT_NEAR(x[3 * v + 1], xn[3 * v + 1] - h * h * 9.81 * (1.0 - push), 1e-15);
      else
        EXPECT_EQ(x[3 * v + 1], -1.0) << "a hard contact: left to the straight line";
    }
  }
}

struct Flight {
  SimState state;
  int newton = 0, unconverged = 0;
};

Flight fly(const SimModel& m, SimState s, const StepSettings& settings, int frames) {
  CpuStepBackend cpu(m);
  Flight r;
  for (int f = 0; f < frames; ++f) {
    const StepReport rep = cpu.step(s, settings);
    r.newton += rep.newtonIterations;
    r.unconverged += rep.converged ? 0 : 1;
  }
  r.state = std::move(s);
  return r;
}

StepSettings converged() {
  return convergedPreset();
}

// The bar clamped at x = 0, three slices cut off its free end, all thrown upwards.
SimState thrownSlices(const SimModel& m) {
  SimState s = initialState(m);
  for (double c : {0.03, 0.05, 0.07}) cutAt(m, s, c);
  AnchorConstraint clamp;
  for (int v = 0; v < m.numVertices(); ++v)
    if (m.mesh.vertices[v].x() < 1e-9) clamp.vertices.push_back(v);
  s.anchors = {clamp};
  for (int v = 0; v < m.numVertices(); ++v) s.v[v] = Vec3(0.0, 1.0, 0.5);
  return s;
}

// A stiff bar clamped at one end, three slices cut off its free end, all thrown upwards: the
// slices fly on together, pushing on each other, while the clamp holds the rest. Starting each
// piece with its acceleration (gravity and its neighbours' push) takes no more Newton iterations
// than the straight line, converges every frame and stays nearer the reference's motion. (A
// slice started a fall's worth into the bar's face took 76 iterations against 41: pieces whose
// start would press on a held one keep the straight line.)
TEST(AcceleratedStart, SlicesThrownOffAClampedBarConvergeAsFastAndNearer) {
  const SimModel m = buildSimModel(gridBar(10, 2, 2, 0.01), rubber(5e6));
  const SimState s = thrownSlices(m);
  // The starts compared alone: no local iterations after them (a region's choice shifts the
  // count by an iteration either way).
  StepSettings start = converged();
  start.localNewton = false;
  StepSettings straight = start;
  straight.acceleratedStart = false;
  const int frames = 30;
  const Flight accelerated = fly(m, s, start, frames);
  const Flight line = fly(m, s, straight, frames);
  const Flight reference = fly(m, s, referenceSettings(StepSettings{}), frames);
  auto error = [&](const SimState& st) {
    double err = 0.0, travel = 0.0;
    for (int v = 0; v < m.numVertices(); ++v) {
      err = std::max(err, (st.x[v] - reference.state.x[v]).norm());
      travel = std::max(travel, (reference.state.x[v] - s.x[v]).norm());
    }
    EXPECT_GT(travel, 0.1) << "the slices flew";
    return err / travel;
  };
  std::printf(
      "Newton iterations over %d frames: accelerated %d, straight line %d (%d unconverged); "
      "error %.2e / %.2e\n",
      frames, accelerated.newton, line.newton, line.unconverged, error(accelerated.state),
      error(line.state));
  EXPECT_EQ(accelerated.unconverged, 0);
  EXPECT_LE(accelerated.newton, line.newton);
  EXPECT_LT(error(accelerated.state), error(line.state));
  EXPECT_LT(error(accelerated.state), 1e-3) << "within 0.1 % of the reference's motion";
}

// The start reads the gradients the last accepted trial left (a frame's later sub-steps, and
// each frame after the first) where nothing changed since, and evaluates them where damage,
// positions or rest shapes did: stepping on with one backend gives the same bits as a fresh
// backend every frame (which has no gradients yet: a reopened project), through the slices
// thrown off a clamped bar, the bar breaking further at its clamp, and sub-steps.
TEST(AcceleratedStart, HeldGradientsStartPiecesAsEvaluatedOnesDo) {
  SimModel m = buildSimModel(gridBar(10, 2, 2, 0.01), rubber(5e6));
  m.fracture = buildFractureField(m, {2e3, 0.0, 0.0, 1});
  const SimState s = thrownSlices(m);
  for (const int substeps : {1, 2}) {
    StepSettings settings = converged();
    settings.substeps = substeps;
    SimState on = s, fresh = s;
    CpuStepBackend backend(m);
    int broken = 0;
    for (int f = 0; f < 20; ++f) {
      broken += backend.step(on, settings).newlyDamaged;
      CpuStepBackend(m).step(fresh, settings);
      ASSERT_TRUE(on.x == fresh.x) << "frame " << f << ", " << substeps << " sub-steps";
      ASSERT_TRUE(on.damaged == fresh.damaged) << "frame " << f;
    }
    std::printf("%d sub-steps: %d edges broke\n", substeps, broken);
  }
}

// A thrown body cut in two, falling freely, is solved where it starts: every vertex at
// x_n + h (v_n + h g), to round-off, after one Newton iteration. Small pieces are moved by one
// thread each, a large one (over kLargePiece vertices) by reductions and a launch over its
// vertices; the straight-line start leaves the linear solve's error on the fall.
TEST(AcceleratedStart, AFallingBodyIsSolvedWhereItStartsSmallOrLarge) {
  for (const int cells : {3, 14}) {
    const SimModel m = buildSimModel(gridBar(cells, cells, cells, 0.01), rubber());
    SimState start = initialState(m);
    cutAt(m, start, 0.015);
    const PieceLayout layout = pieceLayout(m, start.damaged);
    ASSERT_EQ(layout.pieces(), 2);
    const bool large = layout.pieceStart[2] - layout.pieceStart[1] > kLargePiece;
    for (int v = 0; v < m.numVertices(); ++v) start.v[v] = Vec3(0.5, 2.0, -1.0);
    StepSettings once = converged();
    once.newtonIterations = 1;
    StepSettings straight = once;
    straight.acceleratedStart = false;
    const double h = once.dt;
    double worst = 0.0, worstStraight = 0.0;
    SimState a = start, b = start;
    step(m, a, once);
    step(m, b, straight);
    for (int v = 0; v < m.numVertices(); ++v) {
      const Vec3 exact = start.x[v] + h * (start.v[v] + h * m.gravity);
      worst = std::max(worst, (a.x[v] - exact).norm());
      worstStraight = std::max(worstStraight, (b.x[v] - exact).norm());
    }
    const double fall = h * h * m.gravity.norm();
    std::printf(
        "%d vertices (a %s piece): off the exact fall by %.1e, straight line %.1e of h^2 g\n",
        m.numVertices(), large ? "large" : "small", worst / fall, worstStraight / fall);
    EXPECT_LT(worst, 1e-9 * fall);
    EXPECT_GT(worstStraight, 1e-6 * fall) << "(the straight line leaves the solve's error)";
  }
}

}  // namespace
}  // namespace galsculpt
