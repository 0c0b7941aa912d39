#include "asbuilt/stereo/disparity.h"

#include <gtest/gtest.h>

namespace asbuilt {
namespace {
TEST(DisparityOptions, DefaultsAreValid) { EXPECT_NO_THROW(DisparityOptions{}.Check()); }
}  // namespace
}  // namespace asbuilt
