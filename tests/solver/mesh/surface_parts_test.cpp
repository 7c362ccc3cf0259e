#include "solver/mesh/surface_parts.h"

#include <gtest/gtest.h>

#include "solver/mesh/shape_generators.h"
#include "solver/mesh/surface_checks.h"

namespace galsculpt {
namespace {

TEST(SurfaceParts, ShellsComeApartAndBackWhole) {
  // Two spheres in one surface: split by shell, each is its sphere with its own numbering;
  // appended again, the same surface.
  const TriMesh a = makeIcosphere(1.0, 2), b = makeIcosphere(0.5, 1);
  TriMesh both = a;
  TriMesh moved = b;
  for (Vec3& p : moved.vertices) p += Vec3(3, 0, 0);
  appendSurface(both, moved);
  ASSERT_EQ(both.numVertices(), a.numVertices() + b.numVertices());
  std::vector<int> shellOfFace;
  ASSERT_EQ(countSurfacePieces(both, &shellOfFace), 2);
  const std::vector<TriMesh> parts = splitByGroup(both, shellOfFace, 2);
  ASSERT_EQ(parts.size(), 2u);
  // The same triangles, corner by corner, in the same order.
  auto sameTriangles = [](const TriMesh& part, const TriMesh& shape) {
    ASSERT_EQ(part.numFaces(), shape.numFaces());
    EXPECT_EQ(part.numVertices(), shape.numVertices());
    for (int f = 0; f < shape.numFaces(); ++f)
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(part.vertices[part.faces[f][k]], shape.vertices[shape.faces[f][k]]);
  };
  sameTriangles(parts[0], a);
  sameTriangles(parts[1], moved);
  const TriMesh second = facesOfGroup(both, shellOfFace, 1);
  EXPECT_EQ(second.faces, parts[1].faces);
  EXPECT_EQ(second.vertices, parts[1].vertices);
}

TEST(SurfaceParts, AVertexTwoGroupsShareIsAVertexOfEach) {
  // A square of two triangles sharing an edge, each its own group; -1 and groups past the count
  // are left out.
  TriMesh square;
  square.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  square.faces = {{0, 1, 2}, {0, 2, 3}, {1, 2, 3}};
  const std::vector<TriMesh> parts = splitByGroup(square, {0, 1, -1}, 2);
  EXPECT_EQ(parts[0].numVertices(), 3);
  EXPECT_EQ(parts[1].numVertices(), 3);
  EXPECT_EQ(parts[1].vertices[0], Vec3(0, 0, 0));
  EXPECT_EQ(parts[1].vertices[2], Vec3(0, 1, 0));
  EXPECT_EQ(parts[1].faces[0], (Tri{0, 1, 2}));
  EXPECT_TRUE(facesOfGroup(square, {0, 1, 5}, 5).faces.size() == 1);
}

}  // namespace
}  // namespace galsculpt
