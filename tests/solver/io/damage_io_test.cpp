#include "solver/io/damage_io.h"

#include <gtest/gtest.h>

#include "solver/io/input_error.h"
#include "solver/model/sim_model.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

TEST(DamageIo, RoundTrip) {
  test::TempDir dir;
  const SimModel model = buildSimModel(test::gridBar(2, 2, 2, 0.1), MaterialParams{});
  std::vector<std::uint8_t> damaged(model.numEdges(), 0);
  std::vector<float> crossing(model.numEdges(), kNoCrossing);
  for (int e = 0; e < model.numEdges(); e += 3) damaged[e] = 1;
  for (int e = 0; e < model.numEdges(); e += 6) crossing[e] = 0.01f + 0.98f * e / model.numEdges();
  crossing[3] = 1.0f / 3.0f;  // a fraction with no short decimal form comes back bit for bit
  writeDamage(dir / "bar.damage", model.edges, damaged, crossing);
  const EdgeDamageState back = readDamage(dir / "bar.damage", model.edges);
  EXPECT_EQ(back.damaged, damaged);
  EXPECT_EQ(back.crossing, crossing);
  // Without crossings (fracture): none read back.
  writeDamage(dir / "bar.damage", model.edges, damaged);
  EXPECT_EQ(readDamage(dir / "bar.damage", model.edges).crossing,
            std::vector<float>(model.numEdges(), kNoCrossing));
  const std::vector<std::uint8_t> none(model.numEdges(), 0);
  writeDamage(dir / "bar.damage", model.edges, none);
  EXPECT_EQ(readDamage(dir / "bar.damage", model.edges).damaged, none);
}

TEST(DamageIo, Version1FilesAndReversedEdgesRead) {
  test::TempDir dir;
  const std::vector<Edge> edges = {{0, 1}, {0, 2}, {1, 2}};
  test::writeText(dir / "v1.damage", "# galsculpt damage 1\n2\n0 1\n2 1\n");
  EdgeDamageState d = readDamage(dir / "v1.damage", edges);
  EXPECT_EQ(d.damaged, (std::vector<std::uint8_t>{1, 0, 1}));
  EXPECT_EQ(d.crossing, std::vector<float>(3, kNoCrossing));
  // A line listing an edge from its second vertex: the fraction is turned round.
  test::writeText(dir / "v2.damage", "1\n2 0 0.25\n");
  d = readDamage(dir / "v2.damage", edges);
  EXPECT_EQ(d.damaged, (std::vector<std::uint8_t>{0, 1, 0}));
  EXPECT_EQ(d.crossing[1], 0.75f);
}

TEST(DamageIo, MalformedFilesNameFileAndLine) {
  test::TempDir dir;
  const std::vector<Edge> edges = {{0, 1}, {0, 2}, {1, 2}};
  auto expectError = [&](const std::string& text, const std::string& message) {
    test::writeText(dir / "d.damage", text);
    EXPECT_THROW_WITH(readDamage(dir / "d.damage", edges), InputError, message);
  };
  expectError("# galsculpt damage 1\n2\n0 1\n", "d.damage:3: unexpected end of file");
  expectError("1\n0 3\n", "d.damage:2: (0, 3) is not an edge of the mesh");
  expectError("2\n1 0\n0 1\n", "d.damage:3: edge listed twice");
  expectError("1\n0 1\n1 2\n", "d.damage:3: more edges than the count on line 1 says");
  expectError("1\n0 x\n", "d.damage:2:");
  expectError("9\n", "d.damage:1: the mesh has 3 edges");
  expectError("1\n-1 2\n", "d.damage:2:");
  expectError("1\n0 1 1.5\n", "d.damage:2: where a blade crossed the edge must be a fraction");
  expectError("1\n0 1 -0.5\n", "d.damage:2: where a blade crossed the edge must be a fraction");
  expectError("1\n0 1 nan\n", "d.damage:2:");
  expectError("1\n0 1 1e999\n",
              "d.damage:2: where a blade crossed the edge is beyond the range of a double");
  expectError("1\n0 1 0.5 7\n", "d.damage:2: expected two vertex numbers and, optionally");
  EXPECT_THROW(readDamage(dir / "missing.damage", edges), InputError);
}

TEST(DamageIo, TetDamageFractionCountsDamagedEdges) {
  const std::vector<std::array<int, 6>> tetEdges = {{0, 1, 2, 3, 4, 5}, {5, 6, 7, 8, 9, 10}};
  std::vector<std::uint8_t> damaged(11, 0);
  damaged[5] = damaged[0] = damaged[10] = 1;
  const std::vector<double> f = tetDamageFraction(tetEdges, damaged);
  EXPECT_DOUBLE_EQ(f[0], 2.0 / 6.0);
  EXPECT_DOUBLE_EQ(f[1], 2.0 / 6.0);
}

}  // namespace
}  // namespace galsculpt
