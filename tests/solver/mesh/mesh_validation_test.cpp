#include "solver/mesh/mesh_validation.h"

#include <gtest/gtest.h>

#include "solver/io/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

TetMesh twoTets() {
  TetMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0),
                Vec3(0, 0, 1), Vec3(1, 1, 1), Vec3(5, 5, 5)};
  m.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  return m;
}

TEST(MeshValidation, InvertedTetsAreReorientedAndUnusedVerticesCounted) {
  TetMesh m = twoTets();
  std::swap(m.tets[1][0], m.tets[1][1]);  // one inverted
  const double before = tetSixVolume(m.vertices[m.tets[1][0]], m.vertices[m.tets[1][1]],
                                     m.vertices[m.tets[1][2]], m.vertices[m.tets[1][3]]);
  MeshReadReport report;
  validateTets(m, "m.ele", {2, 3}, report);
  EXPECT_EQ(report.reorientedTets, 1);
  EXPECT_EQ(report.unusedVertices, 1) << "vertex 5 is in no tet";
  for (const Tet& t : m.tets)
    EXPECT_GT(tetSixVolume(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]),
              0.0);
  EXPECT_LT(before, 0.0);
}

TEST(MeshValidation, BadTetsNameTheFileAndLine) {
  auto errorOf = [](TetMesh m) {
    MeshReadReport report;
    try {
      validateTets(m, "m.ele", {7, 9}, report);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  TetMesh repeated = twoTets();
  repeated.tets[1] = {1, 2, 2, 4};
  EXPECT_NE(errorOf(repeated).find("m.ele:9: degenerate tet: vertex 2 appears twice"),
            std::string::npos)
      << errorOf(repeated);
  TetMesh flat = twoTets();
  flat.vertices[4] = Vec3(0.5, 0.5, 0.0);
  flat.tets[1] = {0, 1, 2, 4};
  EXPECT_NE(errorOf(flat).find("m.ele:9: degenerate tet: zero volume"), std::string::npos)
      << errorOf(flat);
  TetMesh duplicate = twoTets();
  duplicate.tets[1] = {3, 2, 1, 0};
  EXPECT_NE(errorOf(duplicate).find("m.ele:9: duplicate tet"), std::string::npos)
      << errorOf(duplicate);
  TetMesh outOfRange = twoTets();
  outOfRange.tets[0][3] = 6;
  EXPECT_NE(errorOf(outOfRange).find("m.ele:7:"), std::string::npos) << errorOf(outOfRange);
}

}  // namespace
}  // namespace galsculpt
