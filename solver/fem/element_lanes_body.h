// The body of element_lanes.h's kernel, compiled once per instruction set: the including file
// defines GALSCULPT_LANES_NAMESPACE (and its compiler flags). No include guard on purpose.
//
// Every expression mirrors element_kernels.h's scalar code operation by operation (same
// operands, same order), so each lane rounds exactly as the scalar kernel does (the material
// models are not mirrored: their one source, templated on the number type, is instantiated here
// with this file's lane type); branches become
// per-lane selections, loops that stop early run until every lane has stopped (each lane
// keeping its values from where it stopped), and the scalar code's turn to its accurate SVD
// becomes a lane handed back. Nothing here may call an inline function of another header: this
// file is compiled with instruction sets the rest of the program does not assume, and the linker
// could keep such a copy for everyone (templates instantiated with this file's own types, as the
// material models are, have internal linkage and are safe).
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

D determinant(const Mat& m) {
  return m(0, 0) * (m(1, 1) * m(2, 2) - m(2, 1) * m(1, 2)) -
         m(0, 1) * (m(1, 0) * m(2, 2) - m(2, 0) * m(1, 2)) +
         m(0, 2) * (m(1, 0) * m(2, 1) - m(2, 0) * m(1, 1));
}

D maxAbs(const Mat& m) {
  D s = all(0.0);
  for (const D& v : m.a) s = larger(s, absolute(v));
  return s;
}

void cross(const D x[3], const D y[3], D out[3]) {
  out[0] = x[1] * y[2] - x[2] * y[1];
  out[1] = x[2] * y[0] - x[0] * y[2];
  out[2] = x[0] * y[1] - x[1] * y[0];
}

bool any(Mask m) {
  for (int l = 0; l < kLanes; ++l)
    if (m[l]) return true;
  return false;
}

// closedFormSymmetricEigen: returns the lanes where it returns true.
Mask closedFormEigen(const Mat& a, D w[3], Mat& q) {
  const D shift = (a(0, 0) + a(1, 1) + a(2, 2)) / 3.0;
  Mat b = a;
  for (int i = 0; i < 3; ++i) b(i, i) -= shift;
  const D scale = maxAbs(b);
  const Mask multipleOfIdentity = scale == 0.0;
  Mask ok = scale > 0.0;
  const D divisor = select(ok, scale, all(1.0));
  for (D& x : b.a) x /= divisor;
  const D off = b(0, 1) * b(0, 1) + b(0, 2) * b(0, 2) + b(1, 2) * b(1, 2);
  const D p = (b(0, 0) * b(0, 0) + b(1, 1) * b(1, 1) + b(2, 2) * b(2, 2) + 2.0 * off) / 6.0;
  const D sq = root(p);
  const D half = determinant(b) / (2.0 * p * sq);
  D cosLargest, cosSmallest;
  for (int l = 0; l < kLanes; ++l) {
    const double phi = acos(fmin(1.0, fmax(-1.0, half[l]))) / 3.0;
    cosLargest[l] = cos(phi);
    cosSmallest[l] = cos(phi + 2.0943951023931954923);
  }
  D t[3];
  t[2] = 2.0 * sq * cosLargest;
  t[0] = 2.0 * sq * cosSmallest;
  t[1] = -t[0] - t[2];
  const Mask kIsLargest = (t[2] - t[1]) > (t[1] - t[0]);
  const D value = select(kIsLargest, t[2], t[0]);
  D vk[3] = {all(0.0), all(0.0), all(0.0)};
  {
    const D r[3][3] = {{b(0, 0) - value, b(0, 1), b(0, 2)},
                       {b(1, 0), b(1, 1) - value, b(1, 2)},
                       {b(2, 0), b(2, 1), b(2, 2) - value}};
    D best = all(0.0);
    for (int i = 0; i < 3; ++i) {
      D c[3];
      cross(r[i], r[(i + 1) % 3], c);
      const D n = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
      const Mask better = n > best;
      best = select(better, n, best);
      for (int j = 0; j < 3; ++j) vk[j] = select(better, c[j], vk[j]);
    }
    ok &= best > 0.0;
    const D inv = 1.0 / root(select(ok, best, all(1.0)));
    for (int j = 0; j < 3; ++j) vk[j] *= inv;
  }
  D v1[3] = {all(0.0), all(0.0), all(0.0)};
  {
    D best = all(0.0);
    for (int i = 0; i < 3; ++i) {
      const D r[3] = {b(i, 0) - (i == 0 ? t[1] : all(0.0)), b(i, 1) - (i == 1 ? t[1] : all(0.0)),
                      b(i, 2) - (i == 2 ? t[1] : all(0.0))};
      D c[3];
      cross(vk, r, c);
      const D n = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
      const Mask better = n > best;
      best = select(better, n, best);
      for (int j = 0; j < 3; ++j) v1[j] = select(better, c[j], v1[j]);
    }
    ok &= best > 1e-20;
    const D norm = root(select(ok, best, all(1.0)));
    for (D& x : v1) x /= norm;
  }
  D other[3];
  cross(vk, v1, other);
  for (int r = 0; r < 3; ++r) {
    q(r, 0) = select(kIsLargest, other[r], vk[r]);
    q(r, 1) = v1[r];
    q(r, 2) = select(kIsLargest, vk[r], other[r]);
  }
  const Mask flip = determinant(q) < 0.0;
  for (int r = 0; r < 3; ++r) {
    q(r, 0) = select(flip & kIsLargest, -q(r, 0), q(r, 0));
    q(r, 2) = select(flip & ~kIsLargest, -q(r, 2), q(r, 2));
  }
  for (int i = 0; i < 3; ++i) w[i] = t[i] * scale + shift;
  const D tolerance = 1e-11 * larger(maxAbs(a), all(1e-300));
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) {
      const D value =
          q(r, 0) * w[0] * q(c, 0) + q(r, 1) * w[1] * q(c, 1) + q(r, 2) * w[2] * q(c, 2);
      ok &= absolute(value - a(r, c)) <= tolerance;
    }
  // The scalar code's early exit for a multiple of the identity.
  for (int i = 0; i < 3; ++i) w[i] = select(multipleOfIdentity, shift, w[i]);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      q(r, c) = select(multipleOfIdentity, all(r == c ? 1.0 : 0.0), q(r, c));
  return ok | multipleOfIdentity;
}

// symmetricEigen (cyclic Jacobi) in the lanes of `active`: each lane rotates exactly as the
// scalar loop would and stops where it breaks.
void jacobiEigen(const Mat& input, D w[3], Mat& q, Mask active) {
  D a[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a[r][c] = 0.5 * (input(r, c) + input(c, r));
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) q(r, c) = all(r == c ? 1.0 : 0.0);
  Mask running = active;
  for (int sweep = 0; sweep < 32; ++sweep) {
    const D off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const D diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    running &= (off > 1e-34 * diag) & (off > 1e-300);
    if (!any(running)) break;
    for (int pair = 0; pair < 3; ++pair) {
      const int p = pair == 2 ? 1 : 0, k = pair == 0 ? 1 : 2;
      const D apk = a[p][k];
      const Mask rotate = running & (apk != 0.0);
      const D theta = (a[k][k] - a[p][p]) / (2.0 * select(rotate, apk, all(1.0)));
      const D tNear =
          select(theta >= 0.0, all(1.0), all(-1.0)) / (absolute(theta) + root(theta * theta + 1.0));
      const D t = select(absolute(theta) > 1e150, 0.5 / theta, tNear);
      const D c = 1.0 / root(t * t + 1.0), s = t * c;
      for (int i = 0; i < 3; ++i) {  // A <- A J
        const D aip = a[i][p], aik = a[i][k];
        a[i][p] = select(rotate, c * aip - s * aik, aip);
        a[i][k] = select(rotate, s * aip + c * aik, aik);
      }
      for (int i = 0; i < 3; ++i) {  // A <- J^T A
        const D api = a[p][i], aki = a[k][i];
        a[p][i] = select(rotate, c * api - s * aki, api);
        a[k][i] = select(rotate, s * api + c * aki, aki);
      }
      for (int i = 0; i < 3; ++i) {  // Q <- Q J
        const D qip = q(i, p), qik = q(i, k);
        q(i, p) = select(rotate, c * qip - s * qik, qip);
        q(i, k) = select(rotate, s * qip + c * qik, qik);
      }
    }
  }
  for (int i = 0; i < 3; ++i) w[i] = a[i][i];
}

// fastSymmetricEigen: the closed form where accurate, Jacobi in the other lanes of `inUse`.
void fastEigen(const Mat& a, D w[3], Mat& q, Mask inUse) {
  const Mask jacobi = ~closedFormEigen(a, w, q) & inUse;
  if (!any(jacobi)) return;
  D wj[3];
  Mat qj;
  jacobiEigen(a, wj, qj, jacobi);
  for (int i = 0; i < 3; ++i) w[i] = select(jacobi, wj[i], w[i]);
  for (int i = 0; i < 9; ++i) q.a[i] = select(jacobi, qj.a[i], q.a[i]);
}

// rotationVariantSvd where its first attempt (fastSymmetricEigen of F^T F) reproduces F.
void svd(const Mat& f, Mat& u, D s[3], Mat& v, Mask& ok) {
  Mat normal;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      normal(r, c) = f(0, r) * f(0, c) + f(1, r) * f(1, c) + f(2, r) * f(2, c);
  D w[3];
  Mat q;
  fastEigen(normal, w, q, ok);
  // Descending eigenvalues: the scalar code's selection sort as compare-exchanges.
  const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (const auto& pair : pairs) {
    const int i = pair[0], j = pair[1];
    const Mask swap = w[j] > w[i];
    const D wi = w[i];
    w[i] = select(swap, w[j], wi);
    w[j] = select(swap, wi, w[j]);
    for (int r = 0; r < 3; ++r) {
      const D qi = q(r, i);
      q(r, i) = select(swap, q(r, j), qi);
      q(r, j) = select(swap, qi, q(r, j));
    }
  }
  v = q;
  const Mask reflect = determinant(v) < 0.0;
  for (int r = 0; r < 3; ++r) v(r, 2) = select(reflect, -v(r, 2), v(r, 2));
  Mat b;  // columns s_i u_i
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) b(r, c) = f(r, 0) * v(0, c) + f(r, 1) * v(1, c) + f(r, 2) * v(2, c);
  const D scale = larger(maxAbs(f), all(1e-300));
  const D n0 = root(b(0, 0) * b(0, 0) + b(1, 0) * b(1, 0) + b(2, 0) * b(2, 0));
  ok &= n0 > 1e-14 * scale;
  const D n0Safe = select(ok, n0, all(1.0));
  D u0[3];
  for (int r = 0; r < 3; ++r) u0[r] = b(r, 0) / n0Safe;
  const D proj = u0[0] * b(0, 1) + u0[1] * b(1, 1) + u0[2] * b(2, 1);
  D u1[3] = {b(0, 1) - proj * u0[0], b(1, 1) - proj * u0[1], b(2, 1) - proj * u0[2]};
  const D n1 = root(u1[0] * u1[0] + u1[1] * u1[1] + u1[2] * u1[2]);
  ok &= n1 > 1e-14 * scale;
  const D n1Safe = select(ok, n1, all(1.0));
  for (D& x : u1) x /= n1Safe;
  D u2[3];
  cross(u0, u1, u2);
  for (int r = 0; r < 3; ++r) {
    u(r, 0) = u0[r];
    u(r, 1) = u1[r];
    u(r, 2) = u2[r];
  }
  for (int i = 0; i < 3; ++i) s[i] = u(0, i) * b(0, i) + u(1, i) * b(1, i) + u(2, i) * b(2, i);
  D dropped = all(0.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (i != j)
        dropped =
            larger(dropped, absolute(u(0, i) * b(0, j) + u(1, i) * b(1, j) + u(2, i) * b(2, j)));
  ok &= dropped / scale < 1e-11;
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

struct Energy {
  D energy;
  D gradient[3];
  Mat hessian;
};

// The number type D's operations the material models ask for (material_table.h): a type of this
// file's own, so that every model is instantiated here for these lanes alone.
struct LaneMath {
  static D all(double x) { return D{x, x, x, x}; }
  static D log(D x) {
    D out;
    for (int l = 0; l < kLanes; ++l) out[l] = ::log(x[l]);
    return out;
  }
};

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

// u diag(d) v^T.
Mat scaledProduct(const Mat& u, const D d[3], const Mat& v) {
  Mat m;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      m(r, c) = u(r, 0) * d[0] * v(c, 0) + u(r, 1) * d[1] * v(c, 1) + u(r, 2) * d[2] * v(c, 2);
  return m;
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
  // deformationGradient.
  Mat ds, f;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) ds(r, c) = x[3 * (c + 1) + r] - x[r];
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      f(r, c) =
          ds(r, 0) * dmInverse(0, c) + ds(r, 1) * dmInverse(1, c) + ds(r, 2) * dmInverse(2, c);
  // Lanes with a NaN, an infinity or a huge entry go to the scalar kernel (the selections
  // below assume ordered, finite numbers).
  for (const D& v : f.a) ok &= absolute(v) < 1e100;
  // shapeGradients.
  D c[4][3];
  for (int j = 0; j < 3; ++j) {
    c[0][j] = all(0.0);
    for (int a = 1; a < 4; ++a) {
      c[a][j] = dmInverse.a[(a - 1) + 3 * j];
      c[0][j] -= c[a][j];
    }
  }
  Mat u, v;
  D s[3];
  svd(f, u, s, v, ok);
  double yield[kLanes];
  for (int l = 0; l < kLanes; ++l) yield[l] = in.yield[l < in.count ? l : 0];
  const Energy e = singularValueEnergy(model, lame, s, yield);
  const Mat p = scaledProduct(u, e.gradient, v);
  const D energy = volume * e.energy;
  D gradient[12];
  for (int a = 0; a < 4; ++a)
    for (int r = 0; r < 3; ++r)
      gradient[3 * a + r] = volume * (p(r, 0) * c[a][0] + p(r, 1) * c[a][1] + p(r, 2) * c[a][2]);
  if (!in.stiffness) return writeEnergyAndForce(in.count, ok, energy, gradient, out);
  // forEachStressMode with the projection, its nine modes first collected: mode m's 12-vector
  // w and its scaled copy (volume lambda) w. A clamped mode (lambda 0) adds zeros, which leave
  // each sum's bits as the scalar kernel's skip does (a sum that starts at +0 is never -0).
  constexpr int kModes = 9;
  D modeW[kModes][12], modeScaledW[kModes][12];
  int modes = 0;
  auto visit = [&](D lambda, const Mat& q) {
    lambda = larger(lambda, all(0.0));
    D* w = modeW[modes];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i)
        w[3 * a + i] = q(i, 0) * c[a][0] + q(i, 1) * c[a][1] + q(i, 2) * c[a][2];
    const D scale = volume * lambda;
    for (int col = 0; col < 12; ++col) modeScaledW[modes][col] = scale * w[col];
    ++modes;
  };
  {
    D w[3];
    Mat q;
    fastEigen(e.hessian, w, q, ok);
    for (int m = 0; m < 3; ++m) {
      const D d[3] = {q(0, m), q(1, m), q(2, m)};
      visit(w[m], scaledProduct(u, d, v));
    }
  }
  const double invSqrt2 = 0.70710678118654752440;
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      Mat twist, flip;
      for (int col = 0; col < 3; ++col) {
        for (int r = 0; r < 3; ++r) {
          const D a = u(r, i) * v(col, j) * invSqrt2, b = u(r, j) * v(col, i) * invSqrt2;
          twist(r, col) = a - b;
          flip(r, col) = a + b;
        }
      }
      const D gi = e.gradient[i], gj = e.gradient[j];
      // safeQuotient.
      const D sumDen = s[i] + s[j], diffDen = s[i] - s[j];
      visit(select(absolute(sumDen) < 1e-8, e.hessian(i, i) + e.hessian(i, j), (gi + gj) / sumDen),
            twist);
      visit(
          select(absolute(diffDen) < 1e-8, e.hessian(i, i) - e.hessian(i, j), (gi - gj) / diffDen),
          flip);
    }
  }
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
