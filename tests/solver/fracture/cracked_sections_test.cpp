#include "solver/fracture/cracked_sections.h"

#include <gtest/gtest.h>

#include "solver/fracture/debris.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

// A 6 x 2 x 2 bar of cubes (h = 0.1) whose slab between the vertex planes x = 0.2 and x = 0.3
// is cracked through: every edge across the slab is damaged but those `keep` says.
struct CrackedSlab {
  SimModel model = buildSimModel(test::gridBar(6, 2, 2, 0.1),
                                 {MaterialModel::StVK, lameFromYoungPoisson(1e5, 0.3), 1000.0, {}});
  std::vector<std::uint8_t> damaged = std::vector<std::uint8_t>(model.numEdges(), 0);

  template <typename Keep>
  explicit CrackedSlab(Keep keep) {
    for (int e = 0; e < model.numEdges(); ++e) {
      const Vec3& a = model.mesh.vertices[model.edges[e][0]];
      const Vec3& b = model.mesh.vertices[model.edges[e][1]];
      const bool across = std::min(a.x(), b.x()) < 0.25 && std::max(a.x(), b.x()) > 0.25;
      if (across && !keep(a, b)) damaged[e] = 1;
    }
  }
  int pieces() const { return censusPieces(model, damaged).pieces; }
};

bool onBottomEdgeLine(const Vec3& a, const Vec3& b) {
  return a.y() < 1e-9 && a.z() < 1e-9 && b.y() < 1e-9 && b.z() < 1e-9;
}

// One intact edge across the slab pins the two halves together: every element around it is
// cracked, so the halves' undamaged elements share no face. That edge, and only it, breaks.
TEST(CrackedSections, AnEdgeThatAloneLinksTwoPartsThroughCrackedElementsBreaks) {
  CrackedSlab slab(onBottomEdgeLine);
  ASSERT_EQ(slab.pieces(), 1) << "the pin holds the halves together";
  std::vector<int> pins;
  for (int e = 0; e < slab.model.numEdges(); ++e) {
    const Vec3& a = slab.model.mesh.vertices[slab.model.edges[e][0]];
    const Vec3& b = slab.model.mesh.vertices[slab.model.edges[e][1]];
    if (!slab.damaged[e] && std::min(a.x(), b.x()) < 0.25 && std::max(a.x(), b.x()) > 0.25)
      pins.push_back(e);
  }
  ASSERT_EQ(pins.size(), 1u);
  EXPECT_EQ(crackedSectionEdges(slab.model, tetFaceNeighbours(slab.model.mesh), slab.damaged, 0.01),
            pins);
  for (const int e : pins) slab.damaged[e] = 1;
  EXPECT_EQ(slab.pieces(), 2);
  EXPECT_TRUE(
      crackedSectionEdges(slab.model, tetFaceNeighbours(slab.model.mesh), slab.damaged, 0.01)
          .empty())
      << "nothing left";
  // Off (fraction 0), and when one half is below the fraction (it is no part of its own).
  CrackedSlab again(onBottomEdgeLine);
  EXPECT_TRUE(
      crackedSectionEdges(again.model, tetFaceNeighbours(again.model.mesh), again.damaged, 0.0)
          .empty());
  EXPECT_TRUE(
      crackedSectionEdges(again.model, tetFaceNeighbours(again.model.mesh), again.damaged, 0.4)
          .empty())
      << "the 2-cube half holds a third of the body, under 0.4";
}

// Where the slab's undamaged elements still join the halves through faces, the section holds
// area: a crack across half the section (a slit, the upper row of cubes whole) or a ligament of
// one whole cube breaks nothing. (Keeping only the edges of the top face would leave a line:
// those edges break.)
TEST(CrackedSections, ASlitOrALigamentWithAreaBreaksNothing) {
  const CrackedSlab slit([](const Vec3& a, const Vec3& b) { return a.y() > 0.05 && b.y() > 0.05; });
  EXPECT_EQ(slit.pieces(), 1);
  EXPECT_TRUE(
      crackedSectionEdges(slit.model, tetFaceNeighbours(slit.model.mesh), slit.damaged, 0.01)
          .empty());
  const CrackedSlab ligament([](const Vec3& a, const Vec3& b) {
    return a.y() < 0.15 && a.z() < 0.15 && b.y() < 0.15 && b.z() < 0.15;
  });
  EXPECT_TRUE(crackedSectionEdges(ligament.model, tetFaceNeighbours(ligament.model.mesh),
                                  ligament.damaged, 0.01)
                  .empty())
      << "the corner cube across the slab is whole and shares faces with both halves";
  const CrackedSlab line([](const Vec3& a, const Vec3& b) { return a.y() > 0.15 && b.y() > 0.15; });
  EXPECT_EQ(line.pieces(), 1);
  EXPECT_FALSE(
      crackedSectionEdges(line.model, tetFaceNeighbours(line.model.mesh), line.damaged, 0.01)
          .empty())
      << "the top face's edges alone join the halves along a line";
  // Cut clean through (no edge across kept): already two pieces, nothing to break.
  const CrackedSlab cut([](const Vec3&, const Vec3&) { return false; });
  EXPECT_EQ(cut.pieces(), 2);
  EXPECT_TRUE(
      crackedSectionEdges(cut.model, tetFaceNeighbours(cut.model.mesh), cut.damaged, 0.01).empty());
}

// A vertex of the crack that no undamaged element holds goes with the part nearest through
// intact edges, so the rule leaves no vertex on its own.
TEST(CrackedSections, PartingLeavesNoLooseVertex) {
  CrackedSlab slab(onBottomEdgeLine);
  // Crack every element touching the slab's middle vertex plane too (x = 0.2 and 0.3 stay),
  // so the vertices of the plane x = 0.3 belong to no undamaged element of the right half.
  for (int e = 0; e < slab.model.numEdges(); ++e) {
    const Vec3& a = slab.model.mesh.vertices[slab.model.edges[e][0]];
    const Vec3& b = slab.model.mesh.vertices[slab.model.edges[e][1]];
    const bool across = std::min(a.x(), b.x()) < 0.35 && std::max(a.x(), b.x()) > 0.35;
    if (across && !onBottomEdgeLine(a, b)) slab.damaged[e] = 1;
  }
  const PieceCensus before = censusPieces(slab.model, slab.damaged);
  const std::vector<int> parted =
      crackedSectionEdges(slab.model, tetFaceNeighbours(slab.model.mesh), slab.damaged, 0.01);
  ASSERT_FALSE(parted.empty());
  for (const int e : parted) slab.damaged[e] = 1;
  const PieceCensus after = censusPieces(slab.model, slab.damaged);
  EXPECT_EQ(after.pieces, before.pieces + 1);
  for (int p = 0; p < after.pieces; ++p) EXPECT_GT(after.vertexCount[p], 1) << "piece " << p;
}

}  // namespace
}  // namespace galsculpt
