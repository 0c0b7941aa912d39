#include "asbuilt/util/text.h"

#include <gtest/gtest.h>

namespace asbuilt {
namespace {

TEST(AsciiLower, LowersLatinLettersOnly) {
  EXPECT_EQ(AsciiLower(".PNG"), ".png");
  EXPECT_EQ(AsciiLower("Door_2 Wall"), "door_2 wall");
  EXPECT_EQ(AsciiLower("ÄÖ.EXR"), "ÄÖ.exr");  // UTF-8 bytes untouched.
  EXPECT_EQ(AsciiLower(""), "");
}

}  // namespace
}  // namespace asbuilt
