// A frame's arrays in executor memory, shared by its parts as MuJoCo's stage functions share
// mjData: the model's arrays (mirrored: read in place on the CPU, uploaded once to a GPU), the
// state and the Newton iteration's vectors, the elements' outputs, the system's blocks, the
// held vertices and the scalars handed back to the host. Everything is allocated here, up front:
// nothing may allocate inside a captured section. The parts (incremental_potential.h,
// line_search.h, linear_solve.h, held_vertices.h) and the frame (frame_solver.h) take it by
// reference; the sub-step's settings, length and damping stiffness choice are set by the frame.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "solver/fem/element_kernels.h"
#include "solver/frame/element_pass.h"
#include "solver/frame/frame_scalars.h"
#include "solver/frame/step.h"
#include "solver/model/sim_model.h"

namespace galsculpt {

template <typename Exec>
struct FrameData {
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;
  template <typename T>
  using Mirror = typename Exec::template Mirror<T>;

  explicit FrameData(const SimModel& model)
      : n(model.numVertices()),
        tets(model.numTets()),
        edges(model.numEdges()),
        blocks(model.numBlocks()) {
    // Each block's row, and the index of its transpose partner (c, r) of (r, c): the stiffness
    // is gathered into the blocks on and above the diagonal and mirrored into the others.
    std::vector<int> rows(blocks), transposed(blocks);
    for (int r = 0; r < n; ++r)
      for (int k = model.pattern.rowStart[r]; k < model.pattern.rowStart[r + 1]; ++k) {
        rows[k] = r;
        transposed[k] = model.pattern.find(model.pattern.columns[k], r);
      }
    blockRow.adopt(std::move(rows));
    transposedBlock.adopt(std::move(transposed));
    tetVertices.mirror(model.tetVertexArray(), 4 * static_cast<size_t>(tets));
    tetEdges.mirror(model.tetEdgeArray(), 6 * static_cast<size_t>(tets));
    rest.mirror(model.rest);
    mass.mirror(model.mass);
    rowStart.mirror(model.pattern.rowStart);
    diagonal.mirror(model.pattern.diagonal);
    columns.mirror(model.pattern.columns);
    vertexSlotStart.mirror(model.vertexSlotStart);
    vertexSlots.mirror(model.vertexSlots);
    blockSlotStart.mirror(model.blockSlotStart);
    blockSlots.mirror(model.blockSlots);
    for (Buffer<double>* b :
         {&x, &v, &xn, &vn, &xhat, &grad, &trialGrad, &acceptedGrad, &g, &delta, &trial, &dampedK,
          &tmp, &savedX, &savedV, &rhs, &product, &trialG, &trialForces})
      b->resize(3 * n);
    fixed.resize(n);
    removed.resize(n);
    springK.resize(n);
    springTarget.resize(3 * n);
    damaged.resize(edges);
    for (Buffer<double>* b : {&elemEnergy, &elemInverted, &trialEnergy, &trialInverted})
      b->resize(tets);
    guardDirty.resize(tets);
    for (Buffer<double>* b : {&guardLength, &potentialAtX, &potentialAtTrial}) b->resize(n);
    guardChanged.resize(n);
    for (Buffer<std::uint8_t>* b : {&regionVertex, &regionScratch, &regionFixed, &regionTouched})
      b->resize(n);
    regionElement.resize(tets);
    vertexResidual.resize(n);
    stiffnessF.resize(9 * static_cast<size_t>(tets));
    stiffnessFresh.resize(tets);
    stiffnessOpened.resize(tets);
    trialOpened.resize(tets);
    elemGrad.resize(12 * static_cast<size_t>(tets));
    elemHess.resize(ElementPass::kPackedHessian * static_cast<size_t>(tets));
    for (Buffer<double>* b : {&stiffness, &system}) b->resize(9 * static_cast<size_t>(blocks));
    scalars.resize(1);
  }

  // The stiffness that damping multiplies: frozen at x_n (a copy) with several Newton
  // iterations, otherwise the current one.
  const double* frozenBlocks() const { return frozenIsK ? stiffness.data() : frozen.data(); }
  FrameScalars* sc() { return scalars.data(); }
  // What the Newton system holds still: the held vertices, and in a local iteration
  // (local_region.h) every vertex outside the region too. The residual is always the body's.
  const std::uint8_t* solveFixed() const { return local ? regionFixed.data() : fixed.data(); }
  // The elements an iteration evaluates: all (null), or in a local iteration the region's.
  const std::uint8_t* evaluated() const { return local ? regionElement.data() : nullptr; }
  // The vertices whose gathered sums such an iteration changes: all (null), or the corners of the
  // region's elements.
  const std::uint8_t* touched() const { return local ? regionTouched.data() : nullptr; }

  const int n, tets, edges, blocks;

  // The model's arrays.
  Mirror<int> tetVertices, tetEdges, rowStart, columns;
  Mirror<int> diagonal;  // (n) each row's diagonal block
  Mirror<int> vertexSlotStart, vertexSlots, blockSlotStart, blockSlots;  // the gathers' lists
  Mirror<kernels::RestData> rest;
  Mirror<double> mass;
  Buffer<int> blockRow;
  Buffer<int> transposedBlock;  // (blocks) the index of block (c, r) for block (r, c)

  // Positions and velocities (3n): now, at the sub-step's start, the inertial target x_n + h v_n
  // and the saved state a failed sub-step returns to.
  Buffer<double> x, v, xn, vn, xhat, savedX, savedV;
  // The Newton iteration's: the elastic and contact gradient at x, at the trial and at the
  // accepted trial, the backward-Euler gradient g, the step, the trial positions, beta K0 (y-x_n),
  // scratch, and the linear system's right-hand side and A delta.
  Buffer<double> grad, trialGrad, acceptedGrad, g, delta, trial, dampedK, tmp, rhs, product;
  // At the last trial, where the frame tests residuals between iterations: g and the pass
  // terms' forces (IncrementalPotential::residualAtTrials).
  Buffer<double> trialG, trialForces;
  // Per element: energy and inversion at x and at the trial, gradient (12) and packed stiffness.
  Buffer<double> elemEnergy, elemInverted, trialEnergy, trialInverted, elemGrad, elemHess;
  // 3x3 blocks of the pattern: the stiffness K, K frozen at x_n, and the system H.
  Buffer<double> stiffness, frozen, system;
  Buffer<FrameScalars> scalars;  // one
  // The vertex guard's per-vertex step lengths and potentials at x and at the trial.
  Buffer<double> guardLength, potentialAtX, potentialAtTrial;
  Buffer<std::uint8_t> guardChanged, guardDirty;
  // Kept element stiffnesses (StepSettings::stiffnessTolerance): the deformation gradient each
  // element's stiffness in elemHess was evaluated at in this sub-step (NaN: evaluate again)
  // and whether this pass evaluated it. Damage needs no check: a damaged element is evaluated
  // every time, and an intact one's stiffness does not depend on its neighbours'.
  Buffer<double> stiffnessF;
  Buffer<std::uint8_t> stiffnessFresh;
  // Each element's open cracks where the stiffness was evaluated and at the last trial: a chord
  // step is taken only while few differ.
  Buffer<std::uint8_t> stiffnessOpened, trialOpened;
  Buffer<std::uint8_t> damaged;  // (edges)
  // The held vertices (held_vertices.h): anchored or removed debris (fixed), removed debris
  // (removed), and the anchored ones' targets at the sub-step's end.
  Buffer<std::uint8_t> fixed, removed;
  Buffer<int> anchorVertices;
  Buffer<double> anchorTargets;
  size_t anchorCount = 0;
  // Soft anchors (AnchorConstraint::springWeights): each vertex's spring stiffness (0: none) and
  // its target at the sub-step's end; terms of the potential, not held vertices.
  Buffer<double> springK, springTarget;
  // The local iteration's region (local_region.h): its vertices, a scratch for growing it, the
  // elements that touch it and their corners (touched), what its solve holds still, and each
  // vertex's |g|^2 it was chosen by.
  Buffer<std::uint8_t> regionVertex, regionScratch, regionFixed, regionElement, regionTouched;
  Buffer<double> vertexResidual;

  // The sub-step's, set by the frame.
  const StepSettings* settings = nullptr;
  double h = 0.0;
  bool frozenIsK = true;
  bool local = false;  // this Newton iteration solves only in the region (local_region.h)
};

}  // namespace galsculpt
