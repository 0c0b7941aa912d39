#include "asbuilt/util/stats.h"

#include <cmath>

#include <gtest/gtest.h>

namespace asbuilt {
namespace {

TEST(Median, OddEvenAndNone) {
  EXPECT_EQ(Median({3, 1, 2}), 2);
  EXPECT_EQ(Median({4, 1, 3, 2}), 2.5);
  EXPECT_EQ(Median({7}), 7);
  EXPECT_TRUE(std::isnan(Median({})));
}

TEST(UpperMedian, TheUpperOfTheTwoMiddleValues) {
  EXPECT_EQ(UpperMedian({3, 1, 2}), 2);
  EXPECT_EQ(UpperMedian({4, 1, 3, 2}), 3);
  EXPECT_TRUE(std::isnan(UpperMedian({})));
}

}  // namespace
}  // namespace asbuilt
