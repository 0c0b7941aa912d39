#include "asbuilt/stereo/corners.h"

#include <gtest/gtest.h>

namespace asbuilt {
namespace {
TEST(CornerOptions, DefaultsAreValid) { EXPECT_NO_THROW(CornerOptions{}.Check()); }
}  // namespace
}  // namespace asbuilt
