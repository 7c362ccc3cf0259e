// The SIMD element lanes against the scalar element kernel: the same bits for every element
// they take, the hard ones handed back, and a simulation that runs on identically.
#include "solver/fem/element_lanes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "solver/fem/material_kernels.h"
#include "solver/fem/material_table.h"
#include "solver/frame/element_pass.h"
#include "solver/frame/step.h"
#include "tests/test_util.h"

namespace galsculpt::kernels {
namespace {

struct Scalar {
  double energy, gradient[12], packed[90];
};

Scalar scalarElement(MaterialModel model, const Lame& lame, const RestData& rest,
                     const double x[12]) {
  Scalar out;
  double h[144];
  evaluateElement(model, lame, rest, x, kIntact, true, Hessian::ProjectedSpd, out.energy,
                  out.gradient, h);
  ElementPass::pack(h, out.packed);  // the frame's packing, which the lanes write directly
  return out;
}

std::vector<LaneBuild> builds() {
  std::vector<LaneBuild> out;
  for (LaneBuild b : {LaneBuild::Portable, LaneBuild::Avx2})
    if (laneKernel(b)) out.push_back(b);
  return out;
}

// A random element: a random rest tet (positive volume) and a deformation of it, mild to
// severe, some turned inside out, or a rigid motion, or none.
struct Element {
  RestData rest;
  double x[12];
};

std::vector<Element> randomElements(int count, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<Element> out;
  while (static_cast<int>(out.size()) < count) {
    double p[12];
    for (double& v : p) v = 0.01 * n(gen);
    Element e;
    if (!computeRest(p, e.rest) || e.rest.volume < 1e-9) continue;
    const int kind = static_cast<int>(out.size()) % 6;
    if (kind < 4) {  // deformed, mildly to severely (some inside out)
      const double amount = std::array<double, 4>{0.01, 0.1, 0.4, 1.0}[kind];
      for (int i = 0; i < 12; ++i) e.x[i] = 3.0 * p[i] + 0.01 * amount * n(gen) + 0.5;
    } else {  // moved rigidly (F a rotation to round-off), or at rest (F = I)
      const Eigen::Matrix3d r =
          kind == 4
              ? Eigen::Quaterniond(n(gen), n(gen), n(gen), n(gen)).normalized().toRotationMatrix()
              : Eigen::Matrix3d::Identity();
      const Eigen::Vector3d shift =
          kind == 4 ? Eigen::Vector3d(n(gen), n(gen), n(gen)) : Eigen::Vector3d::Zero();
      for (int a = 0; a < 4; ++a) {
        const Eigen::Vector3d y = r * Eigen::Vector3d(p[3 * a], p[3 * a + 1], p[3 * a + 2]) + shift;
        for (int k = 0; k < 3; ++k) e.x[3 * a + k] = y[k];
      }
    }
    out.push_back(e);
  }
  return out;
}

// Runs `elements` through the lanes in groups of 1-4; counts the elements handed back and
// checks every other one against the scalar kernel, bit for bit. Without `stiffness` the lanes
// are given no stiffness to write (null) and only the energy and the force are compared.
void compareWithScalar(LaneBuild build, MaterialModel model, const std::vector<Element>& elements,
                       int& handedBack, bool stiffness = true) {
  const Lame lame{3.4e4, 1.4e5};
  const LaneKernel kernel = laneKernel(build);
  handedBack = 0;
  size_t next = 0;
  for (int group = 0; next < elements.size(); ++group) {
    const int count = std::min<int>(1 + group % kLanes, static_cast<int>(elements.size() - next));
    LaneInputs in;
    LaneOutputs out;
    std::vector<Scalar> got(count);
    const double sentinel = -12345.0;
    for (int l = 0; l < count; ++l) {
      const Element& e = elements[next + l];
      in.rest[l] = &e.rest;
      std::memcpy(in.x[l], e.x, sizeof e.x);
      got[l].energy = sentinel;
      out.energy[l] = &got[l].energy;
      out.gradient[l] = got[l].gradient;
      out.packedHessian[l] = stiffness ? got[l].packed : nullptr;
    }
    in.count = count;
    in.stiffness = stiffness;
    const unsigned back = kernel(model, lame, in, out);
    EXPECT_EQ(back >> count, 0u) << "only lanes in use are handed back";
    for (int l = 0; l < count; ++l) {
      const Element& e = elements[next + l];
      if (back >> l & 1u) {
        ++handedBack;
        EXPECT_EQ(got[l].energy, sentinel) << "a lane handed back is not written";
        continue;
      }
      const Scalar want = scalarElement(model, lame, e.rest, e.x);
      ASSERT_EQ(std::memcmp(&want.energy, &got[l].energy, sizeof(double)), 0)
          << laneBuildName(build) << " element " << next + l;
      ASSERT_EQ(std::memcmp(want.gradient, got[l].gradient, sizeof want.gradient), 0)
          << laneBuildName(build) << " element " << next + l;
      if (stiffness) {
        ASSERT_EQ(std::memcmp(want.packed, got[l].packed, sizeof want.packed), 0)
            << laneBuildName(build) << " element " << next + l;
      }
    }
    next += count;
  }
}

TEST(ElementLanes, ComputeTheScalarKernelsBitsForTheElementsTheyTake) {
  const std::vector<LaneBuild> available = builds();
  ASSERT_FALSE(available.empty()) << "the portable build always exists";
  const std::vector<Element> elements = randomElements(4000, 11);
  for (LaneBuild build : available) {
    // Every model of the table. (The corotational singular-value Hessian, lambda 11^T + 2 mu I,
    // has a repeated eigenvalue: the lanes take it through their Jacobi sweeps, as the scalar
    // kernel does.)
    for (const MaterialInfo& row : kMaterialModels) {
      int back = 0;
      compareWithScalar(build, row.model, elements, back);
      // Only what the scalar kernel's accurate SVD must redo goes back: rare.
      EXPECT_LT(back, 40) << laneBuildName(build) << " hands back too much for " << row.name;
    }
  }
}

// A line search's trial: the energy and the force alone, the scalar kernel's bits, and no
// stiffness written (its pointers are null).
TEST(ElementLanes, WithoutTheStiffnessComputeTheScalarKernelsEnergyAndForce) {
  const std::vector<Element> elements = randomElements(1000, 23);
  for (LaneBuild build : builds()) {
    for (const MaterialInfo& row : kMaterialModels) {
      int back = 0;
      compareWithScalar(build, row.model, elements, back, false);
      EXPECT_LT(back, 20) << laneBuildName(build) << " hands back too much for " << row.name;
    }
  }
}

TEST(ElementLanes, HandBackTheElementsTheClosedFormsCannotTake) {
  std::vector<Element> elements = randomElements(4, 5);
  // All corners at one point (F = 0), a NaN corner and a tet collapsed onto a line (rank-one F)
  // go back; a tet flattened into a plane (rank two, a zero singular value the closed forms
  // resolve) is taken, with the scalar kernel's bits.
  for (int i = 0; i < 12; ++i) elements[0].x[i] = 0.5;
  elements[1].x[4] = std::numeric_limits<double>::quiet_NaN();
  for (int a = 0; a < 4; ++a) elements[2].x[3 * a] = elements[2].x[3 * a + 2] = 0.25;
  for (int a = 0; a < 4; ++a) elements[3].x[3 * a + 2] = 0.25;
  const Lame lame{3.4e4, 1.4e5};
  for (LaneBuild build : builds()) {
    LaneInputs in;
    LaneOutputs out;
    Scalar got[4];
    in.count = 4;
    for (int l = 0; l < 4; ++l) {
      in.rest[l] = &elements[l].rest;
      std::memcpy(in.x[l], elements[l].x, sizeof elements[l].x);
      out.energy[l] = &got[l].energy;
      out.gradient[l] = got[l].gradient;
      out.packedHessian[l] = got[l].packed;
    }
    EXPECT_EQ(laneKernel(build)(MaterialModel::StableNeoHookean, lame, in, out), 0b0111u)
        << laneBuildName(build);
    const Scalar want =
        scalarElement(MaterialModel::StableNeoHookean, lame, elements[3].rest, elements[3].x);
    EXPECT_EQ(std::memcmp(want.packed, got[3].packed, sizeof want.packed), 0);
  }
}

// A damaged element by the scalar kernel: energy, force, open cracks and the packed projected
// stiffness.
struct ScalarCracked {
  double energy, gradient[12], packed[90];
  std::uint8_t opened;
};

ScalarCracked scalarCracked(const Lame& lame, const RestData& rest, const double x[12],
                            std::uint8_t intact, bool resists) {
  ScalarCracked out{};
  double h[144];
  evaluateElement(MaterialModel::StableNeoHookean, lame, rest, x, intact, resists,
                  Hessian::ProjectedSpd, out.energy, out.gradient, h, &out.opened);
  ElementPass::pack(h, out.packed);
  return out;
}

// Every damaged-edge set the cracked lanes take (all but intact and the three two-pieces
// sets), with and without crack contact, over random deformations (some
// pressing cracks shut, some pulling them open, so that the pivoting flips): the scalar
// kernel's bits, in groups of 1-4 lanes of mixed sets, under both closing laws.
TEST(ElementLanes, DamagedElementsGetTheScalarKernelsBits) {
  Lame lame{3.4e4, 1.4e5};
  std::vector<std::uint8_t> sets;
  for (int m = 0; m < kIntact; ++m)
    if (!holdsTwoPieces(static_cast<std::uint8_t>(m))) sets.push_back(static_cast<std::uint8_t>(m));
  ASSERT_EQ(sets.size(), 60u);
  // Random rest tets under random deformations within 20 % of rest (edges pressed and
  // pulled), and a few at rest exactly (every strain zero: the ties).
  std::mt19937 gen(23);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<Element> elements;
  while (elements.size() < 2400) {
    double p[12];
    for (double& v : p) v = 0.01 * n(gen);
    Element e;
    if (!computeRest(p, e.rest) || e.rest.volume < 1e-9) continue;
    Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
    if (elements.size() % 10 != 0)
      for (int i = 0; i < 9; ++i) f(i % 3, i / 3) += 0.1 * n(gen);
    for (int a = 0; a < 4; ++a) {
      const Eigen::Vector3d y = f * Eigen::Vector3d(p[3 * a], p[3 * a + 1], p[3 * a + 2]);
      for (int k = 0; k < 3; ++k) e.x[3 * a + k] = y[k] + 0.25;
    }
    elements.push_back(e);
  }
  // The hard closing law and the smooth one (crack_law.h), whose openings the same per-element
  // call solves.
  for (double width : {0.0, 1e-2})
    for (LaneBuild build : builds()) {
      SCOPED_TRACE(::testing::Message() << "crack width " << width);
      lame.crackWidth = width;
      const CrackedLaneKernel kernel = crackedLaneKernel(build);
      ASSERT_NE(kernel, nullptr);
      int handedBack = 0, flipped = 0, unloaded = 0, cutFree = 0;
      size_t next = 0;
      for (int group = 0; next < elements.size(); ++group) {
        const int count =
            std::min<int>(1 + group % kLanes, static_cast<int>(elements.size() - next));
        CrackedLaneInputs in;
        LaneOutputs out;
        ScalarCracked got[kLanes];
        for (int l = 0; l < count; ++l) {
          const size_t i = next + l;
          in.rest[l] = &elements[i].rest;
          std::memcpy(in.x[l], elements[i].x, sizeof elements[i].x);
          in.intact[l] = sets[(i * 7) % sets.size()];
          in.resists[l] = (i / 3) % 4 != 0;
          got[l].energy = -12345.0;
          out.energy[l] = &got[l].energy;
          out.gradient[l] = got[l].gradient;
          out.packedHessian[l] = got[l].packed;
          out.opened[l] = &got[l].opened;
        }
        in.count = count;
        const unsigned back = kernel(lame, in, out);
        EXPECT_EQ(back >> count, 0u);
        for (int l = 0; l < count; ++l) {
          if (back >> l & 1u) {
            ++handedBack;
            continue;
          }
          const size_t i = next + l;
          const ScalarCracked want =
              scalarCracked(lame, elements[i].rest, elements[i].x, in.intact[l], in.resists[l]);
          const std::uint8_t damaged = static_cast<std::uint8_t>(~in.intact[l] & kIntact);
          unloaded += want.energy == 0.0 && want.opened == damaged;
          // The pivoting starts from the damaged edges not pressed shorter: count the elements
          // where it flipped some.
          double d[6][3], strain[6];
          edgeGreenStrains(elements[i].rest, elements[i].x, d, strain);
          std::uint8_t guess = in.resists[l] ? 0 : damaged;
          for (int e = 0; e < 6; ++e)
            if ((damaged >> e & 1) && strain[e] >= 0.0) guess |= static_cast<std::uint8_t>(1u << e);
          flipped += want.opened != guess;
          ASSERT_EQ(want.opened, got[l].opened) << laneBuildName(build) << " element " << i;
          ASSERT_EQ(std::memcmp(&want.energy, &got[l].energy, sizeof(double)), 0)
              << laneBuildName(build) << " element " << i;
          ASSERT_EQ(std::memcmp(want.gradient, got[l].gradient, sizeof want.gradient), 0)
              << laneBuildName(build) << " element " << i;
          if (in.intact[l] == 0 && want.opened == kIntact) {
            // Zero, and not written: the caller skips it.
            for (double v : want.packed) ASSERT_EQ(v, 0.0);
            ++cutFree;
            continue;
          }
          ASSERT_EQ(std::memcmp(want.packed, got[l].packed, sizeof want.packed), 0)
              << laneBuildName(build) << " element " << i;
        }
        next += count;
      }
      EXPECT_EQ(handedBack, 0) << laneBuildName(build);
      EXPECT_GT(unloaded, 20) << "the set of unloaded elements is exercised";
      EXPECT_GT(flipped, 200) << "the pivoting's flips are exercised";
      EXPECT_GT(cutFree, 20) << "elements whose stiffness is zero are exercised";
    }
}

// A NaN corner goes back, its group's other lanes are written with the scalar kernel's bits.
TEST(ElementLanes, DamagedElementsWithANaNCornerAreHandedBack) {
  std::vector<Element> elements = randomElements(4, 9);
  elements[2].x[7] = std::numeric_limits<double>::quiet_NaN();
  const Lame lame{3.4e4, 1.4e5};
  for (LaneBuild build : builds()) {
    CrackedLaneInputs in;
    LaneOutputs out;
    ScalarCracked got[4];
    in.count = 4;
    for (int l = 0; l < 4; ++l) {
      in.rest[l] = &elements[l].rest;
      std::memcpy(in.x[l], elements[l].x, sizeof elements[l].x);
      in.intact[l] = 0x07;
      in.resists[l] = true;
      out.energy[l] = &got[l].energy;
      out.gradient[l] = got[l].gradient;
      out.packedHessian[l] = got[l].packed;
      out.opened[l] = &got[l].opened;
    }
    EXPECT_EQ(crackedLaneKernel(build)(lame, in, out), 0b0100u) << laneBuildName(build);
    const ScalarCracked want = scalarCracked(lame, elements[3].rest, elements[3].x, 0x07, true);
    EXPECT_EQ(std::memcmp(want.packed, got[3].packed, sizeof want.packed), 0);
  }
}

TEST(ElementLanes, ASimulationRunsOnIdenticallyWithAndWithoutThem) {
  const SimModel m =
      buildSimModel(test::gridBar(2, 8, 2, 0.1),
                    {MaterialModel::StableNeoHookean, lameFromYoungPoisson(1e5, 0.4), 1000.0, {}});
  StepSettings settings;
  settings.newtonIterations = 3;
  // Intact, and with damage: a slit across the bar and its lowest part cut loose into
  // elements with every edge damaged (which fall, their cracks open: zero stiffness).
  auto run = [&](LaneBuild build, bool damaged) {
    setLaneBuild(build);
    SimState s = initialState(m);
    AnchorConstraint top;
    const BoundingBox box = boundingBox(m.mesh.vertices);
    const double yMax = box.max.y(), height = box.size().y();
    for (int v = 0; v < m.numVertices(); ++v)
      if (m.mesh.vertices[v].y() > yMax - 1e-9) top.vertices.push_back(v);
    s.anchors = {top};
    if (damaged) {
      const double slit = box.min.y() + 0.6 * height, loose = box.min.y() + 0.2 * height;
      for (int e = 0; e < m.numEdges(); ++e) {
        const double ya = m.mesh.vertices[m.edges[e][0]].y(),
                     yb = m.mesh.vertices[m.edges[e][1]].y();
        const bool crosses =
            std::min(ya, yb) < slit && std::max(ya, yb) > slit &&
            m.mesh.vertices[m.edges[e][0]].x() < box.min.x() + 0.6 * box.size().x();
        if (crosses || std::max(ya, yb) < loose) s.damaged[e] = 1;
      }
      ++s.damageRevision;
    }
    for (int f = 0; f < 8; ++f) step(m, s, settings);
    return s.x;
  };
  for (bool damaged : {false, true}) {
    const auto off = run(LaneBuild::Off, damaged);
    for (LaneBuild build : builds()) {
      const auto laned = run(build, damaged);
      ASSERT_EQ(off.size(), laned.size());
      for (size_t v = 0; v < off.size(); ++v)
        ASSERT_EQ(off[v], laned[v]) << laneBuildName(build) << " damaged " << damaged;
    }
  }
  setLaneBuild(chosenLaneBuild() == LaneBuild::Off ? LaneBuild::Off : builds().back());
}

}  // namespace
}  // namespace galsculpt::kernels
