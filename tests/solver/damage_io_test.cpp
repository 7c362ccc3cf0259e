#include "solver/damage_io.h"

#include <gtest/gtest.h>

#include "solver/input_error.h"
#include "solver/sim_model.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

TEST(DamageIo, RoundTrip) {
  test::TempDir dir;
  const SimModel model = buildSimModel(test::gridBar(2, 2, 2, 0.1), MaterialParams{});
  std::vector<std::uint8_t> damaged(model.numEdges(), 0);
  for (int e = 0; e < model.numEdges(); e += 3) damaged[e] = 1;
  writeDamage(dir / "bar.damage", model.edges, damaged);
  EXPECT_EQ(readDamage(dir / "bar.damage", model.edges), damaged);
  const std::vector<std::uint8_t> none(model.numEdges(), 0);
  writeDamage(dir / "bar.damage", model.edges, none);
  EXPECT_EQ(readDamage(dir / "bar.damage", model.edges), none);
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
