#include "solver/io/input_error.h"

#include <gtest/gtest.h>

namespace galsculpt {
namespace {

TEST(InputError, MessagesNameTheFileAndTheLine) {
  EXPECT_STREQ(InputError("a.node", 12, "expected 3 coordinates").what(),
               "a.node:12: expected 3 coordinates");
  EXPECT_STREQ(InputError("s.json", 0, "$.mesh: is required").what(),
               "s.json: $.mesh: is required");
  EXPECT_STREQ(InputError("whole message").what(), "whole message");
  EXPECT_STREQ(OutputError("cannot write out.obj").what(), "cannot write out.obj");
}

}  // namespace
}  // namespace galsculpt
