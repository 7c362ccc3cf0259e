#include "solver/io/tetgen_io.h"

#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "solver/io/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

TEST(TetGenIo, RoundTripKeepsCountsAndPositions) {
  TempDir dir;
  const TetMesh cube = test::unitCubeTets(0.37, Vec3(1.0 / 3.0, -2.0, 1e-3));
  writeTetGen(dir / "cube", cube);
  MeshReadReport report;
  const TetMesh back = readTetGen(dir / "cube.node", &report);
  ASSERT_EQ(back.numVertices(), 8);
  ASSERT_EQ(back.numTets(), 6);
  for (int i = 0; i < 8; ++i)
    EXPECT_EQ(back.vertices[i], cube.vertices[i]) << "17 digits round-trip exactly";
  EXPECT_EQ(back.tets, cube.tets);
  EXPECT_EQ(report.reorientedTets, 0);
  EXPECT_EQ(report.indexBase, 0);
  EXPECT_EQ(back.faces.size(), 12u) << "the .face file holds the 12 boundary triangles";
}

TEST(TetGenIo, ReadsOneBasedCommentsAttributesMarkersAndCrlf) {
  MeshReadReport report;
  const TetMesh m = readTetGen(fs::path(GALSCULPT_TEST_DATA) / "valid" / "tricky", &report);
  EXPECT_EQ(report.indexBase, 1);
  ASSERT_EQ(m.numVertices(), 5);
  ASSERT_EQ(m.numTets(), 2);
  EXPECT_EQ(m.vertices[4], Vec3(1, 1, 1));
  EXPECT_EQ(m.vertexMarkers, (std::vector<int>{1, 1, 0, 1, 1}));
  EXPECT_EQ(report.reorientedTets, 1) << "the second tet is inverted in the file";
  for (int t = 0; t < m.numTets(); ++t) EXPECT_GT(tetVolume(m, t), 0.0);
  ASSERT_EQ(m.faces.size(), 1u);
  EXPECT_EQ(m.faces[0], (Tri{0, 2, 1}));
  EXPECT_EQ(m.faceMarkers, std::vector<int>{5});
  ASSERT_FALSE(report.notes.empty());
  EXPECT_NE(report.notes[0].find("reoriented 1 inverted tet"), std::string::npos);
}

TEST(TetGenIo, TenNodeTetsKeepCorners) {
  TempDir dir;
  test::writeText(dir / "q.node",
                  "10 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 .5 0 0\n5 .5 .5 0\n6 0 .5 0\n"
                  "7 0 0 .5\n8 .5 0 .5\n9 0 .5 .5\n");
  test::writeText(dir / "q.ele", "1 10 0\n0 0 1 2 3 4 5 6 7 8 9\n");
  MeshReadReport report;
  const TetMesh m = readTetGen(dir / "q.ele", &report);
  ASSERT_EQ(m.numTets(), 1);
  EXPECT_EQ(m.tets[0], (Tet{0, 1, 2, 3}));
  EXPECT_EQ(report.unusedVertices, 6);
}

// Every file of the broken corpus gives its own file:line message.
TEST(TetGenIo, BrokenCorpusGivesFileAndLineErrors) {
  const fs::path dir = fs::path(GALSCULPT_TEST_DATA) / "broken";
  std::istringstream expected(test::readText(dir / "expected.tsv"));
  std::string line;
  int cases = 0;
  while (std::getline(expected, line)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t tab = line.find('\t');
    ASSERT_NE(tab, std::string::npos) << line;
    const std::string name = line.substr(0, tab), message = line.substr(tab + 1);
    SCOPED_TRACE(name);
    EXPECT_THROW_WITH(readTetGen(dir / name), InputError, message);
    ++cases;
  }
  EXPECT_GE(cases, 20);
}

// Truncation at every byte and random corruption never crash: they parse or throw InputError.
TEST(TetGenIo, TruncatedAndCorruptedFilesNeverCrash) {
  TempDir dir;
  writeTetGen(dir / "good", test::unitCubeTets());
  const std::string node = test::readText(dir / "good.node");
  const std::string ele = test::readText(dir / "good.ele");
  int parsed = 0, rejected = 0;
  auto attempt = [&](const std::string& n, const std::string& e) {
    test::writeText(dir / "t.node", n);
    test::writeText(dir / "t.ele", e);
    try {
      readTetGen(dir / "t");
      ++parsed;
    } catch (const InputError&) {
      ++rejected;
    }
  };
  for (size_t cut = 0; cut < node.size(); ++cut) attempt(node.substr(0, cut), ele);
  for (size_t cut = 0; cut < ele.size(); ++cut) attempt(node, ele.substr(0, cut));
  std::mt19937 gen(42);
  for (int trial = 0; trial < 400; ++trial) {
    std::string n = node, e = ele;
    std::string& target = (trial % 2) ? n : e;
    for (int k = 0; k < 1 + trial % 5; ++k)
      target[gen() % target.size()] = static_cast<char>(gen() & 0xff);
    attempt(n, e);
  }
  for (int trial = 0; trial < 50; ++trial) {
    std::string junk(1 + gen() % 300, '\0');
    for (char& c : junk) c = static_cast<char>(gen() & 0xff);
    attempt(junk, junk);
  }
  EXPECT_GT(rejected, 500);
  EXPECT_GT(parsed, 0) << "some corruptions (inside comments) still give a valid mesh";
}

TEST(TetGenIo, StemResolution) {
  EXPECT_EQ(tetgenStem("a/b.node"), fs::path("a/b"));
  EXPECT_EQ(tetgenStem("a/b.ele"), fs::path("a/b"));
  EXPECT_EQ(tetgenStem("a/b"), fs::path("a/b"));
}

TEST(TetGenIo, WriteIntoMissingFolderFailsAndLeavesNothing) {
  TempDir dir;
  EXPECT_THROW_WITH(writeTetGen(dir / "missing" / "x", test::unitCubeTets()), OutputError,
                    "does not exist");
}

}  // namespace
}  // namespace galsculpt
