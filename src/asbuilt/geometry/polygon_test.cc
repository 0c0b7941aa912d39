#include "asbuilt/geometry/polygon.h"

#include <gtest/gtest.h>

namespace asbuilt {
namespace {

TEST(PointInPolygon, AnLShapedRoomEitherWay) {
  std::vector<Vec2> l = {{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}};
  EXPECT_TRUE(PointInPolygon(l, {1, 1}));
  EXPECT_TRUE(PointInPolygon(l, {1, 3}));
  EXPECT_FALSE(PointInPolygon(l, {3, 3}));  // The notch.
  EXPECT_FALSE(PointInPolygon(l, {5, 1}));
  std::reverse(l.begin(), l.end());  // Clockwise: the same.
  EXPECT_TRUE(PointInPolygon(l, {1, 3}));
  EXPECT_FALSE(PointInPolygon(l, {3, 3}));
}

TEST(PointInPolygon, FewerThanThreePointsContainNothing) {
  EXPECT_FALSE(PointInPolygon({}, {0, 0}));
  EXPECT_FALSE(PointInPolygon({{0, 0}, {1, 1}}, {0.5, 0.5}));
}

}  // namespace
}  // namespace asbuilt
