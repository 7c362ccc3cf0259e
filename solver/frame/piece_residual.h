// The residual piece by piece: how well each piece of a broken body solves its own equations.
//
// A sub-step converges when the body's backward-Euler residual |g| (free DOFs) is within the
// tolerance of its force scale (FrameSolver::relativeResidual): one 2-norm over every vertex.
// A body in one piece is judged fairly by it. A body in many is not: the norm adds the pieces'
// residuals in squares, so a piece holding a small share of the vertices may keep a residual many
// times its own weight while the body's stays within the tolerance (measured after many cuts:
// docs/notes/2026-12-03-residual-piece-piece.md).
//
// This measures it: for each piece of more than kMeasuredPieceVertices vertices (the size below
// which the issue's own targets stop counting pieces), |g_p| / max(|W_p|, |f_p|) over its free
// vertices, with W_p its weight (at 1 g at least, as for the body) and f_p the elastic and
// contact forces on it, and the largest of them. The frame reports it beside its residual
// (StepReport::pieceResidual), and with StepSettings::convergePieces (the scenes' default)
// solves for it: a sub-step has converged when it too is within the tolerance
// (FrameSolver::piecesWithinTolerance).
//
// A piece's vertices are summed in chunks of kChunk (a thread each) and a piece's chunks by one
// thread, in a fixed order: the same sums for any thread count, on either executor, and no GPU
// thread walks a whole body. The layout is rebuilt on the host when the damage changes, from
// the pieces the frame finds once for this and the pieces' start (accelerated_start.h). The
// largest is read back: one more host read a sub-step (and, with convergePieces, one per Newton
// iteration that finds the body converged or its step null), only for a body in two or more
// measured pieces (on the CPU within the bench's noise after 100 cuts).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "solver/fem/dense_kernels.h"
#include "solver/frame/accelerated_start.h"

namespace galsculpt {

// Pieces of more vertices than this are measured.
inline constexpr int kMeasuredPieceVertices = 10;

// The measured pieces' vertices (CSR) and their chunks, from the damage (host).
struct PieceResidualLayout {
  std::vector<int> vertices;            // the measured pieces' vertices, piece after piece
  std::vector<int> chunkBegin{0};       // (chunks + 1) ranges in `vertices`
  std::vector<int> pieceChunkStart{0};  // (pieces + 1) ranges of chunks
  int pieces() const { return static_cast<int>(pieceChunkStart.size()) - 1; }
  int chunks() const { return static_cast<int>(chunkBegin.size()) - 1; }
};

PieceResidualLayout pieceResidualLayout(const PieceLayout& pieces, int chunk);

template <typename Exec>
class PieceResidual {
 public:
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;
  static constexpr int kChunk = 512;

  // Whether measure() reads anything for these pieces (two or more measured): where not, the
  // body's residual is the answer and g and f are not read.
  bool measures(const PieceLayout& pieces) {
    if (!built_ || builtRevision_ != pieces.revision) rebuild(pieces);
    return pieces_ >= 2;
  }

  // The largest relative residual over the measured pieces, or -1 when the body has fewer than
  // two of them (then the body's residual says it all). `pieces`: the body's pieces
  // (pieceLayout; the device copy is rebuilt when its revision changes); `g`: the backward-Euler
  // gradient, `f`: the elastic and contact forces (3n each); `gravity`: |g| in m/s^2.
  double measure(const Exec& ex, const PieceLayout& pieces, const double* g, const double* f,
                 const std::uint8_t* fixed, const double* mass, double gravity) {
    if (!launch(ex, pieces, g, f, fixed, mass, gravity)) return -1.0;
    double worst = 0.0;
    ex.read(result_.data(), &worst, 1);
    return worst;
  }
  // measure()'s launches without its read: the largest ratio is then at result(), for a read
  // the caller makes with others (the sub-step's end). False where no piece is measured.
  bool launch(const Exec& ex, const PieceLayout& pieces, const double* g, const double* f,
              const std::uint8_t* fixed, const double* mass, double gravity) {
    if (!built_ || builtRevision_ != pieces.revision) rebuild(pieces);
    if (pieces_ < 2) return false;
    const int* vertices = vertices_.data();
    const int* chunkBegin = chunkBegin_.data();
    double* chunkSums = chunkSums_.data();
    ex.forEach(chunks_, [=] GALSCULPT_LAMBDA(int c) {
      double gg = 0.0, ff = 0.0, mm = 0.0;
      for (int i = chunkBegin[c]; i < chunkBegin[c + 1]; ++i) {
        const int v = vertices[i];
        if (fixed[v]) continue;
        for (int k = 0; k < 3; ++k) {
          gg += g[3 * v + k] * g[3 * v + k];
          ff += f[3 * v + k] * f[3 * v + k];
        }
        mm += mass[v] * mass[v];
      }
      chunkSums[3 * c] = gg;
      chunkSums[3 * c + 1] = ff;
      chunkSums[3 * c + 2] = mm;
    });
    const int* pieceChunkStart = pieceChunkStart_.data();
    double* ratio = ratio_.data();
    const double weightG = fmax(gravity, 9.81);
    ex.forEach(pieces_, [=] GALSCULPT_LAMBDA(int p) {
      double gg = 0.0, ff = 0.0, mm = 0.0;
      for (int c = pieceChunkStart[p]; c < pieceChunkStart[p + 1]; ++c) {
        gg += chunkSums[3 * c];
        ff += chunkSums[3 * c + 1];
        mm += chunkSums[3 * c + 2];
      }
      const double scale = fmax(weightG * sqrt(mm), sqrt(ff));
      ratio[p] = scale > 0.0 ? sqrt(gg) / scale : 0.0;  // (all anchored: nothing to solve)
    });
    ex.maximum(
        pieces_, [=] GALSCULPT_LAMBDA(int p) { return ratio[p]; }, result_.data());
    return true;
  }
  const double* result() const { return result_.data(); }

 private:
  void rebuild(const PieceLayout& pieces) {
    builtRevision_ = pieces.revision;
    built_ = true;
    const PieceResidualLayout layout = pieceResidualLayout(pieces, kChunk);
    pieces_ = layout.pieces();
    chunks_ = layout.chunks();
    vertices_.upload(layout.vertices);
    chunkBegin_.upload(layout.chunkBegin);
    pieceChunkStart_.upload(layout.pieceChunkStart);
    chunkSums_.resize(3 * static_cast<size_t>(chunks_));
    ratio_.resize(static_cast<size_t>(pieces_));
    result_.resize(1);
  }

  bool built_ = false;
  std::uint64_t builtRevision_ = 0;  // of the pieces the layout is for
  int pieces_ = 0, chunks_ = 0;
  Buffer<int> vertices_, chunkBegin_, pieceChunkStart_;
  Buffer<double> chunkSums_, ratio_, result_;
};

}  // namespace galsculpt
