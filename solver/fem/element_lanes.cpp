#include "solver/fem/element_lanes.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace galsculpt::kernels {

namespace {

bool cpuHasAvx2() {
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

LaneBuild fromEnvironment() {
  const char* wanted = std::getenv("GALSCULPT_ELEMENT_LANES");
  // The portable build is slower than the scalar kernel (SSE2 halves, the Jacobi sweeps of a
  // few lanes paid by all): without AVX2 the scalar kernel does the work.
  const LaneBuild best = cpuHasAvx2() ? LaneBuild::Avx2 : LaneBuild::Off;
  if (!wanted || !*wanted) return best;
  if (std::strcmp(wanted, "off") == 0) return LaneBuild::Off;
  if (std::strcmp(wanted, "portable") == 0) return LaneBuild::Portable;
  if (std::strcmp(wanted, "avx2") == 0) {
    if (cpuHasAvx2()) return LaneBuild::Avx2;
    std::fprintf(stderr,
                 "galsculpt: note: GALSCULPT_ELEMENT_LANES=avx2 but this CPU has no AVX2; "
                 "using the scalar kernel\n");
    return LaneBuild::Off;
  }
  std::fprintf(stderr,
               "galsculpt: note: GALSCULPT_ELEMENT_LANES=%s is not one of avx2, portable, off; "
               "using %s\n",
               wanted, laneBuildName(best));
  return best;
}

// -1 until set: the environment decides.
std::atomic<int> setBuild{-1};

// A build's kernel of the two it was compiled as: none when off, or AVX2 without the CPU for it.
template <class Kernel>
Kernel kernelOf(LaneBuild build, Kernel portable, Kernel avx2) {
  switch (build) {
    case LaneBuild::Off:
      return nullptr;
    case LaneBuild::Portable:
      return portable;
    case LaneBuild::Avx2:
      return cpuHasAvx2() ? avx2 : nullptr;
  }
  return nullptr;
}

}  // namespace

LaneBuild chosenLaneBuild() {
  const int set = setBuild.load(std::memory_order_relaxed);
  if (set >= 0) return static_cast<LaneBuild>(set);
  static const LaneBuild fromEnv = fromEnvironment();
  return fromEnv;
}

void setLaneBuild(LaneBuild build) {
  setBuild.store(static_cast<int>(build), std::memory_order_relaxed);
}

LaneKernel laneKernel(LaneBuild build) {
  return kernelOf<LaneKernel>(build, &portable::evaluateIntactLanes, &avx2::evaluateIntactLanes);
}

void openCracks(const double k[6][6], const double eps[6], std::uint8_t free, std::uint8_t oneWay,
                double width, bool wantStiffness, CrackedStrainState& out) {
  addOpenedCrackEnergy(k, eps, free, oneWay, width, wantStiffness, out);
}

CrackedLaneKernel crackedLaneKernel(LaneBuild build) {
  return kernelOf<CrackedLaneKernel>(build, &portable::evaluateCrackedLanes,
                                     &avx2::evaluateCrackedLanes);
}

const char* laneBuildName(LaneBuild build) {
  switch (build) {
    case LaneBuild::Off:
      return "off";
    case LaneBuild::Portable:
      return "portable";
    case LaneBuild::Avx2:
      return "avx2";
  }
  return "?";
}

}  // namespace galsculpt::kernels
