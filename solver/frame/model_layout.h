// The model, the fracture field and the multigrid hierarchy as flat arrays, in the order the
// executors read them (host code, built with or without CUDA).
//
// Race-free assembly without atomics: every output (a vertex's force, a 3x3 block of the
// stiffness, a 12x12 block of a coarse operator) has its own list of the element or finer
// contributions that add into it, in the order the CPU adds them (element colour by colour for
// the fine level; aggregate row by row for the coarse ones), so each output is one thread's
// fixed-order sum. Patterns never change; damage only rebuilds the hierarchy's lists.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/fem/element_kernels.h"
#include "solver/fracture/fracture.h"
#include "solver/model/sim_model.h"
#include "solver/multigrid/multigrid.h"

namespace galsculpt {

struct ModelLayout {
  int vertices = 0, tets = 0, edges = 0, blocks = 0;
  std::vector<int> tetVertices;         // (4 nTets)
  std::vector<int> tetEdges;            // (6 nTets) global edge of each local edge
  std::vector<kernels::RestData> rest;  // (nTets)
  std::vector<double> mass;             // (nVerts) kg
  std::vector<int> rowStart, columns;   // fine block pattern (CSR over vertices)
  std::vector<int> diagonal;            // (nVerts) block index of (v, v)
  std::vector<int> vertexSlotStart;     // (nVerts + 1) CSR: 4 t + a of each tet corner
  std::vector<int> vertexSlots;
  std::vector<int> blockSlotStart;  // (nBlocks + 1) CSR: 16 t + 4 a + b
  std::vector<int> blockSlots;
};

ModelLayout buildModelLayout(const SimModel& model);

// The fracture pass's data. The kernel's cells are numbered, each with the numbers of the 27
// cells around it (-1 where there is none, in dz-fastest order), so a
// thread finds an edge's neighbourhood without a search and can skip it when no cell near it
// holds an edge over the smallest threshold.
struct FractureLayout {
  std::vector<int> slotStart, slots;  // edge -> 6 t + local edge
  std::vector<double> threshold;      // (nEdges)
  std::vector<double> midpoint;       // (3 nEdges) rest midpoints
  std::vector<int> cellBegin, cellEnd, cellEdges;
  std::vector<int> edgeCell;       // (nEdges) the cell of each edge's midpoint
  std::vector<int> cellNeighbors;  // (27 cells)
  int cells() const { return static_cast<int>(cellBegin.size()); }
};

FractureLayout buildFractureLayout(const FractureField& field);

struct LevelLayout {
  int rows = 0;                  // rows of the finer level (fine vertices for level 0)
  int handles = 0;               // rows of this level
  std::vector<int> parent;       // (rows) handle, -1: none
  std::vector<double> y;         // level 0: (4 rows) [(x - c)/s; 1]
  std::vector<double> toParent;  // levels > 0: (144 rows) column-major 12x12
  std::vector<int> rowStart, columns, diagonal;  // coarse block CSR, diagonal block of each row
  std::vector<int> contribStart;  // (nnz + 1) CSR: finer blocks adding into each coarse block
  std::vector<int> contribBlock, contribRow;
  std::vector<int> memberStart, members;   // (handles + 1) CSR: finer rows of each aggregate
  std::vector<std::uint8_t> empty;         // (handles) no rows: identity-regularized
  std::vector<int> colorStart, colorRows;  // multi-colour Gauss-Seidel groups
};

struct MultigridLayout {
  std::vector<int> fineColorStart, fineColorRows;
  std::vector<LevelLayout> levels;
  // Coarsest pieces (pieceCount >= 2 only).
  int pieceCount = 0;
  std::vector<int> pieceOfHandle;      // (coarsest handles)
  std::vector<double> pieceMap;        // (144 coarsest handles)
  std::vector<int> pieceContribStart;  // (pieces + 1) CSR: coarsest blocks inside each piece
  std::vector<int> pieceContribBlock, pieceContribRow;
  std::vector<int> pieceHandleStart, pieceHandles;  // (pieces + 1) CSR: coarsest handles
  // Fragments: small pieces corrected in their own affine modes.
  std::vector<int> fragmentStart, fragmentVertices;
  std::vector<int> fragmentOf;        // (nVerts) -1: none
  std::vector<double> fragmentFrame;  // (4 nFragments) center xyz, scale
  std::vector<double> restPositions;  // (3 nVerts)
};

MultigridLayout buildMultigridLayout(const Multigrid& mg, const BlockPattern& fine);

}  // namespace galsculpt
