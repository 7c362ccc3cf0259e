// Where Newton starts for a piece that nothing holds: its predicted path with its acceleration.
//
// The predicted start x_n + h v_n (StepSettings::predictedStart) is the path of a body with no
// force on it. A body cut into pieces is mostly pieces that gravity pulls and their neighbours
// push: a piece cut off a hanging sphere falls, the sphere itself hangs still. Each piece that no
// anchor, removed debris or collider holds, and that presses on no held piece (HeldPieces),
// starts instead from
//     x_n + h s (v_n + h a),   a = g + F / m,   s = 1 / (1 + h alpha),
// with m the piece's mass and F the net elastic force its neighbours exert on it at x_n (the
// sum of its corners' forces in the elements it shares with other pieces: within a piece the
// elastic forces cancel). a is its centre of mass's acceleration at x_n, the same for all its
// vertices, so that a falling piece's prediction is backward Euler's exact answer for its
// centre of mass (with mass damping alpha; the elastic forces do not move it), a piece resting
// on another (F = -m g) keeps the straight line, and pieces falling together in a cluster start
// together (gravity only on pieces nothing pushes would move them apart). A push larger than
// kMostPush times the piece's weight (a hard contact, whose force the step changes most) keeps the
// straight line. Only the start changes, not the equations (with stiffness damping K(x_0) too, but
// only in the elements between pieces: the start moves each piece rigidly).
//
// A free piece is not started rigidly turned (by h omega): the straight line already turns a
// spinning piece by atan(h omega) and only stretches it, a linear correction, where a turned
// start leaves Newton a rotation to find (the measurements and the variants tried are in
// docs/notes/2026-12-02-pieces-start-their-acceleration.md).
//
// A piece is a set of vertices joined by undamaged edges (as for debris, debris.h). Pieces are
// found on the host when the damage changes; per sub-step one launch marks held vertices, one
// marks held pieces (then rounds spread them), one evaluates the elements between pieces at x_n
// that touch a piece not held (between held pieces nothing reads them), and one moves the small
// pieces (a thread each, a serial loop over its vertices and corners); a large piece (the body
// itself, a big chunk) is summed by reductions and moved by a launch over its vertices, so that no
// GPU thread walks a whole body. Either way the sums are the same for any thread count.
//
// The elements between pieces are evaluated only where the frame no longer has their gradients
// at x_n: x_n is the last sub-step's accepted trial, whose element pass left every element's
// gradient behind, and unless something changed since (damage, positions, rest shapes, removed
// debris: FrameSolver::gradientAtX_) those are copied instead, the same bits (on the host
// executor; FrameSolver::startPiecesAccelerated says why not on the GPU).
#pragma once

#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "solver/fem/collider_kernels.h"
#include "solver/fem/dense_kernels.h"
#include "solver/fem/element_kernels.h"
#include "solver/fem/launch_key.h"
#include "solver/fracture/debris.h"
#include "solver/frame/element_pass.h"
#include "solver/model/sim_model.h"

namespace galsculpt {

// The pieces (CSR over their vertices) and the elements between them: an element with corners
// in two or more pieces is the only way one piece pushes on another (a crack face closing), so
// a piece's net elastic force is the sum of its corners' forces in those elements.
struct PieceLayout {
  std::vector<int> pieceStart{0}, pieceVertices;
  std::vector<int> pieceOf;                         // (nVerts)
  std::vector<int> sharedTets;                      // elements with corners in two or more pieces
  std::vector<int> couplingStart{0}, couplingSlot;  // per piece: 12 i + 3 corner into sharedTets
  // Per piece, the damaged edges from its vertices to other pieces' (the piece's end first):
  // where its crack faces meet theirs.
  std::vector<int> crackStart{0}, crackEnds;  // crackEnds: 2 per edge
  std::vector<double> crackRestLengthSq;
  // Set by whoever keeps the layout, different for different pieces: what the device copies of
  // it (AcceleratedStart, PieceResidual) compare to know whether they are up to date. (Handed
  // beside the layout it was once read before the layout was brought up to date.)
  std::uint64_t revision = 0;
  int pieces() const { return static_cast<int>(pieceStart.size()) - 1; }
};

PieceLayout pieceLayout(const SimModel& model, const std::vector<std::uint8_t>& damaged,
                        std::uint64_t revision = 0);
// The same from the damage's census (censusPieces), where the caller has it already.
PieceLayout pieceLayout(const SimModel& model, const PieceCensus& census,
                        const std::vector<std::uint8_t>& damaged, std::uint64_t revision);

// A piece whose neighbours push on it with more than this many times its weight (at 1 g at
// least) keeps the straight-line start: a hard contact.
inline constexpr double kMostPush = 2.0;

// A piece is held when one of its vertices is (operator(): one thread walks the piece), or when
// it presses on a held piece (spread: one round; rounds run until nothing changes): a damaged
// edge between them is shorter than at rest at x_n, a crack face closed on the other. A piece
// lodged in the body that holds it keeps the straight line with it, while pieces falling
// together, pressing only on each other, start together. (A crack counted as touching when
// merely near closing would hold back pieces that are leaving.)
struct HeldPieces {
  const int *pieceStart, *pieceVertices, *pieceOf;
  const std::uint8_t* heldVertex;
  const std::uint8_t* removed;  // (nVerts) or null: removed debris, which holds up nothing
  const int *crackStart, *crackEnds;
  const double* crackRestLengthSq;
  const double* xn;

  GALSCULPT_HD std::uint8_t operator()(int p) const {
    for (int i = pieceStart[p]; i < pieceStart[p + 1]; ++i)
      if (heldVertex[pieceVertices[i]]) return 1;
    return 0;
  }
  GALSCULPT_HD std::uint8_t spread(int p, const std::uint8_t* held) const {
    return held[p] || pressesOnHeld(p, held, xn);
  }
  // Whether a crack edge from piece p to a held piece is pressed at positions y.
  GALSCULPT_HD bool pressesOnHeld(int p, const std::uint8_t* held, const double* y) const {
    for (int i = crackStart[p]; i < crackStart[p + 1]; ++i) {
      const int a = crackEnds[2 * i], b = crackEnds[2 * i + 1];
      if (held[pieceOf[b]] && !(removed && removed[b]) && pressing(y, a, b, crackRestLengthSq[i]))
        return true;
    }
    return false;
  }
  // Shorter than at rest past the strain at which a crack closes (kCrackClosingStrain: the
  // edge's Green strain below minus it): a crack face pressed on the other, not one still at
  // rest where the knife left it (there every such edge is a tie, and the GPU's fused
  // multiply-adds put an eighth of them a last bit short, holding every piece a cut sphere
  // drops).
  GALSCULPT_HD static bool pressing(const double* y, int a, int b, double restSq) {
    double lengthSq = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double d = y[3 * b + k] - y[3 * a + k];
      lengthSq += d * d;
    }
    return lengthSq < restSq * (1.0 - 2.0 * kernels::kCrackClosingStrain);
  }
};

// 1 where vertex v holds its piece: anchored or removed (`fixed`), or within reach of a
// collider in the sub-step.
struct HeldVertices {
  const std::uint8_t* fixed;
  const double *xn, *xhat, *vn;
  const kernels::ColliderPose* poses;
  int colliders;
  double fallPerStep;  // h^2 |g|
  double h;

  GALSCULPT_HD std::uint8_t operator()(int v) const {
    if (fixed[v]) return 1;
    const double* p0 = xn + 3 * v;
    const double* p1 = xhat + 3 * v;
    const double speed =
        sqrt(vn[3 * v] * vn[3 * v] + vn[3 * v + 1] * vn[3 * v + 1] + vn[3 * v + 2] * vn[3 * v + 2]);
    const double reach = fallPerStep + h * speed;
    for (int c = 0; c < colliders; ++c) {
      double normal[3];
      if (kernels::colliderDistance(poses[c], p0, normal) < reach ||
          kernels::colliderDistance(poses[c], p1, normal) < reach)
        return 1;
    }
    return 0;
  }
};

// Pieces of more vertices than this are summed by the executor's reductions, not one thread.
inline constexpr int kLargePiece = 2048;

// A piece's start (the header's formula): its acceleration from its mass and the sum of its
// corners' energy gradients in the elements it shares (false when the push is harder than
// kMostPush), and its vertices moved with it; operator() does all of it for piece p in one
// thread, unless the piece is held (HeldPieces). Writes x (3n).
struct AcceleratedPiece {
  const int *pieceStart, *pieceVertices;
  const std::uint8_t* heldPiece;
  const int *couplingStart, *couplingSlot;
  const double* sharedGradient;  // (12 sharedTets) elastic energy gradients at x_n
  const double *xn, *vn, *mass;
  double h, damping, gravity[3];
  double* x;

  GALSCULPT_HD bool acceleration(double m, const double grad[3], double a[3]) const {
    const double g = fmax(
        sqrt(gravity[0] * gravity[0] + gravity[1] * gravity[1] + gravity[2] * gravity[2]), 9.81);
    const double push = sqrt(grad[0] * grad[0] + grad[1] * grad[1] + grad[2] * grad[2]);
    if (!(m > 0.0) || !(push <= kMostPush * m * g)) return false;
    for (int k = 0; k < 3; ++k) a[k] = gravity[k] - grad[k] / m;
    return true;
  }

  GALSCULPT_HD void move(int v, const double a[3]) const {
    const double step = h / (1.0 + h * damping);
    for (int k = 0; k < 3; ++k) x[3 * v + k] = xn[3 * v + k] + step * (vn[3 * v + k] + h * a[k]);
  }

  GALSCULPT_HD void operator()(int p) const {
    if (heldPiece[p]) return;
    const int begin = pieceStart[p], end = pieceStart[p + 1];
    double m = 0.0;
    for (int i = begin; i < end; ++i) m += mass[pieceVertices[i]];
    double grad[3] = {0.0, 0.0, 0.0}, a[3];
    for (int i = couplingStart[p]; i < couplingStart[p + 1]; ++i)
      for (int k = 0; k < 3; ++k) grad[k] += sharedGradient[couplingSlot[i] + k];
    if (!acceleration(m, grad, a)) return;
    for (int i = begin; i < end; ++i) move(pieceVertices[i], a);
  }
};

// The elements between pieces at x_n (tets[i]) that a piece starting on its own reads: all but
// those whose four corners lie in held pieces.
struct SharedElements {
  const int* tets;
  const int* cornerPiece;  // (4 per element) each corner's piece
  const std::uint8_t* heldPiece;
  GALSCULPT_HD bool read(int i) const {
    const int* p = cornerPiece + 4 * i;
    return !(heldPiece[p[0]] && heldPiece[p[1]] && heldPiece[p[2]] && heldPiece[p[3]]);
  }
};

// out[12 i..] = the energy gradient at y of each element the frame's pieces read
// (shared.read(i), i < count), by the frame's element kernel (element_launches.h).
template <typename Exec>
void launchElementGradients(const Exec& ex, const ElementModel& element,
                            const SharedElements& shared, int count, const double* y, double* out);

// The accelerated start on an executor: the pieces' layout in its memory (rebuilt when the
// damage changes) and a sub-step's launches. Held vertices, held pieces (a thread per small
// piece, reductions for a large one) spread to those pressing on them round by round, then the
// elements between pieces at x_n that a free piece reads (`elementGradient(t, y, gradient12)`:
// the frame's element kernel), and the free pieces moved.
template <typename Exec>
class AcceleratedStart {
 public:
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;

  struct SubstepInputs {
    bool anyFixed;                // some vertex anchored or removed (known on the host)
    const std::uint8_t* fixed;    // (nVerts) anchored or removed
    const std::uint8_t* removed;  // (nVerts) removed debris (it pushes on nothing)
    const double *xn, *xhat, *vn, *mass;
    const kernels::ColliderPose* poses;
    int colliders;
    double h, damping, gravity[3];
  };

  // `gradientsAtXn`: every element's energy gradient at x_n (12 per element) where the frame
  // still has them from its last accepted trial, or null: the elements between pieces are then
  // evaluated with `elementGradient`, the same kernel, to the same bits: the frame's
  // ElementModel (launchElementGradients) or any `gradient(t, y, gradient12)` (the tests').
  // `layout`: the body's pieces (pieceLayout; the device copy is rebuilt when its revision
  // changes).
  template <typename Gradient>
  void start(const Exec& ex, const SimModel& model, const PieceLayout& layout,
             const SubstepInputs& in, const Gradient& elementGradient, const double* gradientsAtXn,
             double* x) {
    if (!built_ || builtRevision_ != layout.revision) rebuild(model, layout);
    if (pieceCount_ == 1 && in.anyFixed) return;  // a body in one piece, anchored: no launch
    const double g = sqrt(in.gravity[0] * in.gravity[0] + in.gravity[1] * in.gravity[1] +
                          in.gravity[2] * in.gravity[2]);
    const HeldVertices heldTest{in.fixed, in.xn,        in.xhat,         in.vn,
                                in.poses, in.colliders, in.h * in.h * g, in.h};
    std::uint8_t* held = held_.data();
    ex.forEach(static_cast<int>(held_.size()),
               [=] GALSCULPT_LAMBDA(int v) { held[v] = heldTest(v); });
    const double* xn = in.xn;
    const HeldPieces heldPieces{
        pieceStart_.data(), pieceVertices_.data(), pieceOf_.data(),           held, in.removed,
        crackStart_.data(), crackEnds_.data(),     crackRestLengthSq_.data(), xn};
    std::uint8_t* heldPiece = heldPiece_.data();
    const int* small = smallPieces_.data();
    ex.forEach(smallPieceCount_,
               [=] GALSCULPT_LAMBDA(int i) { heldPiece[small[i]] = heldPieces(small[i]); });
    const int* vertices = pieceVertices_.data();
    const int* slots = couplingSlot_.data();
    const double* mass = in.mass;
    double* sums = largeSums_.data();
    for (size_t j = 0; j < large_.size(); ++j) {
      const LargePiece& lp = large_[j];
      const int begin = lp.begin, p = lp.piece;
      double* out = sums + 5 * j;
      ex.sum(
          lp.end - begin,
          [=] GALSCULPT_LAMBDA(int i) { return held[vertices[begin + i]] ? 1.0 : 0.0; }, out);
      ex.forEach(1, [=] GALSCULPT_LAMBDA(int) { heldPiece[p] = out[0] > 0.0 ? 1 : 0; });
      ex.sum(
          lp.end - begin, [=] GALSCULPT_LAMBDA(int i) { return mass[vertices[begin + i]]; },
          out + 1);
    }
    spreadHeld(ex, heldPieces, in.xn, nullptr, nullptr);
    // The elements between pieces at x_n (how hard each piece's neighbours push on it), where a
    // corner is in a piece that starts on its own: only such a piece reads them.
    const SharedElements shared{sharedTets_.data(), sharedCornerPieces_.data(), heldPiece};
    double* sharedGradient = sharedGradient_.data();
    if (gradientsAtXn)
      ex.forEach(sharedTetCount_, [=] GALSCULPT_LAMBDA(int i) {
        if (!shared.read(i)) return;
        for (int j = 0; j < 12; ++j)
          sharedGradient[12 * i + j] = gradientsAtXn[12 * shared.tets[i] + j];
      });
    else if constexpr (std::is_same_v<Gradient, ElementModel>)
      launchElementGradients(ex, elementGradient, shared, sharedTetCount_, xn, sharedGradient);
    else
      ex.forEach(sharedTetCount_, [=] GALSCULPT_LAMBDA(int i) {
        if (shared.read(i)) elementGradient(shared.tets[i], xn, sharedGradient + 12 * i);
      });
    for (size_t j = 0; j < large_.size(); ++j) {
      const int cBegin = large_[j].couplingBegin;
      double* out = sums + 5 * j;
      for (int k = 0; k < 3; ++k)
        ex.sum(
            large_[j].couplingEnd - cBegin,
            [=] GALSCULPT_LAMBDA(int i) { return sharedGradient[slots[cBegin + i] + k]; },
            out + 2 + k);
    }
    const AcceleratedPiece piece{pieceStart_.data(),
                                 vertices,
                                 heldPiece,
                                 couplingStart_.data(),
                                 slots,
                                 sharedGradient,
                                 xn,
                                 in.vn,
                                 mass,
                                 in.h,
                                 in.damping,
                                 {in.gravity[0], in.gravity[1], in.gravity[2]},
                                 x};
    ex.forEach(smallPieceCount_, [=] GALSCULPT_LAMBDA(int i) { piece(small[i]); });
    moveLarge(ex, piece);
    spreadHeld(ex, heldPieces, x, in.xhat, x);
  }

  // The large pieces moved by their sums: each launch over a piece's vertices forms the piece's
  // acceleration from the sums where they lie (no read). Public only because nvcc refuses
  // extended lambdas in private member functions.
  void moveLarge(const Exec& ex, const AcceleratedPiece& piece) {
    if (large_.empty()) return;
    const int* vertices = pieceVertices_.data();
    std::uint8_t* heldPiece = heldPiece_.data();
    double* sums = largeSums_.data();
    for (size_t j = 0; j < large_.size(); ++j) {  // held, after the spread
      double* out = sums + 5 * j;
      const int p = large_[j].piece;
      ex.forEach(1, [=] GALSCULPT_LAMBDA(int) { out[0] = heldPiece[p]; });
    }
    for (size_t j = 0; j < large_.size(); ++j) {
      const double* r = sums + 5 * j;
      const int begin = large_[j].begin;
      ex.forEach(large_[j].end - begin, [=] GALSCULPT_LAMBDA(int i) {
        double a[3];
        if (r[0] > 0.0 || !piece.acceleration(r[1], r + 2, a)) return;
        piece.move(vertices[begin + i], a);
      });
    }
  }

  // Rounds until no piece changes (a loop whose test the device makes): a piece with a crack
  // pressed, at positions y,
  // against a held piece is held. Before the pieces move, y is x_n (HeldPieces::spread). After
  // they have, y is their starts and `straight` is given: a free piece whose start presses on a
  // held piece (its predicted fall drives it into a piece that stays) goes back to the straight
  // line there and counts as held, and a piece put back may now be pressed by another. Without
  // that a slice lying against a clamped bar started a fall's worth (h^2 g) into the bar's face:
  // Newton found the contact in 25 iterations where the straight line took 7. Public only
  // because nvcc refuses extended lambdas in private member functions.
  void spreadHeld(const Exec& ex, const HeldPieces& heldPieces, const double* y,
                  const double* straight, double* x) {
    if (sharedTetCount_ == 0) return;
    std::uint8_t* heldPiece = heldPiece_.data();
    std::uint8_t* next = heldPieceNext_.data();
    double* changed = largeSums_.data() + 5 * large_.size();
    const int* pieceStart = pieceStart_.data();
    const int* vertices = pieceVertices_.data();
    const int pieces = pieceCount_;
    // A round after the last change changes nothing: each piece's put-back and the copy apply
    // only where next differs from heldPiece.
    ex.forEach(1, [=] GALSCULPT_LAMBDA(int) { *changed = 1.0; });
    const std::uint64_t key = LaunchKey()
                                  .mixBytes(heldPieces)
                                  .mix(static_cast<std::uint64_t>(pieces))
                                  .mixPointer(heldPiece)
                                  .mixPointer(next)
                                  .mixPointer(changed)
                                  .mixPointer(pieceStart)
                                  .mixPointer(vertices)
                                  .mixPointer(y)
                                  .mixPointer(straight)
                                  .mixPointer(x)
                                  .value();
    ex.loopOnDevice(key, changed, kSpreadRounds, [&] {
      ex.forEach(pieces, [=] GALSCULPT_LAMBDA(int p) {
        next[p] = heldPiece[p] || heldPieces.pressesOnHeld(p, heldPiece, y) ? 1 : 0;
      });
      ex.sum(
          pieces, [=] GALSCULPT_LAMBDA(int p) { return next[p] != heldPiece[p] ? 1.0 : 0.0; },
          changed);
      if (straight)
        ex.forEach(pieces, [=] GALSCULPT_LAMBDA(int p) {
          if (next[p] == heldPiece[p]) return;
          for (int i = pieceStart[p]; i < pieceStart[p + 1]; ++i)
            for (int k = 0; k < 3; ++k) x[3 * vertices[i] + k] = straight[3 * vertices[i] + k];
        });
      ex.copy(heldPiece, next, static_cast<size_t>(pieces));
    });
  }

 private:
  struct LargePiece {
    int piece, begin, end, couplingBegin, couplingEnd;  // ranges in pieceVertices_, couplingSlot_
  };
  static constexpr int kSpreadRounds = 16;  // then the rest counts as free

  void rebuild(const SimModel& model, const PieceLayout& layout) {
    builtRevision_ = layout.revision;
    built_ = true;
    std::vector<int> small;
    large_.clear();
    for (int p = 0; p < layout.pieces(); ++p) {
      if (layout.pieceStart[p + 1] - layout.pieceStart[p] > kLargePiece)
        large_.push_back({p, layout.pieceStart[p], layout.pieceStart[p + 1],
                          layout.couplingStart[p], layout.couplingStart[p + 1]});
      else
        small.push_back(p);
    }
    pieceCount_ = layout.pieces();
    smallPieceCount_ = static_cast<int>(small.size());
    sharedTetCount_ = static_cast<int>(layout.sharedTets.size());
    smallPieces_.upload(small);
    pieceStart_.upload(layout.pieceStart);
    pieceVertices_.upload(layout.pieceVertices);
    pieceOf_.upload(layout.pieceOf);
    sharedTets_.upload(layout.sharedTets);
    std::vector<int> cornerPieces(4 * layout.sharedTets.size());
    for (size_t i = 0; i < layout.sharedTets.size(); ++i)
      for (int c = 0; c < 4; ++c)
        cornerPieces[4 * i + c] = layout.pieceOf[model.mesh.tets[layout.sharedTets[i]][c]];
    sharedCornerPieces_.upload(cornerPieces);
    couplingStart_.upload(layout.couplingStart);
    couplingSlot_.upload(layout.couplingSlot);
    crackStart_.upload(layout.crackStart);
    crackEnds_.upload(layout.crackEnds);
    crackRestLengthSq_.upload(layout.crackRestLengthSq);
    held_.resize(model.numVertices());
    sharedGradient_.resize(12 * static_cast<size_t>(sharedTetCount_));
    heldPiece_.resize(pieceCount_);
    heldPieceNext_.resize(pieceCount_);
    largeSums_.resize(5 * large_.size() + 1);
  }

  bool built_ = false;
  std::uint64_t builtRevision_ = 0;  // of the pieces the layout is for
  std::vector<LargePiece> large_;
  int pieceCount_ = 0, smallPieceCount_ = 0, sharedTetCount_ = 0;
  Buffer<int> pieceStart_, pieceVertices_, pieceOf_, sharedTets_, couplingStart_, couplingSlot_,
      smallPieces_, crackStart_, crackEnds_;
  Buffer<int> sharedCornerPieces_;  // (4 sharedTets) the piece of each corner
  Buffer<double> sharedGradient_, largeSums_, crackRestLengthSq_;
  Buffer<std::uint8_t> held_, heldPiece_, heldPieceNext_;
};

}  // namespace galsculpt
