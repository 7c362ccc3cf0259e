#include "solver/io/text_lines.h"

#include <gtest/gtest.h>

#include "solver/io/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

TEST(TextLines, TokensKeepTheirLineNumbersAcrossCommentsBlankLinesAndCrlf) {
  TextLines lines("m.node", "# header\r\n\r\n4 3  0 0\r\n  1 0.5 -2e-3 7 # trailing\n\n2 x\n");
  EXPECT_EQ(lines.remaining(), 3u);
  const TextLine& a = lines.next("the header");
  EXPECT_EQ(a.number, 3);
  ASSERT_EQ(a.tokens.size(), 4u);
  EXPECT_EQ(lines.parseInt(a, 0, "a count"), 4);
  const TextLine& b = lines.next("a vertex");
  EXPECT_EQ(b.number, 4);
  ASSERT_EQ(b.tokens.size(), 4u) << "the comment is dropped";
  EXPECT_DOUBLE_EQ(lines.parseDouble(b, 2, "a coordinate"), -2e-3);
  ASSERT_NE(lines.peek(), nullptr);
  EXPECT_EQ(lines.peek()->number, 6);
  const TextLine& c = lines.next("a vertex");
  EXPECT_THROW_WITH(lines.parseInt(c, 1, "an index"), InputError,
                    "m.node:6: expected an index (an integer), got 'x'");
  EXPECT_TRUE(lines.atEnd());
  EXPECT_THROW_WITH(lines.next("a vertex"), InputError, "m.node");
  EXPECT_THROW_WITH(lines.next("a vertex"), InputError, "unexpected end of file");
}

TEST(TextLines, NumbersAreParsedStrictly) {
  TextLines lines("m.ele", "12abc 1.5e 3 nan inf 0x10 -7\n");
  const TextLine& l = lines.next("a line");
  EXPECT_THROW(lines.parseInt(l, 0, "an index"), InputError);
  EXPECT_THROW(lines.parseDouble(l, 1, "a number"), InputError);
  EXPECT_EQ(lines.parseInt(l, 2, "an index"), 3);
  EXPECT_THROW(lines.parseDouble(l, 3, "a number"), InputError) << "not finite";
  EXPECT_THROW(lines.parseDouble(l, 4, "a number"), InputError) << "not finite";
  EXPECT_THROW(lines.parseInt(l, 5, "an index"), InputError);
  EXPECT_EQ(lines.parseInt(l, 6, "an index"), -7);
}

TEST(TextLines, ACommentCharacterOfZeroKeepsHashes) {
  TextLines lines("f.txt", "a # b\n", 0);
  EXPECT_EQ(lines.next("a line").tokens.size(), 3u);
}

}  // namespace
}  // namespace galsculpt
