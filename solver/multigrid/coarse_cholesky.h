// The coarsest level's direct solve in host memory: a sparse Cholesky by 12x12 blocks (block
// CSR in), with a fill-reducing (AMD) ordering of the handle graph analysed once per pattern.
//
// Why not the dense factorization the device uses: the handles are coupled only to their
// neighbours, so the sparse factor costs a fraction of the dense one, and the dense one grows
// with the cube of their number. Cracks split the coarse handles (a handle whose aggregate a
// crack divides becomes one per part): on the hanging sphere (35,540 tets) 10 random cuts took
// the coarsest level from 50 to 110 handles and 100 cuts to 199, and the dense factorization,
// refreshed with every Newton matrix, went from a few milliseconds to hundreds. Uncut, 50 to 61
// handles, the dense factorization still took 5-9 ms of each Newton matrix on the human figure
// and Charpy's bar, whose handle graphs follow their limbs and length, and this one 0.5-0.7 ms
// (docs/notes/2026-12-05-crack-faces-newton-and-the-coarsest-factor.md): the host factors every
// coarsest level so.
//
// Why by blocks and not Eigen's SimplicialLLT (which this replaced): every handle is twelve
// affine DOFs coupled as a whole, so the factor's pattern is the handle graph's, block for block.
// Factored column by column of blocks, each update is a dense 12x12 product instead of scalar
// updates through index lists (docs/notes/2026-12-03-coarsest-level-factored-1212-blocks.md
// has the measurements). Single-threaded, in a fixed order, so its round-off does not
// depend on the thread count (tests/engine/session/determinism_test.cpp); CHOLMOD's supernodal
// factor would thread through BLAS.
#pragma once

#include <memory>

namespace galsculpt {

class CoarseCholesky {
 public:
  CoarseCholesky();
  ~CoarseCholesky();
  CoarseCholesky(const CoarseCholesky&) = delete;
  CoarseCholesky& operator=(const CoarseCholesky&) = delete;

  // Factors the symmetric matrix of `handles` x `handles` blocks of 12x12 (block CSR with both
  // triangles: rowStart (handles + 1), columns, blocks of 144 column-major doubles each). The
  // ordering is analysed again only when the pattern differs from the last one. False when the
  // matrix is not positive definite (nothing to solve with then).
  bool factor(int handles, const int* rowStart, const int* columns, const double* blocks);
  // x <- A^-1 x with the last successful factorization (12 handles doubles).
  void solve(double* x) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace galsculpt
