// Elements evaluated four at a time, one element per SIMD lane: the CPU's fast path for what
// dominates an element pass. Intact elements: the energy, force and projected stiffness, or
// the energy and force alone (a line search's trial).
// Damaged elements (the edge-strain form with cracks that open one way): the energy, force,
// open cracks and projected stiffness (after many cuts most of the body's elements).
//
// The lanes compute exactly the bits of the scalar kernel (element_kernels.h's evaluateElement,
// the stiffness then packed): the same algorithm (closed-form eigen-solves and, where those are
// not accurate, the same cyclic Jacobi sweeps; the rotation-variant SVD; the analytic
// eigensystem of dP/dF; for a damaged element each lane's own pivoting over its open cracks),
// the same operations in the same order, no fused multiply-add; transcendental calls go to libm
// lane by lane. Where the scalar kernel would turn to its accurate SVD (a rank-deficient F,
// factors that do not reproduce F) or a result is not finite, the lane is handed back and the
// caller evaluates that element with the scalar kernel; an element whose two intact edges hold
// two pieces (holdsTwoPieces) never enters them. So the scalar kernel stays the one definition
// of the physics (and the one the GPU runs), pinned determinism hashes do not move, and a test
// compares the two bit for bit.
//
// Two builds of the same source: one for AVX2 (four doubles per instruction), chosen at startup
// where the CPU has it, and a portable one (SSE2 pairs) for every x86-64, slower than the scalar
// kernel and so never chosen by default (it keeps the lane logic tested on any x86-64). The
// environment variable GALSCULPT_ELEMENT_LANES (avx2, portable, off) overrides the choice, which
// also picks the multigrid's fine smoother rows (solver/multigrid/fine_rows.h).
#pragma once

#include "solver/fem/element_kernels.h"
#include "solver/fem/material_types.h"

namespace galsculpt::kernels {

inline constexpr int kLanes = 4;

struct LaneInputs {
  int count = 0;                      // lanes in use, 1..kLanes
  const RestData* rest[kLanes] = {};  // each lane's rest data
  double x[kLanes][12] = {};          // each lane's corner positions
  double yield[kLanes] = {};          // each lane's yield stress (Lame::yield)
  bool stiffness = true;  // false: the energy and the force only (packedHessian not written)
};

// Where each lane writes: its energy (J), its force gradient (12) and its stiffness as the ten
// upper 3x3 blocks (a <= c) of the 12x12, block (a, c) at 9 (4a - a(a-1)/2 + c - a), each
// column-major: FrameSolver's packed layout.
struct LaneOutputs {
  double* energy[kLanes] = {};
  double* gradient[kLanes] = {};
  double* packedHessian[kLanes] = {};
  std::uint8_t* opened[kLanes] = {};  // damaged elements only: their open cracks
};

// Damaged elements: besides the rest data and corners, each lane's intact edges (neither all
// six nor two opposite ones: holdsTwoPieces) and whether its cracks resist closing.
struct CrackedLaneInputs {
  int count = 0;
  const RestData* rest[kLanes] = {};
  double x[kLanes][12] = {};
  std::uint8_t intact[kLanes] = {};
  bool resists[kLanes] = {};
};

// Evaluates the lanes in use; returns the bit mask of those it handed back (not written).
using LaneKernel = unsigned (*)(MaterialModel, const Lame&, const LaneInputs&, const LaneOutputs&);
// Damaged elements with their stiffness (Hessian::ProjectedSpd); returns the lanes handed back.
// The stiffness of an element whose six edges' cracks all opened is zero and is not written
// (the caller tells it by `opened`: every bit set).
using CrackedLaneKernel = unsigned (*)(const Lame&, const CrackedLaneInputs&, const LaneOutputs&);

enum class LaneBuild { Off, Portable, Avx2 };

// The build for this process: the last setLaneBuild, else the environment's choice, else AVX2
// where the CPU has it (Off otherwise: the scalar kernel).
LaneBuild chosenLaneBuild();
// Process-wide, as the environment variable is (tests compare builds in one process).
void setLaneBuild(LaneBuild build);
// The kernel of a build; null for Off, and for Avx2 on a CPU without AVX2.
LaneKernel laneKernel(LaneBuild build);
CrackedLaneKernel crackedLaneKernel(LaneBuild build);
const char* laneBuildName(LaneBuild build);

// element_kernels.h's addOpenedCrackEnergy, compiled with the program's own flags: what the
// damaged elements' lanes call for each element's opening problem.
void openCracks(const double k[6][6], const double eps[6], std::uint8_t free, std::uint8_t oneWay,
                double width, bool wantStiffness, CrackedStrainState& out);

namespace avx2 {
unsigned evaluateIntactLanes(MaterialModel, const Lame&, const LaneInputs&, const LaneOutputs&);
unsigned evaluateCrackedLanes(const Lame&, const CrackedLaneInputs&, const LaneOutputs&);
}  // namespace avx2
namespace portable {
unsigned evaluateIntactLanes(MaterialModel, const Lame&, const LaneInputs&, const LaneOutputs&);
unsigned evaluateCrackedLanes(const Lame&, const CrackedLaneInputs&, const LaneOutputs&);
}  // namespace portable

}  // namespace galsculpt::kernels
