// The body of element_lanes.h's kernel, compiled once per instruction set: the including file
// defines GALSCULPT_LANES_NAMESPACE (and its compiler flags). No include guard on purpose.
//
// The material models and the eigen-solves and SVD are not written here: their one source,
// templated on the number type (solver/fem/materials/, eigen_svd.h), is instantiated with this
// file's lane type and its LaneMath. What is still written here mirrors element_kernels.h's
// scalar code operation by operation (same operands, same order), so that each lane rounds
// exactly as the scalar kernel does: the deformation gradient, the stress modes and the
// stiffness's sums. Branches become per-lane selections, and the scalar code's turn to its
// accurate SVD becomes a lane handed back. Nothing here may call an inline function of another
// header: this file is compiled with instruction sets the rest of the program does not assume,
// and the linker could keep such a copy for everyone (templates instantiated with this file's
// own types, as the material models and eigen_svd.h's are, have internal linkage and are safe).
#include <cmath>
#include <cstring>

#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace galsculpt::kernels::GALSCULPT_LANES_NAMESPACE {
namespace {

typedef double D __attribute__((vector_size(32)));
typedef long long Bits __attribute__((vector_size(32)));
using Mask = decltype(D{} < D{});

inline D all(double x) {
  return D{x, x, x, x};
}

inline D root(D x) {
#if defined(__AVX__)
  return _mm256_sqrt_pd(x);
#else
  return D{__builtin_sqrt(x[0]), __builtin_sqrt(x[1]), __builtin_sqrt(x[2]), __builtin_sqrt(x[3])};
#endif
}

// |x| by clearing the sign bit, as fabs does.
inline D absolute(D x) {
  return (D)((Bits)x & 0x7fffffffffffffffLL);
}
// fmax and fmin for operands that are not NaN (a lane with a NaN is handed back).
inline D larger(D x, D y) {
  return x > y ? x : y;
}
inline D select(Mask m, D x, D y) {
  return m ? x : y;
}

struct Mat {
  D a[9];  // column-major
  D& operator()(int r, int c) { return a[r + 3 * c]; }
  const D& operator()(int r, int c) const { return a[r + 3 * c]; }
};

// The number type D's operations: what the material models (material_table.h) and the
// eigen-solves and SVD (eigen_svd.h) ask for. A type of this file's own, so that every model and
// eigen_svd.h's templates are instantiated here for these lanes alone. Its comparisons assume
// ordered, finite numbers: a lane with a NaN or an infinity is handed back to the scalar kernel.
struct LaneMath {
  using Mask = decltype(D{} < D{});
  static D all(double x) { return D{x, x, x, x}; }
  static D log(D x) {
    return eachLane(x, [](double v) { return ::log(v); });
  }
  static D sqrt(D x) { return root(x); }
  static D abs(D x) { return absolute(x); }
  static D max(D x, D y) { return larger(x, y); }
  static D clampedAcos(D x) {
    return eachLane(x, [](double v) { return ::acos(::fmin(1.0, ::fmax(-1.0, v))); });
  }
  static D cos(D x) {
    return eachLane(x, [](double v) { return ::cos(v); });
  }
  static D select(Mask m, D x, D y) { return m ? x : y; }
  static bool any(Mask m) {
    for (int l = 0; l < kLanes; ++l)
      if (m[l]) return true;
    return false;
  }
  static Mask invert(Mask m) { return ~m; }

 private:
  template <typename F>
  static D eachLane(D x, F f) {
    D out;
    for (int l = 0; l < kLanes; ++l) out[l] = f(x[l]);
    return out;
  }
};

// rotationVariantSvd where its first attempt (the closed-form eigen-solve of F^T F, Jacobi where
// that is not accurate) reproduces F; the other lanes leave `ok` (the scalar kernel's turn to its
// accurate SVD becomes a lane handed back).
void svd(const Mat& f, Mat& u, D s[3], Mat& v, Mask& ok) {
  D w[3];
  Mat q;
  fastEigenOf<LaneMath>(normalMatrixOf(f), w, q, ok);
  Mask regular;
  const D dropped = svdFromEigenOf<LaneMath>(f, w, q, u, s, v, regular);
  ok &= regular;
  ok &= dropped < 1e-11;
}

// Entries [0, count) of the lane vectors `from` to each written lane's own array (`to[l]`),
// four entries at a time through a 4x4 transpose.
void writeTransposed(const D* from, int count, double* const to[kLanes], int lanes, unsigned skip) {
  const Bits even = {0, 4, 2, 6}, odd = {1, 5, 3, 7}, low = {0, 1, 4, 5}, high = {2, 3, 6, 7};
  for (int i = 0; i < count; i += kLanes) {
    const D t0 = __builtin_shuffle(from[i], from[i + 1], even);
    const D t1 = __builtin_shuffle(from[i], from[i + 1], odd);
    const D t2 = __builtin_shuffle(from[i + 2], from[i + 3], even);
    const D t3 = __builtin_shuffle(from[i + 2], from[i + 3], odd);
    const D byLane[kLanes] = {__builtin_shuffle(t0, t2, low), __builtin_shuffle(t1, t3, low),
                              __builtin_shuffle(t0, t2, high), __builtin_shuffle(t1, t3, high)};
    const bool whole = count - i >= kLanes;  // else the last two entries (90 = 22 x 4 + 2)
    for (int l = 0; l < lanes; ++l) {
      if (skip >> l & 1u) continue;
      if (whole)
        std::memcpy(to[l] + i, &byLane[l], sizeof(D));
      else
        std::memcpy(to[l] + i, &byLane[l], sizeof(D) / 2);
    }
  }
}

using Energy = SingularValueEnergyOf<D, Mat>;

// singularValueEnergy: the same model source as the scalar kernel, in lanes. A model whose
// energy depends on the element's own state (kLaneByLane: its yield stress, `yield`, one per
// lane) is evaluated one lane at a time; the SVD and the stiffness around it stay in lanes.
Energy singularValueEnergy(MaterialModel model, const Lame& lame, const D s[3],
                           const double yield[kLanes]) {
  Energy out;
  D hessian[3][3];
  withMaterial(model, [&](auto m) {
    using Model = decltype(m);
    if constexpr (requires { Model::kLaneByLane; }) {
      for (int l = 0; l < kLanes; ++l) {
        Lame laneLame = lame;
        laneLame.yield = yield[l];
        const double laneS[3] = {s[0][l], s[1][l], s[2][l]};
        double energy, gradient[3], laneHessian[3][3];
        Model::template singularValues<double, ScalarMath>(laneLame, laneS, energy, gradient,
                                                           laneHessian);
        out.energy[l] = energy;
        for (int i = 0; i < 3; ++i) {
          out.gradient[i][l] = gradient[i];
          for (int j = 0; j < 3; ++j) hessian[i][j][l] = laneHessian[i][j];
        }
      }
    } else {
      Model::template singularValues<D, LaneMath>(lame, s, out.energy, out.gradient, hessian);
    }
  });
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.hessian(i, j) = hessian[i][j];
  return out;
}

// The upper triangle (row <= col) of the 12x12 stiffness, column by column.
constexpr int upperIndex(int row, int col) {
  return col * (col + 1) / 2 + row;
}

// Entry i of the packed stiffness (element_lanes.h) as an upper-triangle index: block (a, c),
// a <= c, column-major, its lower half mirrored.
struct PackedFromUpper {
  int index[90];
  constexpr PackedFromUpper() : index{} {
    for (int a = 0; a < 4; ++a)
      for (int c = a; c < 4; ++c)
        for (int j = 0; j < 3; ++j)
          for (int r = 0; r < 3; ++r) {
            const int row = 3 * a + r, col = 3 * c + j;
            index[9 * (4 * a - a * (a - 1) / 2 + (c - a)) + r + 3 * j] =
                row <= col ? upperIndex(row, col) : upperIndex(col, row);
          }
  }
  constexpr int operator[](int i) const { return index[i]; }
};
constexpr PackedFromUpper kPackedFromUpper;

// Each lane's energy and force (`count` lanes in use); returns the lanes handed back: those
// whose results are not finite (the scalar kernel's to report) or that `ok` leaves out.
unsigned writeEnergyAndForce(int count, Mask ok, const D& energy, const D gradient[12],
                             const LaneOutputs& out) {
  ok &= absolute(energy) < 1e300;
  unsigned handedBack = 0;
  for (int l = 0; l < count; ++l) {
    if (!ok[l]) {
      handedBack |= 1u << l;
      continue;
    }
    *out.energy[l] = energy[l];
  }
  // Lanes to elements: four entries of the four lanes at a time, transposed.
  writeTransposed(gradient, 12, out.gradient, count, handedBack);
  return handedBack;
}

}  // namespace

unsigned evaluateIntactLanes(MaterialModel model, const Lame& lame, const LaneInputs& in,
                             const LaneOutputs& out) {
  // Unused lanes repeat lane 0, so that every lane computes on sensible numbers.
  Mat dmInverse;
  D volume, x[12];
  Mask ok = all(0.0) == 0.0;
  for (int l = 0; l < kLanes; ++l) {
    const int from = l < in.count ? l : 0;
    const RestData& r = *in.rest[from];
    for (int i = 0; i < 9; ++i) dmInverse.a[i][l] = r.dmInverse[i];
    volume[l] = r.volume;
    for (int i = 0; i < 12; ++i) x[i][l] = in.x[from][i];
  }
  const Mat f = deformationGradientOf(dmInverse, x);
  // Lanes with a NaN, an infinity or a huge entry go to the scalar kernel (the selections
  // below assume ordered, finite numbers).
  for (const D& v : f.a) ok &= absolute(v) < 1e100;
  D c[4][3];
  shapeGradientsOf<LaneMath>(dmInverse, c);
  Mat u, v;
  D s[3];
  svd(f, u, s, v, ok);
  double yield[kLanes];
  for (int l = 0; l < kLanes; ++l) yield[l] = in.yield[l < in.count ? l : 0];
  const Energy e = singularValueEnergy(model, lame, s, yield);
  const Mat p = scaledProductOf(u, e.gradient, v);
  const D energy = volume * e.energy;
  D gradient[12];
  elementForceOf(volume, p, c, gradient);
  if (!in.stiffness) return writeEnergyAndForce(in.count, ok, energy, gradient, out);
  // forEachStressMode with the projection, its nine modes first collected: mode m's 12-vector
  // w and its scaled copy (volume lambda) w. A clamped mode (lambda 0) adds zeros, which leave
  // each sum's bits as the scalar kernel's skip does (a sum that starts at +0 is never -0).
  constexpr int kModes = 9;
  D modeW[kModes][12], modeScaledW[kModes][12];
  int modes = 0;
  forEachStressModeOf<LaneMath>(u, s, v, e, ok, [&](D lambda, const Mat& q) {
    lambda = larger(lambda, all(0.0));
    D* w = modeW[modes];
    modeVectorOf(q, c, w);
    const D scale = volume * lambda;
    for (int col = 0; col < 12; ++col) modeScaledW[modes][col] = scale * w[col];
    ++modes;
  });
  // The scalar kernel's sums, entry by entry over the modes in its order (each sum kept in a
  // register instead of passing the 78 of them through memory once per mode).
  D hessian[78];
  for (int col = 0; col < 12; ++col) {
    D sums[12];
    for (int row = 0; row <= col; ++row) sums[row] = all(0.0);
    for (int m = 0; m < kModes; ++m) {
      const D wc = modeScaledW[m][col];
      for (int row = 0; row <= col; ++row) sums[row] += wc * modeW[m][row];
    }
    for (int row = 0; row <= col; ++row) hessian[upperIndex(row, col)] = sums[row];
  }
  D packed[92];
  for (int i = 0; i < 90; ++i) packed[i] = hessian[kPackedFromUpper[i]];
  packed[90] = packed[91] = all(0.0);
  const unsigned handedBack = writeEnergyAndForce(in.count, ok, energy, gradient, out);
  writeTransposed(packed, 90, out.packedHessian, in.count, handedBack);
  return handedBack;
}

}  // namespace galsculpt::kernels::GALSCULPT_LANES_NAMESPACE
