// The terms of the incremental potential that need a pass over the mesh (the elements, the
// colliders), as a list: IncrementalPotential, Newton (frame_solver.h) and the line search go
// over the list, never over a term by name. The coordinate terms (coordinate_terms.h: inertia,
// gravity, damping, springs) are the other list, summed per coordinate in one launch.
//
// A pass term is a class template over the executor, constructed from a PassTermContext, with:
//   double* energySlot(FrameScalars*, bool trial)  its energy at x (or at the trial), a scalar
//   void atIterate(d, y, reuse, gradient)   energy at Newton's iterate y, its gradient into
//       `gradient` and its Newton blocks (with `reuse`, the last accepted trial's, kept);
//   void atTrial(d, y, only, gradient)      energy at a line-search trial (with `only`, the
//       flagged elements again: the vertex guard's rounds), and with `gradient` not null its
//       gradient there, as atAccepted would give it were the trial accepted;
//   void atAccepted(d, y, gradient)         its gradient at the accepted positions;
//   VertexShare vertexShare(d, bool trial)  add(v, sum): vertex v's share of its energy;
//   Blocks diagonalBlocks(d)                add(r, y, out): its part of free vertex r's 3x3
//       diagonal block, added inside the system's assembly (a term whose blocks are gathered
//       into the stiffness, as the elements', adds none there);
// and a finite-difference test of its gradient and blocks in tests/solver/frame/.
// Adding one: its file and its place in PassTerms (incremental_potential.h).
//
// The order of the sums is part of the frame's pinned bits (determinism_test.cpp), one per sum:
// - gradients in list order, the first term writing `gradient` and the others adding to it
//   (the first may write only some vertices: a local iteration's pass keeps the others);
// - energies folded left in list order, ((e0 + e1) + e2) ...;
// - vertex shares from the last term to the first (the colliders' share before the elements');
// - diagonal blocks in list order.
// Each launches and reduces into the frame's scalars and never reads them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <tuple>

#include "solver/fem/kernel_math.h"
#include "solver/frame/frame_data.h"
#include "solver/frame/frame_scalars.h"
#include "solver/frame/plastic_state.h"
#include "solver/model/sim_model.h"

namespace galsculpt {

// What a pass term is built from.
template <typename Exec>
struct PassTermContext {
  Exec& ex;
  const SimModel& model;
  FrameData<Exec>& data;
  const PlasticState<Exec>& plastic;
};

// The terms' energy scalars, summed left to right on the executor.
template <size_t N>
struct EnergySlots {
  const double* slot[N];
  GALSCULPT_HD double sum() const {
    double s = *slot[0];
    for (size_t i = 1; i < N; ++i) s += *slot[i];
    return s;
  }
};

// The terms' vertex shares, added from the last to the first.
template <typename... Shares>
struct VertexShareList {
  GALSCULPT_HD void add(int, double&) const {}
};
template <typename First, typename... Rest>
struct VertexShareList<First, Rest...> {
  First first;
  VertexShareList<Rest...> rest;
  GALSCULPT_HD void add(int v, double& sum) const {
    rest.add(v, sum);
    first.add(v, sum);
  }
};

// The terms' diagonal blocks, added in list order.
template <typename... Blocks>
struct DiagonalBlockList {
  GALSCULPT_HD void add(int, const double*, double*) const {}
};
template <typename First, typename... Rest>
struct DiagonalBlockList<First, Rest...> {
  First first;
  DiagonalBlockList<Rest...> rest;
  GALSCULPT_HD void add(int r, const double* y, double out[9]) const {
    first.add(r, y, out);
    rest.add(r, y, out);
  }
};

// The lists from their terms' parts, in list order.
inline VertexShareList<> shareList() {
  return {};
}
template <typename First, typename... Rest>
VertexShareList<First, Rest...> shareList(const First& first, const Rest&... rest) {
  return {first, shareList(rest...)};
}
inline DiagonalBlockList<> blockList() {
  return {};
}
template <typename First, typename... Rest>
DiagonalBlockList<First, Rest...> blockList(const First& first, const Rest&... rest) {
  return {first, blockList(rest...)};
}

template <typename Exec, template <typename> class... Terms>
class PassTermList {
 public:
  static constexpr size_t kTerms = sizeof...(Terms);
  static_assert(kTerms > 0, "the first term writes the gradient");
  using Shares = VertexShareList<typename Terms<Exec>::VertexShare...>;
  using Blocks = DiagonalBlockList<typename Terms<Exec>::Blocks...>;

  explicit PassTermList(const PassTermContext<Exec>& context)
      : d_(context.data), terms_(constructedFrom<Terms<Exec>>(context)...) {}

  // The term of type Term (a colliders' pose, a pendulum's force: what is not a sum).
  template <typename Term>
  Term& term() {
    return std::get<Term>(terms_);
  }
  template <typename Term>
  const Term& term() const {
    return std::get<Term>(terms_);
  }

  void atIterate(const double* y, bool reuse, double* gradient) {
    std::apply([&](auto&... t) { (t.atIterate(d_, y, reuse, gradient), ...); }, terms_);
  }
  void atTrial(const double* y, const std::uint8_t* only, double* gradient = nullptr) {
    std::apply([&](auto&... t) { (t.atTrial(d_, y, only, gradient), ...); }, terms_);
  }
  void atAccepted(const double* y, double* gradient) {
    std::apply([&](auto&... t) { (t.atAccepted(d_, y, gradient), ...); }, terms_);
  }
  EnergySlots<kTerms> energies(bool trial) {
    FrameScalars* sc = d_.sc();
    return std::apply([&](auto&... t) { return EnergySlots<kTerms>{{t.energySlot(sc, trial)...}}; },
                      terms_);
  }
  Shares vertexShares(bool trial) {
    return std::apply([&](auto&... t) { return shareList(t.vertexShare(d_, trial)...); }, terms_);
  }
  Blocks diagonalBlocks() {
    return std::apply([&](auto&... t) { return blockList(t.diagonalBlocks(d_)...); }, terms_);
  }

 private:
  template <typename Term>
  static const PassTermContext<Exec>& constructedFrom(const PassTermContext<Exec>& c) {
    return c;
  }

  FrameData<Exec>& d_;
  std::tuple<Terms<Exec>...> terms_;
};

}  // namespace galsculpt
