// The reference solver's linear solve: CHOLMOD's supernodal Cholesky of the fine system, held
// in host memory as 3x3 blocks on the model's pattern (block CSR). The pattern is analysed once;
// each solve factors the current values. Runs only where the system lives in host memory (the
// CPU executor): the reference is the test oracle, not a fast path.
#pragma once

#include <memory>

#include "solver/fem/block_sparse.h"

namespace galsculpt {

class DirectSolver {
 public:
  explicit DirectSolver(const BlockPattern& pattern);
  ~DirectSolver();
  DirectSolver(const DirectSolver&) = delete;
  DirectSolver& operator=(const DirectSolver&) = delete;

  // Solves A x = b, A given by its 9 column-major doubles per block of the pattern. False when
  // A is not positive definite (x is then left as it was).
  bool solve(const double* blocks, const double* b, double* x);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace galsculpt
