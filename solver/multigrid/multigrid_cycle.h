// The Galerkin multigrid's solve (paper section 3.2-3.3, Algorithm 2) as launches of an
// executor (the CPU one or the CUDA one): the hierarchy of multigrid.h (built and split over
// cracks on the host), mirrored as flat arrays (multigrid_layout.h); refresh A_{l+1} = U^T A_l U;
// V-cycles with multi-colour Gauss-Seidel or Jacobi smoothing; CG or a dense Cholesky on the
// coarsest level; per-piece coarse start; fragment corrections; PCG with a V-cycle
// preconditioner. Precompute (the hierarchy, once per mesh and damage change) apart from solve
// (values refreshed per Newton step, then cycles), as libigl's *_precomputation / *_solve.
//
// Nothing in a V-cycle waits for the executor: scalars of the coarse CG (alpha, its stopping
// test) live in executor memory and steer the launches that follow, so a whole solve can be
// captured as one CUDA graph. The only host decisions are structural (levels, colours,
// settings). PCG (multigrid_pcg.h) keeps its scalars there too and reads only its state, once a
// batch of iterations on a device.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "solver/fem/block_sparse.h"
#include "solver/fem/dense_kernels.h"
#include "solver/fem/launch_key.h"
#include "solver/model/solver_options.h"
#include "solver/multigrid/coarse_cholesky.h"
#include "solver/multigrid/fine_smoother.h"
#include "solver/multigrid/fragment_correction.h"
#include "solver/multigrid/kept_coarse_factor.h"
#include "solver/multigrid/multigrid.h"
#include "solver/multigrid/multigrid_layout.h"
#include "solver/multigrid/multigrid_pcg.h"
#include "solver/multigrid/piece_coarse_start.h"

namespace galsculpt {

template <typename Exec>
class MultigridCycle {
 public:
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;

  // `fine`: the model's block pattern, read in place (it must outlive the cycle).
  MultigridCycle(Exec& ex, const BlockPattern& fine)
      : ex_(ex), finePattern_(fine), smoother_(ex), pcg_(ex), pieces_(ex), fragments_(ex) {
    rows_ = fine.rows;
    fineRowStart_.mirror(fine.rowStart);
    fineColumns_.mirror(fine.columns);
    fineDiagonal_.mirror(fine.diagonal);
    ax_.resize(3 * rows_);
    scalars_.resize(kScalars);
  }

  // Mirrors the host hierarchy; call after it was built or changed (updateDamage).
  void upload(const MultigridLayout& m) {
    fineColorStart_ = m.fineColorStart;
    fineColorRows_.upload(m.fineColorRows);
    smoother_.uploadPattern(finePattern_, m.fineColorRows);
    levels_.clear();
    levels_.resize(m.levels.size());
    for (size_t l = 0; l < m.levels.size(); ++l) {
      const LevelLayout& s = m.levels[l];
      Level& d = levels_[l];
      d.rows = s.rows;
      d.handles = s.handles;
      d.nnz = static_cast<int>(s.columns.size());
      // Work per item, for the CPU executor's threading (the GPU ignores it).
      d.refreshCost = (l == 0 ? 48 : 3 * 1728) *
                      (1 + static_cast<long>(s.contribRow.size()) / std::max(1, d.nnz));
      d.memberCost = 36 * (1 + s.rows / std::max(1, s.handles));
      d.rowCost = 144 * (1 + d.nnz / std::max(1, s.handles));
      d.parent.upload(s.parent);
      d.y.upload(s.y);
      d.toParent.upload(s.toParent);
      d.rowStart.upload(s.rowStart);
      d.columns.upload(s.columns);
      d.diagonal.upload(s.diagonal);
      d.contribStart.upload(s.contribStart);
      d.contribBlock.upload(s.contribBlock);
      d.contribRow.upload(s.contribRow);
      d.memberStart.upload(s.memberStart);
      d.members.upload(s.members);
      d.empty.upload(s.empty);
      d.colorStart = s.colorStart;
      d.colorRows.upload(s.colorRows);
      d.blocks.resize(144 * static_cast<size_t>(d.nnz));
      d.diagonalFactor.resize(144 * static_cast<size_t>(d.handles));
      d.b.resize(12 * d.handles);
      d.x.resize(12 * d.handles);
      d.ax.resize(12 * d.handles);
    }
    const Level& c = levels_.back();
    cgR_.resize(12 * c.handles);
    cgP_.resize(12 * c.handles);
    cgAp_.resize(12 * c.handles);
    pieces_.upload(m);
    fragments_.upload(m, rows_);
    dense_.size = 12 * c.handles;
    factored_ = false;
    kept_.clear();
    coarseFactorsKept_ = 0;
    ++uploads_;
  }

  // The anchored fine vertices (one flag per vertex, executor memory; null: none), which the
  // coarse levels leave out: U's rows of an anchored vertex are zero, so that no coarse mode
  // moves what the anchors hold (with them in, a coarse correction moved anchored vertices at
  // the cost of their identity rows and CG needed 30-40 iterations per solve under a brush).
  // Set before refresh().
  void setFixed(const std::uint8_t* fixed) { fixed_ = fixed; }

  // A_{l+1} = U^T A_l U on every level from the fine matrix (9 doubles per block), the
  // smoothers' diagonal factors, the fragments' and pieces' operators, and (when asked) the
  // coarsest level's Cholesky. Returns nothing the host must wait for unless the Cholesky is
  // asked for. `preconditions`: the V-cycle only preconditions CG, so the fine smoother reads a
  // float copy of the fine blocks (smoothFine) and, in host memory, the coarsest level keeps
  // its last factorization while its matrix stays within kCoarseReuse of the one factored
  // (kept_coarse_factor.h).
  void refresh(const double* fine, bool coarseCholesky, bool preconditions = false);

  // The Galerkin product of refresh() on a device, a thread per entry of each coarse block (a
  // block's row of 12 on the levels below the first) instead of one per block, whose thread
  // would walk thousands of contributions with 144 sums in local memory. Each entry sums the same
  // terms in the same order as the block's thread (the same bits). Public only because nvcc refuses
  // extended lambdas in private member functions.
  void galerkinByEntries(int nnz, const int* start, const int* block, const int* row,
                         const int* finerColumns, bool first, const std::uint8_t* fixed,
                         const double* y, const double* toParent, const double* finer, double* out);

  // (kept_coarse_factor.h)
  static constexpr double kCoarseReuse = KeptCoarseFactor::kReuse;

  // Coarsest factorizations reused since the hierarchy was uploaded (for tests).
  long coarseFactorsKept() const { return coarseFactorsKept_; }
  // The coarsest matrix whose factorization is kept for the next refresh (empty: none), and its
  // adoption by a cycle that did not factor it: the next refresh factors it first, as the cycle
  // that saved it had, and then decides whether to keep it as that one would (a restored state
  // runs on to the same bits: StepBackend::carriedState).
  std::vector<double> keptCoarseMatrix() const {
    return factored_ ? kept_.matrix() : std::vector<double>{};
  }
  void adoptKeptCoarseMatrix(std::vector<double> blocks) { adopted_ = std::move(blocks); }

  // The solve's settings are the solver options (solver/model/solver_options.h): the cycle reads
  // fine_sweeps (before and after the coarse correction), the smoother, the coarse solver and
  // its iterations and the cycle count; PCG's tolerance is linear_solve.h's.
  using Settings = SolverOptions;
  // Jacobi where the options ask for it, and with `smoother: auto` on a device where the V-cycle
  // preconditions CG: a colour sweep there is a launch per colour, a Jacobi sweep one launch,
  // and CG takes the weaker smoother to the same tolerance. Without CG (the paper's one V-cycle)
  // the smoother is the solve, and Gauss-Seidel stays
  // (docs/notes/2026-12-04-gpu-second-run.md has the measurements).
  static bool jacobi(const Settings& s) {
    return s.smoother == Smoother::Jacobi ||
           (!Exec::kHostMemory && s.smoother == Smoother::Auto && s.pcgTolerance > 0.0);
  }
  static constexpr double kJacobiWeight = 0.66;

  // x <- x + V-cycles for A x = b (A: fine blocks, 9 doubles each). No host waits.
  void cycles(const double* a, const double* b, double* x, const Settings& s) {
    for (int c = 0; c < s.cycles; ++c) vcycle(a, 0, b, x, s);
  }
  using PcgResult = typename MultigridPcg<Exec>::Result;
  using PcgScalars = typename MultigridPcg<Exec>::Scalars;
  // CG on A x = b from x = 0, preconditioned by one V-cycle per iteration (multigrid_pcg.h).
  PcgResult pcg(const double* a, const double* b, double* x, const Settings& s, double tolerance,
                int maxIterations, double absoluteTarget = 0.0) {
    return pcg_.solve(*this, rows_, a, b, x, s, tolerance, maxIterations, absoluteTarget,
                      bakedKey(s));
  }
  // The same without its read: the result stays in pcgScalars() (MultigridPcg::launch).
  void pcgLaunch(const double* a, const double* b, double* x, const Settings& s, double tolerance,
                 int maxIterations, double absoluteTarget) {
    pcg_.launch(*this, rows_, a, b, x, s, tolerance, maxIterations, absoluteTarget, bakedKey(s));
  }
  const PcgScalars* pcgScalars() const { return pcg_.scalars(); }

  // Where a device's dense factorization of the coarsest level left its status (> 0: it
  // failed), while the host has not read it; null otherwise.
  const double* coarseFailure() const {
    return dense_.statusPending ? scalars_.data() + kFactorFailed : nullptr;
  }
  // The host read that status: where it failed, the coarsest level is solved by CG from now
  // on (until the next refresh), as where a host factorization fails. True on a failure.
  bool takeCoarseFailure(bool failed) {
    dense_.statusPending = false;
    if (failed) factored_ = false;
    return failed;
  }

  // What a V-cycle's launches bake in besides their arguments, for a device that replays them
  // (MultigridPcg's loop): the buffers (new with each upload), the host's choices (the coarsest
  // solve, the float smoother, fragments, pieces) and the settings the cycle reads.
  std::uint64_t bakedKey(const Settings& s) const {
    return LaunchKey()
        .mix(uploads_)
        .mix(factored_)
        .mix(smoother_.single())
        .mix(static_cast<std::uint64_t>(fragments_.fragments()))
        .mix(pieces_.active())
        .mixPointer(fixed_)
        .mixPointer(dense_.inverse.data())
        .mix(static_cast<std::uint64_t>(dense_.size))
        .mix(static_cast<std::uint64_t>(s.fineSweeps))
        .mix(static_cast<std::uint64_t>(s.coarseIterations))
        .mix(static_cast<std::uint64_t>(s.smoother))
        .mix(static_cast<std::uint64_t>(s.coarseSolver))
        .mixDouble(s.pcgTolerance)
        .value();
  }

  // The operator of coarse level l (1: the first coarse level) as a dense matrix, read back
  // from the executor after refresh(): for tests.
  Eigen::MatrixXd coarseMatrix(int l) const {
    const Level& d = levels_[l - 1];
    std::vector<double> blocks(144 * static_cast<size_t>(d.nnz));
    std::vector<int> rowStart(d.handles + 1), columns(d.nnz);
    ex_.download(d.blocks.data(), blocks.data(), blocks.size());
    ex_.download(d.rowStart.data(), rowStart.data(), rowStart.size());
    ex_.download(d.columns.data(), columns.data(), columns.size());
    Eigen::MatrixXd out = Eigen::MatrixXd::Zero(12 * d.handles, 12 * d.handles);
    for (int r = 0; r < d.handles; ++r)
      for (int k = rowStart[r]; k < rowStart[r + 1]; ++k)
        out.block<12, 12>(12 * r, 12 * columns[k]) =
            Eigen::Map<const Eigen::Matrix<double, 12, 12>>(blocks.data() + 144 * k);
    return out;
  }

  // One V-cycle from the given x (the preconditioner of PCG).
  void vcycle(const double* a, int l, const double* b, double* x, const Settings& s) {
    const int levels = static_cast<int>(levels_.size());
    if (l == levels) {
      solveCoarsest(b, x, s);
      return;
    }
    double* ax = l == 0 ? ax_.data() : levels_[l - 1].ax.data();
    if (l == 0) {
      smoothFine(a, b, x, s.fineSweeps, false, s);
      multiplySmoother(a, x, ax);
    } else {
      smoothCoarse(l, b, x, s.fineSweeps, false, s);
      multiplyCoarse(l - 1, x, ax);
    }
    Level& next = levels_[l];
    restrictResidual(l, b, ax, next.b.data());
    double* cx = next.x.data();
    ex_.forEach(12 * next.handles, [=] GALSCULPT_LAMBDA(int i) { cx[i] = 0.0; });
    vcycle(a, l + 1, next.b.data(), cx, s);
    prolongAdd(l, cx, x);
    if (l == 0) {
      if (fragments_.fragments() > 0)
        fragments_.correct(a, fineRowStart_.data(), fineColumns_.data(), b, x);
      smoothFine(a, b, x, s.fineSweeps, true, s);
    } else {
      smoothCoarse(l, b, x, s.fineSweeps, true, s);
    }
  }

  // y = A x on the fine level.
  void multiplyFine(const double* a, const double* x, double* y) {
    const int* rowStart = fineRowStart_.data();
    const int* columns = fineColumns_.data();
    ex_.forEach(rows_, [=] GALSCULPT_LAMBDA(int r) {
      double acc[3] = {0.0, 0.0, 0.0};
      for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) {
        double t[3];
        multiply3(a + 9 * k, x + 3 * columns[k], t);
        for (int i = 0; i < 3; ++i) acc[i] += t[i];
      }
      for (int i = 0; i < 3; ++i) y[3 * r + i] = acc[i];
    });
  }

  int numLevels() const { return static_cast<int>(levels_.size()); }

  // Everything below is public only because CUDA's extended lambdas cannot live in private
  // member functions; the data members stay private.
  struct Level {
    int rows = 0, handles = 0, nnz = 0;
    long refreshCost = 1, memberCost = 1, rowCost = 1;
    Buffer<int> parent;
    Buffer<double> y, toParent;
    Buffer<int> rowStart, columns, diagonal;
    Buffer<int> contribStart, contribBlock, contribRow;
    Buffer<int> memberStart, members;
    Buffer<std::uint8_t> empty;
    std::vector<int> colorStart;
    Buffer<int> colorRows;
    Buffer<double> blocks, diagonalFactor;
    Buffer<double> b, x, ax;  // the right-hand side, solution and product of this level's rows
  };
  enum Scalar { kRr, kPap, kRrNew, kStop, kDone, kBB, kBad, kFactorFailed, kScalars };

  // Gauss-Seidel order: colour by colour (backwards when reversed, for the symmetric cycle), the
  // rows of one colour at once (no two share a block). `update` gets each row's position in the
  // colour order (colorRows[position] is the row).
  template <typename RowUpdate>
  void forEachColour(const std::vector<int>& colorStart, bool reverse, const RowUpdate& update,
                     long cost = 1) {
    const int colors = static_cast<int>(colorStart.size()) - 1;
    for (int ci = 0; ci < colors; ++ci) {
      const int color = reverse ? colors - 1 - ci : ci;
      const int begin = colorStart[color];
      ex_.forEach(
          colorStart[color + 1] - begin, [=] GALSCULPT_LAMBDA(int j) { update(begin + j); }, cost);
    }
  }

  // The fine level's smoother walks the rows in colour order (a colour's sweep streams through
  // its own rows' blocks). With a single-precision refresh (PCG's preconditioner) it reads a copy
  // of the off-diagonal blocks rounded to float, which halves what every sweep reads (CG's
  // products and residuals stay in double); otherwise the fine blocks themselves, in the same
  // arithmetic as a plain Gauss-Seidel sweep (the paper's V-cycle, which is the whole solve).
  // `a` is the operator of the last refresh().
  void smoothFine(const double* a, const double* b, double* x, int sweeps, bool reverse,
                  const Settings& s);

  // y = A x with the smoother's operator (the V-cycle's residual): the float copy after a
  // single-precision refresh, the fine blocks otherwise.
  void multiplySmoother(const double* a, const double* x, double* y) {
    if (smoother_.single())
      smoother_.multiplySingle(a, x, y, fineColorRows_.data(), fineDiagonal_.data());
    else
      multiplyFine(a, x, y);
  }

  // Smoothing of the operator of levels_[l - 1] (the rows of vcycle level l).
  void smoothCoarse(int l, const double* b, double* x, int sweeps, bool reverse, const Settings& s);

  // y = C x with C the operator of levels_[li].
  void multiplyCoarse(int li, const double* x, double* y) {
    Level& d = levels_[li];
    const int* rowStart = d.rowStart.data();
    const int* columns = d.columns.data();
    const double* blocks = d.blocks.data();
    if constexpr (!Exec::kHostMemory) {
      // On a device a thread per row entry: a coarse level has tens of rows, and a thread per
      // row walked its blocks' 144 entries each serially. Each entry sums in the order the
      // row's thread does (the same bits).
      ex_.forEach(12 * d.handles, [=] GALSCULPT_LAMBDA(int e) {
        const int r = e / 12, i = e % 12;
        double acc = 0.0;
        for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) {
          const double* a = blocks + 144 * k + i;
          const double* xc = x + 12 * columns[k];
          for (int c = 0; c < 12; ++c) acc += a[12 * c] * xc[c];
        }
        y[e] = acc;
      });
      return;
    }
    ex_.forEach(
        d.handles,
        [=] GALSCULPT_LAMBDA(int r) {
          double acc[12] = {};
          for (int k = rowStart[r]; k < rowStart[r + 1]; ++k)
            addMultiply12(blocks + 144 * k, x + 12 * columns[k], acc);
          for (int i = 0; i < 12; ++i) y[12 * r + i] = acc[i];
        },
        d.rowCost);
  }

  // coarse = U_l^T (b - ax), one thread per handle over its aggregate's rows.
  void restrictResidual(int l, const double* b, const double* ax, double* coarse) {
    Level& d = levels_[l];
    const int* start = d.memberStart.data();
    const int* members = d.members.data();
    const double* y = d.y.data();
    const double* toParent = d.toParent.data();
    const bool first = l == 0;
    const std::uint8_t* fixed = fixed_;
    if constexpr (!Exec::kHostMemory) {
      // On a device a thread per coarse entry (a handle's aggregate is hundreds of rows), each
      // summing in the order of the handle's thread (the same bits).
      ex_.forEach(12 * d.handles, [=] GALSCULPT_LAMBDA(int e) {
        const int h = e / 12, c = e % 12;
        double acc = 0.0;
        for (int i = start[h]; i < start[h + 1]; ++i) {
          const int r = members[i];
          if (first) {
            if (fixed && fixed[r]) continue;
            const int m = c / 3, k = c % 3;
            acc += y[4 * r + m] * (b[3 * r + k] - ax[3 * r + k]);
          } else {
            const double* t = toParent + 144 * r + 12 * c;
            double sum = 0.0;
            for (int k = 0; k < 12; ++k) sum += t[k] * (b[12 * r + k] - ax[12 * r + k]);
            acc += sum;
          }
        }
        coarse[e] = acc;
      });
      return;
    }
    ex_.forEach(
        d.handles,
        [=] GALSCULPT_LAMBDA(int h) {
          double acc[12] = {};
          for (int i = start[h]; i < start[h + 1]; ++i) {
            const int r = members[i];
            if (first) {
              if (fixed && fixed[r]) continue;
              for (int m = 0; m < 4; ++m)
                for (int k = 0; k < 3; ++k)
                  acc[3 * m + k] += y[4 * r + m] * (b[3 * r + k] - ax[3 * r + k]);
            } else {
              double res[12];
              for (int k = 0; k < 12; ++k) res[k] = b[12 * r + k] - ax[12 * r + k];
              addMultiplyTransposed12(toParent + 144 * r, res, acc);
            }
          }
          for (int k = 0; k < 12; ++k) coarse[12 * h + k] = acc[k];
        },
        d.memberCost);
  }

  void prolongAdd(int l, const double* coarse, double* x) {
    Level& d = levels_[l];
    const int* parent = d.parent.data();
    const double* y = d.y.data();
    const double* toParent = d.toParent.data();
    if (l == 0) {
      const std::uint8_t* fixed = fixed_;
      ex_.forEach(d.rows, [=] GALSCULPT_LAMBDA(int v) {
        const int p = parent[v];
        if (p < 0 || (fixed && fixed[v])) return;
        for (int m = 0; m < 4; ++m)
          for (int k = 0; k < 3; ++k) x[3 * v + k] += y[4 * v + m] * coarse[12 * p + 3 * m + k];
      });
    } else {
      ex_.forEach(d.rows, [=] GALSCULPT_LAMBDA(int a) {
        addMultiply12(toParent + 144 * a, coarse + 12 * parent[a], x + 12 * a);
      });
    }
  }

  void solveCoarsest(const double* b, double* x, const Settings& s);

  // The coarse CG's start with two or more pieces: each piece's exact affine solution (its
  // 12x12 system), so that CG only corrects within pieces; r = b - A x. A start that is not
  // finite falls back to x = 0.
  void startFromPieces(const double* b, double* x) {
    const Level& c = levels_.back();
    const int n = 12 * c.handles;
    double* r = cgR_.data();
    double* ap = cgAp_.data();
    double* sc = scalars_.data();
    pieces_.solve(c.handles, b, x);
    multiplyCoarse(numLevels() - 1, x, ap);
    ex_.sum(
        n, [=] GALSCULPT_LAMBDA(int i) { return x[i] == x[i] && fabs(x[i]) < 1e300 ? 0.0 : 1.0; },
        sc + kBad);
    ex_.forEach(n, [=] GALSCULPT_LAMBDA(int i) {
      if (sc[kBad] > 0.0) {
        x[i] = 0.0;
        r[i] = b[i];
      } else {
        r[i] = b[i] - ap[i];
      }
    });
  }

  // Whether this coarse CG iteration runs: not stopped, residual above the stop, p^T A p > 0.
  GALSCULPT_HD static bool cgLive(const double* sc) {
    return sc[kDone] == 0.0 && sc[kRr] > sc[kStop] && sc[kPap] > 0.0;
  }

 private:
  void rememberFactored(const Level& c) {
    kept_.remember(factored_, c.blocks.data(), c.blocks.size(), c.diagonal.data(), c.handles);
  }

  Exec& ex_;
  const BlockPattern& finePattern_;
  int rows_ = 0;
  FineSmoother<Exec> smoother_;  // the fine level's operator in colour order
  typename Exec::template Mirror<int> fineRowStart_, fineColumns_, fineDiagonal_;
  const std::uint8_t* fixed_ = nullptr;  // anchored fine vertices (setFixed)
  std::vector<int> fineColorStart_;
  Buffer<int> fineColorRows_;
  std::vector<Level> levels_;
  Buffer<double> ax_, scalars_;
  MultigridPcg<Exec> pcg_;
  Buffer<double> cgR_, cgP_, cgAp_;
  PieceCoarseStart<Exec> pieces_;       // the coarsest level's start with two or more pieces
  FragmentCorrection<Exec> fragments_;  // the fine level's
  // A device's dense factorization of the coarsest level (size x size), the inverse it gives
  // (solveCoarsest's product), and whether the host has yet to read its status.
  struct DenseCoarsest {
    int size = 0;
    Buffer<double> factor, inverse;
    bool statusPending = false;
  } dense_;
  // The host's (coarse_cholesky.h).
  std::unique_ptr<CoarseCholesky> sparse_;
  bool factored_ = false;  // the last refresh factored the coarsest level
  // The coarsest matrix as last factored (host memory only).
  KeptCoarseFactor kept_;
  std::vector<double> adopted_;  // a saved kept matrix, factored at the next refresh
  long coarseFactorsKept_ = 0;
  std::uint64_t uploads_ = 0;  // (bakedKey)
};

}  // namespace galsculpt

#include "solver/multigrid/multigrid_refresh.h"  // (the refresh's definitions)
#include "solver/multigrid/multigrid_smooth.h"   // (the smoothers' and the coarsest solve's)
