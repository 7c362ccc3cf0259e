// The strict OFF and PLY readers (engine/meshing/off_ply_reader.h): polygons split into fans,
// colours and other properties skipped, every byte order of PLY, and errors naming the file and
// the line or byte where assimp would have read on.
#include "engine/meshing/off_ply_reader.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <string>

#include "solver/io/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

TEST(OffPlyReader, OffWithCommentsColoursAndAQuadSplitIntoAFan) {
  test::TempDir dir;
  test::writeText(dir / "q.off", R"(COFF
# a unit square and an apex
5 2 0
0 0 0  255 0 0 255
1 0 0  255 0 0 255
1 1 0  255 0 0 255
0 1 0  255 0 0 255
0.5 0.5 1  255 0 0 255
4 0 1 2 3
3 0 1 4
)");
  const RawSurface s = readOff(dir / "q.off");
  ASSERT_EQ(s.vertices.size(), 5u);
  EXPECT_EQ(s.vertices[4], Vec3(0.5, 0.5, 1));
  ASSERT_EQ(s.faces.size(), 3u) << "the quad is two triangles";
  EXPECT_EQ(s.faces[0], (Tri{0, 1, 2}));
  EXPECT_EQ(s.faces[1], (Tri{0, 2, 3}));
  EXPECT_EQ(s.faces[2], (Tri{0, 1, 4}));
}

TEST(OffPlyReader, AsciiAndBinaryPlyGiveTheSameSurface) {
  test::TempDir dir;
  const std::string header = R"(element vertex 4
property float x
property float y
property float z
property uchar red
element face 2
property list uchar int vertex_indices
element edge 1
property int v1
end_header
)";
  test::writeText(dir / "a.ply", "ply\nformat ascii 1.0\n" + header +
                                     "0 0 0 9\n1 0 0 9\n0 1 0 9\n0 0 1 9\n3 0 1 2\n3 0 1 3\n7\n");
  // The same in big-endian binary.
  std::string binary = "ply\nformat binary_big_endian 1.0\n" + header;
  const auto put = [&](const void* p, size_t n) {
    const char* c = static_cast<const char*>(p);
    for (size_t i = n; i-- > 0;) binary.push_back(c[i]);  // little-endian host to big-endian
  };
  const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const auto& v : xyz) {
    for (float c : v) put(&c, 4);
    binary.push_back(9);
  }
  for (const int f : {2, 3}) {
    binary.push_back(3);
    for (const int i : {0, 1, f}) put(&i, 4);
  }
  const int edge = 7;
  put(&edge, 4);
  std::ofstream(dir / "b.ply", std::ios::binary) << binary;
  const RawSurface a = readPly(dir / "a.ply"), b = readPly(dir / "b.ply");
  ASSERT_EQ(a.vertices.size(), 4u);
  ASSERT_EQ(a.faces.size(), 2u);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_EQ(b.faces[1], (Tri{0, 1, 3}));
}

TEST(OffPlyReader, BadIndicesCountsAndLeftoversNameTheirLineOrByte) {
  test::TempDir dir;
  test::writeText(dir / "index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  EXPECT_THROW_WITH(readOff(dir / "index.off"), InputError, "index.off:6");
  EXPECT_THROW_WITH(readOff(dir / "index.off"), InputError, "vertex index 3 out of range [0, 2]");
  test::writeText(dir / "short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n");
  EXPECT_THROW_WITH(readOff(dir / "short.off"), InputError, "corners but the line lists");
  test::writeText(dir / "more.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n");
  EXPECT_THROW_WITH(readOff(dir / "more.off"), InputError, "unexpected data after the 1 faces");
  test::writeText(dir / "noface.ply",
                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                  "property float z\nelement face 0\nproperty int nothing\nend_header\n0 0 0\n");
  EXPECT_THROW_WITH(readPly(dir / "noface.ply"), InputError, "vertex_indices");
}

}  // namespace
}  // namespace galsculpt
