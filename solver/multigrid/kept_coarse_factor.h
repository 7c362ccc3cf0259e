// The coarsest matrix of the Galerkin multigrid as last factored (host memory) and whether a new
// one is close enough to keep that factorization. Only where the V-cycle preconditions CG
// (multigrid_cycle.h): its coarsest solve may then be that of a nearby matrix, positive definite
// all the same, and the frame still solves the same equations to the same tolerance.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace galsculpt {

class KeptCoarseFactor {
 public:
  // How far the matrix may move from the one factored, entry by entry relative to the geometric
  // mean of its row's and column's diagonal entries (|A_ij - F_ij| <= kReuse sqrt(F_ii F_jj):
  // scale-free, so an affine handle's linear and translation rows count alike). A body at rest
  // keeps its factorization; in motion the matrix moves more than this (crack faces meet and
  // part) and it is factored again.
  static constexpr double kReuse = 1e-2;

  void clear() { blocks_.clear(); }

  // After a factorization of the 12x12 blocks `blocks` (`size` doubles; `diagonal`: each
  // handle's diagonal block): remembered where it succeeded.
  void remember(bool factored, const double* blocks, size_t size, const int* diagonal,
                int handles) {
    if (!factored) {
      blocks_.clear();
      return;
    }
    blocks_.assign(blocks, blocks + size);
    rootDiagonal_.assign(12 * static_cast<size_t>(handles), 0.0);
    for (int h = 0; h < handles; ++h)
      for (int i = 0; i < 12; ++i)
        rootDiagonal_[12 * h + i] =
            std::sqrt(std::abs(blocks[144 * static_cast<size_t>(diagonal[h]) + 13 * i]));
  }

  // Whether the factorization remembered serves `blocks` (same pattern: rowStart, columns).
  bool keeps(const double* blocks, size_t size, const int* rowStart, const int* columns,
             int handles) const {
    if (blocks_.empty() || blocks_.size() != size) return false;
    const double* was = blocks_.data();
    const double* root = rootDiagonal_.data();
    for (int r = 0; r < handles; ++r)
      for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) {
        const double* rowRoot = root + 12 * r;
        const double* columnRoot = root + 12 * columns[k];
        for (int j = 0; j < 12; ++j)
          for (int i = 0; i < 12; ++i) {
            const size_t at = 144 * static_cast<size_t>(k) + i + 12 * j;
            if (!(std::abs(blocks[at] - was[at]) <= kReuse * rowRoot[i] * columnRoot[j]))
              return false;
          }
      }
    return true;
  }

  // The matrix factored (empty: none).
  const std::vector<double>& matrix() const { return blocks_; }

 private:
  std::vector<double> blocks_, rootDiagonal_;  // the matrix factored, its diagonal's roots
};

}  // namespace galsculpt
