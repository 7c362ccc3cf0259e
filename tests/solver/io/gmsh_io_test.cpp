#include "solver/io/gmsh_io.h"

#include <gtest/gtest.h>

#include "solver/io/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

const char* kSparseTags = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
1
3 1 "body"
$EndPhysicalNames
$Nodes
2 5 10 50
0 1 0 1
10
0 0 0
3 1 0 4
20
30
40
50
1 0 0
0 1 0
0 0 1
1 1 1
$EndNodes
$Elements
2 3 1 3
2 1 2 1
1 10 20 30
3 1 4 2
2 10 20 30 40
3 20 40 30 50
$EndElements
)";

TEST(GmshIo, ReadsSparseTagsSkipsOtherElementsAndReorients) {
  test::TempDir dir;
  test::writeText(dir / "m.msh", kSparseTags);
  MeshReadReport report;
  const TetMesh m = readGmsh(dir / "m.msh", &report);
  ASSERT_EQ(m.numVertices(), 5);
  ASSERT_EQ(m.numTets(), 2) << "the triangle block is skipped";
  EXPECT_EQ(m.vertices[4], Vec3(1, 1, 1));
  for (int t = 0; t < 2; ++t) EXPECT_GT(tetVolume(m, t), 0.0);
  EXPECT_EQ(report.reorientedTets, 1);
}

TEST(GmshIo, RoundTrip) {
  test::TempDir dir;
  const TetMesh cube = test::unitCubeTets(0.1, Vec3(0.3, 0.2, 0.1));
  writeGmsh(dir / "c.msh", cube);
  const TetMesh back = readGmsh(dir / "c.msh");
  EXPECT_EQ(back.vertices, cube.vertices);
  EXPECT_EQ(back.tets, cube.tets);
}

TEST(GmshIo, ErrorsNameFileAndLine) {
  test::TempDir dir;
  struct Case {
    std::string text, message;
  };
  const std::vector<Case> cases = {
      {"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n", "x.msh:2: unsupported MSH version 2.2"},
      {"$MeshFormat\n4.1 1 8\n$EndMeshFormat\n", "x.msh:2: binary MSH is not supported"},
      {"hello\n", "x.msh:1: expected a section"},
      {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n", "x.msh: no tetrahedra"},
      {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n3 1 0 1\n1\n0 0 x\n$EndNodes\n",
       "x.msh:8: expected coordinate (a number), got 'x'"},
      {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n3 1 0 1\n1\n0 0 0\n$EndNodes\n"
       "$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n",
       "x.msh:13: unknown node tag 2"},
      {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 999999999 1 1\n",
       "x.msh:5: node counts exceed"},
      {"$MeshFormat\n4.1 0 8\n", "x.msh:2: unexpected end of file, expected $EndMeshFormat"},
  };
  for (const Case& c : cases) {
    test::writeText(dir / "x.msh", c.text);
    EXPECT_THROW_WITH(readGmsh(dir / "x.msh"), InputError, c.message);
  }
}

}  // namespace
}  // namespace galsculpt
