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

TEST(TriangulatePolygon, CoversAnLShapeWithTheRightArea) {
  std::vector<Vec2> l = {{0, 0}, {6, 0}, {6, 2.6}, {2.6, 2.6}, {2.6, 5}, {0, 5}};
  auto tris = TriangulatePolygon(l);
  ASSERT_EQ(tris.size(), 4u);
  double area = 0;
  for (const auto& t : tris) {
    Vec2 a = l[t[0]], b = l[t[1]], c = l[t[2]];
    double cross = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    EXPECT_GT(cross, 0) << "triangles keep the counter-clockwise order";
    area += 0.5 * cross;
  }
  EXPECT_NEAR(area, 6 * 2.6 + 2.6 * 2.4, 1e-9);
}

TEST(OffsetPolygonOutwards, MovesRectangleCornersDiagonally) {
  auto out = OffsetPolygonOutwards({{0, 0}, {4, 0}, {4, 3}, {0, 3}}, 0.2);
  EXPECT_NEAR(out[0].x(), -0.2, 1e-9);
  EXPECT_NEAR(out[0].y(), -0.2, 1e-9);
  EXPECT_NEAR(out[2].x(), 4.2, 1e-9);
  EXPECT_NEAR(out[2].y(), 3.2, 1e-9);
}

TEST(PolygonArea, IsSignedByTheTurn) {
  const std::vector<Vec2> ccw = {{0, 0}, {4, 0}, {4, 3}, {0, 3}};
  EXPECT_NEAR(PolygonArea(ccw), 12.0, 1e-12);
  EXPECT_NEAR(PolygonArea({ccw.rbegin(), ccw.rend()}), -12.0, 1e-12);
  EXPECT_EQ(PolygonArea({{0, 0}, {1, 1}}), 0.0);
}

TEST(PolygonCrossings, CountsCrossingEdgePairs) {
  EXPECT_EQ(PolygonCrossings({{0, 0}, {4, 0}, {4, 3}, {0, 3}}), 0);
  EXPECT_EQ(PolygonCrossings({{0, 0}, {4, 3}, {4, 0}, {0, 3}}), 1);  // A bow tie.
  EXPECT_EQ(PolygonCrossings({{0, 0}, {6, 0}, {6, 2.6}, {2.6, 2.6}, {2.6, 5}, {0, 5}}), 0);
}

}  // namespace
}  // namespace asbuilt
