// Newton iterations where the residual is (StepSettings::localNewton). A brush moves a small part
// of a body: after a sub-step's first Newton iteration the residual left is the flow and the
// springs under the brush, while the rest of the body is already within a small share of the
// tolerance. The next iteration then solves only in the region that holds the residual: the
// vertices outside it are held still (their rows and columns of the Newton system take the held
// vertices' form; region_solve.h solves the region's rows), and only the elements that touch the
// region are evaluated; every other element keeps its energy, gradient and stiffness, which are
// exact because none of its corners moves. The residual checked after the iteration is still the
// whole body's (every vertex's, from every element's gradient at the accepted positions): the
// rest of the body is checked, not solved again, and a region chosen too small only costs
// another iteration.
//
// The region: the fewest vertices, by their |g_v|^2 in powers of two, outside which the residual
// is at most kOutsideShare of the tolerance (so that the region's own solve, to half the
// tolerance, leaves the body within it), grown by kRings rings of neighbours, where the step's
// effect on the residual fades. A region of more than kMostShare of the free vertices is no
// saving: the iteration solves the whole body.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "solver/fem/dense_kernels.h"
#include "solver/frame/frame_data.h"

namespace galsculpt {

template <typename Exec>
class LocalRegion {
 public:
  static constexpr double kOutsideShare = 0.5;
  static constexpr int kRings = 2;
  static constexpr double kMostShare = 0.5;

  LocalRegion(Exec& ex, FrameData<Exec>& data) : ex_(ex), d_(data), host_(data.n) {}

  // Chooses the next iteration's region from g at the accepted positions, `target` the
  // residual the sub-step must reach (absolute, N). True when the region is small enough to be
  // solved alone (its masks are then in FrameData: regionVertex, regionElement, regionFixed,
  // regionTouched). One host read, the region's size.
  bool choose(double target) {
    const int n = d_.n;
    double* r2 = d_.vertexResidual.data();
    FrameScalars* sc = d_.sc();
    const double outside = kOutsideShare * kOutsideShare * target * target;
    squaredResiduals(d_.g.data());
    if constexpr (Exec::kHostMemory) {
      ex_.download(r2, host_.data(), static_cast<size_t>(n));
      const double seedAbove = threshold(outside);
      if (!(seedAbove >= 0.0)) return false;  // a NaN or infinity: the whole body
      ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) { sc->regionSeed = seedAbove; });
    } else {
      ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) { sc->regionOutside = outside; });
      seedOnDevice(n, r2);  // (a NaN or infinity seeds nothing: the whole body)
    }
    launchMasks();
    FrameScalars read;
    ex_.read(sc, &read, 1);
    return decide(read);
  }

  // choose()'s launches without its read, on a device, from `g` (3n) and the seeds' `outside`
  // already in the frame's scalars (regionOutside): a line-search trial forms the region its
  // positions would give, and its size rides the trial's read (decide). The accepted positions
  // are the last trial's, and g there its gradient, so the region is choose()'s.
  void launchChoice(const double* g) {
    squaredResiduals(g);
    seedOnDevice(d_.n, d_.vertexResidual.data());
    launchMasks();
  }

  // The region's size from a read that holds it (choose()'s, or the accepted trial's after
  // launchChoice): true, with the elements' mask launched, when it is small enough.
  bool decide(const FrameScalars& read) {
    vertices_ = static_cast<int>(read.regionVertices);
    if (!(read.regionVertices <= kMostShare * read.freeVertices) || vertices_ == 0) return false;
    const int* tv = d_.tetVertices.data();
    const std::uint8_t* region = d_.regionVertex.data();
    std::uint8_t* element = d_.regionElement.data();
    ex_.forEach(d_.tets, [=] GALSCULPT_LAMBDA(int t) {
      element[t] =
          region[tv[4 * t]] | region[tv[4 * t + 1]] | region[tv[4 * t + 2]] | region[tv[4 * t + 3]];
    });
    return true;
  }

  // |g_v|^2 per vertex. Public only because nvcc refuses extended lambdas in private member
  // functions (so are the two below).
  void squaredResiduals(const double* g) {
    double* r2 = d_.vertexResidual.data();
    ex_.forEach(d_.n, [=] GALSCULPT_LAMBDA(int v) {
      r2[v] = g[3 * v] * g[3 * v] + g[3 * v + 1] * g[3 * v + 1] + g[3 * v + 2] * g[3 * v + 2];
    });
  }

  // The seeds from the threshold in regionSeed, grown by kRings rings, the elements' corners,
  // the held vertices of the region's solve, and the sizes into the frame's scalars.
  void launchMasks() {
    const int n = d_.n;
    const double* r2 = d_.vertexResidual.data();
    const std::uint8_t* fixed = d_.fixed.data();
    FrameScalars* sc = d_.sc();
    std::uint8_t* in = d_.regionVertex.data();
    std::uint8_t* out = d_.regionScratch.data();
    ex_.forEach(n, [=] GALSCULPT_LAMBDA(int v) { in[v] = !fixed[v] && r2[v] >= sc->regionSeed; });
    for (int ring = 0; ring < kRings; ++ring) {
      grow(in, out, fixed);
      std::swap(in, out);
    }
    if (in != d_.regionVertex.data()) ex_.copy(d_.regionVertex.data(), in, n);
    const std::uint8_t* region = d_.regionVertex.data();
    grow(region, d_.regionTouched.data(), nullptr);  // its elements' corners, held ones too
    std::uint8_t* regionFixed = d_.regionFixed.data();
    ex_.forEach(n, [=] GALSCULPT_LAMBDA(int v) { regionFixed[v] = fixed[v] || !region[v]; });
    ex_.sum(
        n, [=] GALSCULPT_LAMBDA(int v) { return region[v] ? 1.0 : 0.0; }, &sc->regionVertices);
    ex_.sum(
        n, [=] GALSCULPT_LAMBDA(int v) { return fixed[v] ? 0.0 : 1.0; }, &sc->freeVertices);
  }

  // to[v] = whether v or a neighbour of v (a vertex of an element around it) is in `from`, and
  // v not `excluded` (null: none). Public only because nvcc refuses extended lambdas in private
  // member functions.
  void grow(const std::uint8_t* from, std::uint8_t* to, const std::uint8_t* excluded) {
    const int* rowStart = d_.rowStart.data();
    const int* columns = d_.columns.data();
    ex_.forEach(d_.n, [=] GALSCULPT_LAMBDA(int v) {
      bool near = from[v];
      for (int k = rowStart[v]; k < rowStart[v + 1] && !near; ++k) near = from[columns[k]];
      to[v] = near && !(excluded && excluded[v]);
    });
  }

  // The last region's vertex count.
  int vertices() const { return vertices_; }

  // The seeds' threshold found where the residuals are (a device): each bin's sum by a thread
  // of its own, over the vertices in their order (the host's sums, to the bit), then the scan by
  // one thread into regionSeed (infinity where a |g_v|^2 is not finite: no seeds), below which
  // the sum left is at most regionOutside. No host wait.
  // Public only because nvcc refuses extended lambdas in private member functions.
  void seedOnDevice(int n, const double* r2) {
    if (bins_.size() != static_cast<size_t>(kBins)) bins_.resize(kBins);
    double* bins = bins_.data();
    FrameScalars* sc = d_.sc();
    ex_.forEach(kBins, [=] GALSCULPT_LAMBDA(int b) {
      double sum = 0.0;
      for (int v = 0; v < n; ++v) {
        const double r = r2[v];
        if (r > 0.0 && finite(r) && binOf(r) == b) sum += r;
      }
      bins[b] = sum;
    });
    ex_.maximum(
        n, [=] GALSCULPT_LAMBDA(int v) { return finite(r2[v]) ? 0.0 : 1.0; }, &sc->regionBad);
    ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) {
      sc->regionSeed = sc->regionBad > 0.0 ? INFINITY : seedFromBins(bins, sc->regionOutside);
    });
  }

  // Neither a NaN nor an infinity (in the frame's device lambdas' form).
  GALSCULPT_HD static bool finite(double r) { return r == r && fabs(r) <= 1.7976931348623157e308; }
  // frexp's exponents of doubles, and subnormals: |g_v|^2 binned by its binary exponent.
  static constexpr int kBins = 2200, kOffset = 1100;
  // The bin of r > 0 (finite): r in [2^(e-1), 2^e).
  GALSCULPT_HD static int binOf(double r) {
    int e = 0;
    frexp(r, &e);
    const int b = e + kOffset;
    return b < 0 ? 0 : (b > kBins - 1 ? kBins - 1 : b);
  }
  // The smallest power of two at or above which the binned |g_v|^2 must be seeds so that those
  // below it add up to at most `outside` (infinity when they all do).
  GALSCULPT_HD static double seedFromBins(const double* bins, double outside) {
    double below = 0.0;
    for (int b = 0; b < kBins; ++b) {
      if (below + bins[b] > outside) return ldexp(1.0, b - kOffset - 1);
      below += bins[b];
    }
    return INFINITY;  // everything is within `outside`
  }

 private:
  // The threshold of seedFromBins over the vertices' |g_v|^2 (host_), -1 for a NaN or an
  // infinity. Binned by exponent: the sum left outside is within a factor of two of the largest
  // allowed, and the pass is linear in the vertices.
  double threshold(double outside) const {
    std::array<double, kBins> bins{};
    for (double r : host_) {
      if (!std::isfinite(r)) return -1.0;
      if (!(r > 0.0)) continue;
      bins[binOf(r)] += r;
    }
    return seedFromBins(bins.data(), outside);
  }

  Exec& ex_;
  FrameData<Exec>& d_;
  std::vector<double> host_;
  typename Exec::template Buffer<double> bins_;  // a device's (seedOnDevice)
  int vertices_ = 0;
};

}  // namespace galsculpt
