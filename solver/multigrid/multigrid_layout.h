// The multigrid hierarchy (multigrid.h) as flat arrays, in the order the executors read them
// (host code, built with or without CUDA); rebuilt when damage changes the hierarchy.
//
// Race-free refresh without atomics, as the fine assembly (SimModel's assembly lists): every
// 12x12 block of a coarse operator has its own list of the finer blocks that add into it,
// aggregate row by row, so each is one thread's fixed-order sum.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/fem/block_sparse.h"
#include "solver/multigrid/multigrid.h"

namespace galsculpt {

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
