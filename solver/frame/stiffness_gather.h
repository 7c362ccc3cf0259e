// The stiffness gather in host memory: the elements' packed upper 3x3 blocks (ElementPass) summed
// into the stiffness blocks on and above the diagonal, element by element over row ranges.
//
// Why not a thread per block, as a device does (ElasticTerm::evaluate): a block's
// terms lie in elements scattered over the element array, and an element's ten blocks are read
// at ten different rows' times, so on a CPU each read waits on memory (asking for them ahead did
// not help). Here each range of rows walks its elements in ascending order, reading each
// element's blocks at once: the element array streams through the caches instead.
//
// The same bits as a thread per block: a block's terms are added in ascending element order
// from zero, as SimModel::blockSlots lists them, whatever the ranges and the thread count (a
// block belongs to one range, and a range walks its elements in order).
#pragma once

#include <cstdint>
#include <vector>

#include "solver/fem/block_sparse.h"
#include "solver/frame/element_pass.h"

namespace galsculpt {

class StiffnessGather {
 public:
  // From the model's block pattern, `scatter` (each tet's 16 block indices) and `tetVertices`
  // (4 per tet); the pattern and the vertices must outlive the gather. The row ranges are made
  // at the first gather, and again when the thread count changes.
  StiffnessGather(const BlockPattern& pattern, const std::vector<TetScatter>& scatter,
                  const int* tetVertices);

  // kb's blocks on and above the diagonal from the packed blocks `packed` (90 per tet), as the
  // per-block gather: `opened` skips the elements whose stiffness is zero
  // (ElementPass::zeroStiffness); with `fresh`, only blocks with a term of an element whose flag
  // is set are summed again (the others keep what kb holds); with `touched`, only blocks whose
  // row and column are both touched. The blocks below the diagonal are not written.
  void gatherUpper(const double* packed, const std::uint8_t* opened, const std::uint8_t* fresh,
                   const std::uint8_t* touched, double* kb);

  // How many row ranges the gather uses for `threads` threads (a few per thread, for balance).
  static int rangesFor(int threads, int rows);

 private:
  void buildRanges(int ranges);

  const BlockPattern& pattern_;
  const int* tetVertices_;
  int tets_ = 0;
  // Each tet's ten packed blocks' targets: the upper block each adds into (packedBlock order).
  std::vector<int> target_;
  int ranges_ = 0;
  std::vector<int> rangeRow_;                   // (ranges + 1) first row of each range
  std::vector<int> rangeTetStart_, rangeTets_;  // CSR: each range's tets, ascending
  std::vector<std::uint8_t> dirty_;             // (blocks) summed again in this gather
};

}  // namespace galsculpt
