#include "engine/scene/json_reader.h"

#include <gtest/gtest.h>

#include "solver/io/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

TEST(JsonReader, SyntaxErrorsGiveTheLine) {
  test::TempDir dir;
  test::writeText(dir / "a.json", "{\n  \"a\": 1,\n  \"b\": ,\n}\n");
  EXPECT_THROW_WITH(parseJsonFile(dir / "a.json"), InputError, "a.json:3: JSON syntax error");
}

TEST(JsonReader, ValuesAreCheckedWithTheirPath) {
  const nlohmann::json j =
      nlohmann::json::parse(R"({"n": 3, "s": "x", "v": [1, 2], "o": {"deep": -1}, "extra": 1})");
  JsonObject o(j, "$", "f.json");
  EXPECT_EQ(o.number("n", 0, 0, 10), 3.0);
  EXPECT_THROW_WITH(o.number("n", 0, 5, 10), InputError, "f.json: $.n: must be at least 5, got 3");
  EXPECT_THROW_WITH(o.string("s", "", {"y", "z"}), InputError,
                    "$.s: unknown value 'x' (expected one of: y, z)");
  EXPECT_THROW_WITH(o.vec3("v", Eigen::Vector3d::Zero()), InputError,
                    "$.v: expected an array of 3 numbers");
  JsonObject inner = o.object("o");
  EXPECT_THROW_WITH(inner.integer("deep", 0, 0, 5), InputError,
                    "$.o.deep: must be at least 0, got -1");
  EXPECT_THROW_WITH(o.rejectUnknownKeys(), InputError, "$.extra: unknown key");
  EXPECT_EQ(o.number("absent", 4.5, 0, 10), 4.5);
  EXPECT_THROW_WITH(o.requiredNumber("absent", 0, 1), InputError, "$.absent: is required");
}

TEST(JsonReader, AKeyGivenTwiceIsRefused) {
  test::TempDir dir;
  test::writeText(dir / "twice.json",
                  "{\n  \"gravity\": [0, -9.81, 0],\n  \"o\": {\"gravity\": 1},\n  \"gravity\": "
                  "[0, 0, 0]\n}\n");
  EXPECT_THROW_WITH(parseJsonFile(dir / "twice.json"), InputError,
                    "twice.json:4: JSON: the key \"gravity\" is given twice in one object");
  // The same key in different objects is fine.
  test::writeText(dir / "ok.json",
                  "{\"a\": {\"k\": 1}, \"b\": {\"k\": 2}, \"c\": [{\"k\": 1}, {\"k\": 2}]}");
  EXPECT_NO_THROW(parseJsonFile(dir / "ok.json"));
}

// Found by the fuzzing run: a missing key read raw threw the JSON library's bare exception.
TEST(JsonReader, AMissingKeyReadRawIsRequired) {
  const nlohmann::json j = nlohmann::json::parse(R"({"a": 1})");
  JsonObject o(j, "$.anchors[0]", "p.gsproj");
  EXPECT_THROW_WITH(o.raw("vertices"), InputError, "p.gsproj: $.anchors[0].vertices: is required");
}

TEST(JsonReader, NumbersOutOfRangeAndDeepNestingNameTheFileAndLine) {
  test::TempDir dir;
  test::writeText(dir / "big.json", "{\n  \"a\": 1,\n  \"b\": 1e999\n}\n");
  EXPECT_THROW_WITH(parseJsonFile(dir / "big.json"), InputError,
                    "big.json:3: JSON: the number '1e999' is beyond the range of a double");
  test::writeText(dir / "deep.json",
                  "{\n\"a\": " + std::string(300, '[') + std::string(300, ']') + "}");
  EXPECT_THROW_WITH(parseJsonFile(dir / "deep.json"), InputError,
                    "deep.json:2: JSON nests deeper than 256 levels");
  // Brackets inside strings do not count.
  test::writeText(dir / "text.json", "{\"a\": \"" + std::string(300, '[') + "\\\"\"}");
  EXPECT_NO_THROW(parseJsonFile(dir / "text.json"));
  // Unsigned values beyond the signed range read back as what they are, not as -1.
  const nlohmann::json j = nlohmann::json::parse(R"({"n": 18446744073709551615})");
  JsonObject o(j, "$", "f.json");
  EXPECT_THROW_WITH(o.integer("n", 0, 0, 1000), InputError,
                    "$.n: must be at most 1000, got 18446744073709551615");
}

}  // namespace
}  // namespace galsculpt
