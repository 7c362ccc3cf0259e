// The damaged elements' lanes of element_lanes.h: element_kernels.h's evaluateEdgeStrainElement
// (strains, crackedStrainState without the two-pieces case, the force and the projected
// stiffness, packed) four elements at a time. Included after element_lanes_body.h, in the same
// namespace, by each build's file. No include guard on purpose.
//
// What every element computes alike runs in the lanes: the edge strains, the strain-space
// stiffness K, and from the opening problem's answer the force and the 12x12 stiffness. Each
// expression mirrors the scalar code operation by operation, so each lane rounds exactly as the
// scalar kernel does; an edge force of zero, which the scalar code skips, leaves a lane's sums
// as they were. The opening problem itself (which cracks open: a pivoting that branches on every
// flip) is solved element by element by the scalar kernel's own function (openCracks). Measured
// alone the lanes are only a little faster than the scalar kernel (0.30 against 0.32 µs an
// element); in the frame, together with the unrolled eliminations and the zero stiffnesses not
// written, the element phase of the settled 100-cut sphere fell by a tenth (docs/benchmarks.md).

namespace galsculpt::kernels::GALSCULPT_LANES_NAMESPACE {
namespace {

// kTetEdges, the edges at each vertex and their signs (element_kernels.h), as local tables.
constexpr int kEdgeEnds[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
constexpr int kEdgesAtVertex[4][3] = {{0, 1, 2}, {0, 3, 4}, {1, 3, 5}, {2, 4, 5}};
constexpr double kEdgeSignAt[4][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {1, 1, 1}};

}  // namespace

unsigned evaluateCrackedLanes(const Lame& lame, const CrackedLaneInputs& in,
                              const LaneOutputs& out) {
  // Unused lanes repeat lane 0, so that every lane computes on sensible numbers.
  D volume, restLengthSq[6], s[36], x[12];
  std::uint8_t damaged[kLanes], oneWay[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    const int from = l < in.count ? l : 0;
    const RestData& r = *in.rest[from];
    volume[l] = r.volume;
    for (int e = 0; e < 6; ++e) restLengthSq[e][l] = r.restLengthSq[e];
    for (int i = 0; i < 36; ++i) s[i][l] = r.strainFromEdges[i];
    for (int i = 0; i < 12; ++i) x[i][l] = in.x[from][i];
    damaged[l] = static_cast<std::uint8_t>(~in.intact[from] & kIntact);
    oneWay[l] = in.resists[from] ? damaged[l] : 0;
  }
  // edgeGreenStrains. Lanes with a NaN, an infinity or a huge edge go to the scalar kernel.
  D d[6][3], eps[6];
  Mask ok = all(0.0) == 0.0;
  for (int e = 0; e < 6; ++e) {
    const int a = kEdgeEnds[e][0], b = kEdgeEnds[e][1];
    D len2 = all(0.0);
    for (int k = 0; k < 3; ++k) {
      d[e][k] = x[3 * b + k] - x[3 * a + k];
      len2 += d[e][k] * d[e][k];
      ok &= absolute(d[e][k]) < 1e100;
    }
    eps[e] = (len2 - restLengthSq[e]) / (2.0 * restLengthSq[e]);
  }
  // crackedStrainState: the unloaded lanes (every edge damaged, none pressed shorter where
  // cracks resist closing; all open).
  Mask unloaded = all(0.0) != all(0.0);
  std::uint8_t opened[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    bool none = in.intact[l < in.count ? l : 0] == 0;
    for (int e = 0; e < 6 && none; ++e)
      none = !((oneWay[l] >> e) & 1) || eps[e][l] + kCrackClosingStrain >= 0.0;
    if (none) unloaded[l] = ~unloaded[l];
    opened[l] = damaged[l];
  }
  // edgeStrainStiffness.
  D k[6][6];
  {
    D a[6];
    for (int c = 0; c < 6; ++c) a[c] = s[6 * c] + s[1 + 6 * c] + s[2 + 6 * c];
    const double normal = 2.0 * lame.mu, shear = 4.0 * lame.mu;
    for (int r = 0; r < 6; ++r) {
      const D* sr = s + 6 * r;
      for (int c = r; c < 6; ++c) {
        const D* sc = s + 6 * c;
        const D sum = normal * (sr[0] * sc[0] + sr[1] * sc[1] + sr[2] * sc[2]) +
                      shear * (sr[3] * sc[3] + sr[4] * sc[4] + sr[5] * sc[5]) +
                      lame.lambda * a[r] * a[c];
        k[r][c] = k[c][r] = sum;
      }
    }
  }
  // addOpenedCrackEnergy, element by element: the pivoting over each element's own set of open
  // cracks branches on every flip, which lanes would pay for all four. It is the scalar
  // kernel's own code (openCracks, compiled with the program's flags), so its bits are.
  D tau[6], stateEnergy, stiff[6][6];
  for (int l = 0; l < kLanes; ++l) {
    CrackedStrainState state;
    state.energy = 0.0;
    for (int r = 0; r < 6; ++r) {
      state.tau[r] = state.z[r] = 0.0;
      for (int c = 0; c < 6; ++c) state.stiffness[r][c] = 0.0;
    }
    if (!unloaded[l] && l < in.count) {
      double kl[6][6], epsl[6];
      for (int r = 0; r < 6; ++r) {
        epsl[r] = eps[r][l];
        for (int c = 0; c < 6; ++c) kl[r][c] = k[r][c][l];
      }
      openCracks(kl, epsl, static_cast<std::uint8_t>(damaged[l] & ~oneWay[l]), oneWay[l],
                 lame.crackWidth, true, state);
      opened[l] = state.opened;
    }
    for (int r = 0; r < 6; ++r) {
      tau[r][l] = state.tau[r];
      for (int c = 0; c < 6; ++c) stiff[r][c][l] = state.stiffness[r][c];
    }
    stateEnergy[l] = state.energy;
  }
  // evaluateEdgeStrainElement.
  const D energy = volume * stateEnergy;
  D g[6][3];
  for (int e = 0; e < 6; ++e)
    for (int k3 = 0; k3 < 3; ++k3) g[e][k3] = d[e][k3] / restLengthSq[e];
  D gradient[12];
  for (D& v : gradient) v = all(0.0);
  for (int e = 0; e < 6; ++e) {
    const Mask loaded = tau[e] != 0.0;
    const int a = kEdgeEnds[e][0], bv = kEdgeEnds[e][1];
    for (int k3 = 0; k3 < 3; ++k3) {
      gradient[3 * bv + k3] =
          select(loaded, gradient[3 * bv + k3] + volume * tau[e] * g[e][k3], gradient[3 * bv + k3]);
      gradient[3 * a + k3] =
          select(loaded, gradient[3 * a + k3] - volume * tau[e] * g[e][k3], gradient[3 * a + k3]);
    }
  }
  D packed[92];
  {
    // edgeStrainHessian, the blocks on and above the diagonal only (what is packed).
    D u[4][6][3];
    for (int a = 0; a < 4; ++a)
      for (int f = 0; f < 6; ++f)
        for (int r = 0; r < 3; ++r) {
          D sum = all(0.0);
          for (int i = 0; i < 3; ++i) {
            const int e = kEdgesAtVertex[a][i];
            sum += kEdgeSignAt[a][i] * stiff[e][f] * g[e][r];
          }
          u[a][f][r] = volume * sum;
        }
    // Block (a, c): each entry's sum over the three edges at c in the scalar code's order (a
    // sign of -1 multiplies exactly). The scalar code writes each block and its mirror, so a
    // diagonal block's entry below its diagonal is the sum at its upper-triangle position.
    for (int a = 0; a < 4; ++a)
      for (int cv = a; cv < 4; ++cv) {
        D sum[3][3];
        for (int r = 0; r < 3; ++r)
          for (int col = 0; col < 3; ++col) sum[r][col] = all(0.0);
        for (int i = 0; i < 3; ++i) {
          const int f = kEdgesAtVertex[cv][i];
          for (int r = 0; r < 3; ++r)
            for (int col = 0; col < 3; ++col) {
              const D term = u[a][f][r] * g[f][col];
              sum[r][col] = kEdgeSignAt[cv][i] > 0.0 ? sum[r][col] + term : sum[r][col] - term;
            }
        }
        D* blk = packed + 9 * (4 * a - a * (a - 1) / 2 + (cv - a));
        for (int col = 0; col < 3; ++col)
          for (int r = 0; r < 3; ++r)
            blk[r + 3 * col] = cv == a && r > col ? sum[col][r] : sum[r][col];
      }
    // The edges' own curvature, where the edge force pulls.
    for (int e = 0; e < 6; ++e) {
      D t = tau[e] / restLengthSq[e];
      t = select(t > 0.0, t, all(0.0));
      const Mask pulls = t != 0.0;
      const D block = volume * t;
      const int a = kEdgeEnds[e][0], bv = kEdgeEnds[e][1];
      D* aa = packed + 9 * (4 * a - a * (a - 1) / 2);
      D* bb = packed + 9 * (4 * bv - bv * (bv - 1) / 2);
      D* ab = packed + 9 * (4 * a - a * (a - 1) / 2 + (bv - a));
      for (int k3 = 0; k3 < 3; ++k3) {
        aa[4 * k3] = select(pulls, aa[4 * k3] + block, aa[4 * k3]);
        bb[4 * k3] = select(pulls, bb[4 * k3] + block, bb[4 * k3]);
        ab[4 * k3] = select(pulls, ab[4 * k3] - block, ab[4 * k3]);
      }
    }
    packed[90] = packed[91] = all(0.0);
  }
  // The unloaded lanes carry nothing, exactly.
  const D energyOut = select(unloaded, all(0.0), energy);
  for (D& v : gradient) v = select(unloaded, all(0.0), v);
  for (D& v : packed) v = select(unloaded, all(0.0), v);
  // A lane whose results are not finite is the scalar kernel's to report.
  ok &= absolute(energy) < 1e300;
  for (const D& v : gradient) ok &= absolute(v) < 1e300;
  unsigned handedBack = 0, zeroStiffness = 0;
  for (int l = 0; l < in.count; ++l) {
    if (!ok[l]) {
      handedBack |= 1u << l;
      continue;
    }
    *out.energy[l] = energyOut[l];
    *out.opened[l] = unloaded[l] ? damaged[l] : opened[l];
    if (*out.opened[l] == kIntact) zeroStiffness |= 1u << l;  // no intact edge either
  }
  writeTransposed(gradient, 12, out.gradient, in.count, handedBack);
  writeTransposed(packed, 90, out.packedHessian, in.count, handedBack | zeroStiffness);
  return handedBack;
}

}  // namespace galsculpt::kernels::GALSCULPT_LANES_NAMESPACE
