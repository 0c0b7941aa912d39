#include "asbuilt/plan/room_iou.h"

#include <cmath>

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

Plan RoomPlan(std::vector<Vec2> polygon) {
  Plan plan;
  plan.rooms.push_back({.polygon = std::move(polygon)});
  return plan;
}

TEST(RoomPolygonOverlap, IdenticalRoomsHaveIouOne) {
  const Plan room = RoomPlan({{0, 0}, {4, 0}, {4, 3}, {0, 3}});
  const auto o = RoomPolygonOverlap(room, room);
  ASSERT_TRUE(o);
  EXPECT_NEAR(o->Iou(), 1.0, 1e-9);
  EXPECT_NEAR(o->truth_m2, 12.0, 1e-3);
}

TEST(RoomPolygonOverlap, ShiftedSquaresMatchTheExactAnswer) {
  // Two 2×2 squares offset by (1, 1): ∩ 1 m², ∪ 7 m².
  const auto o =
      RoomPolygonOverlap(RoomPlan({{0, 0}, {2, 0}, {2, 2}, {0, 2}}), RoomPlan({{1, 1}, {3, 1}, {3, 3}, {1, 3}}));
  ASSERT_TRUE(o);
  EXPECT_NEAR(o->intersection_m2, 1.0, 1e-3);
  EXPECT_NEAR(o->union_m2, 7.0, 1e-3);
  EXPECT_NEAR(o->Iou(), 1.0 / 7.0, 1e-4);
}

TEST(RoomPolygonOverlap, LShapedAndRotatedRoomsAreExactToTheRowStep) {
  // An L (area 3 × 3 − 2 × 2 = 5) in either orientation against its bounding square.
  const Plan l_ccw = RoomPlan({{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}});
  const Plan l_cw = RoomPlan({{0, 3}, {1, 3}, {1, 1}, {3, 1}, {3, 0}, {0, 0}});
  const Plan square = RoomPlan({{0, 0}, {3, 0}, {3, 3}, {0, 3}});
  for (const Plan* l : {&l_ccw, &l_cw}) {
    const auto o = RoomPolygonOverlap(*l, square);
    ASSERT_TRUE(o);
    EXPECT_NEAR(o->predicted_m2, 5.0, 2e-3);
    EXPECT_NEAR(o->Iou(), 5.0 / 9.0, 1e-3);
  }
  // A square turned 45° about its centre against itself upright: ∩ is the
  // regular octagon of inradius 1, area 8(√2 − 1).
  const double r = std::sqrt(2.0);
  const auto o =
      RoomPolygonOverlap(RoomPlan({{0, -r}, {r, 0}, {0, r}, {-r, 0}}), RoomPlan({{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}));
  ASSERT_TRUE(o);
  EXPECT_NEAR(o->intersection_m2, 8 * (r - 1), 2e-3);
}

TEST(RoomPolygonOverlap, NoRoomGivesNothing) {
  EXPECT_FALSE(RoomPolygonOverlap(Plan{}, RoomPlan({{0, 0}, {1, 0}, {1, 1}})));
}

// The placement's fast path gives RoomPolygonOverlap's intersection, row for row.
TEST(RoomIntersectionArea, IsRoomPolygonOverlapsIntersection) {
  const Plan l_shape = RoomPlan({{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}});
  const std::vector<Plan> others = {RoomPlan({{0.5, 0.5}, {4, 0.5}, {4, 5}, {0.5, 5}}),
                                    RoomPlan({{2.5, -1.3}, {6, -1.3}, {6, 0.4}, {2.5, 0.4}}),
                                    RoomPlan({{0, 3.1}, {2, 3.1}, {2, 4}, {0, 4}}), l_shape};
  for (double step : {0.02, 0.05}) {
    for (const Plan& other : others) {
      const auto full = RoomPolygonOverlap(l_shape, other, {.row_step_m = step});
      const auto fast = RoomIntersectionArea(l_shape, other, {.row_step_m = step});
      ASSERT_TRUE(full && fast);
      EXPECT_NEAR(*fast, full->intersection_m2, 1e-9) << step;
    }
  }
  EXPECT_FALSE(RoomIntersectionArea(Plan{}, l_shape));
}

TEST(RoomIouOptions, BadRowStepIsRefused) {
  EXPECT_THROW(RoomIouOptions{.row_step_m = 0}.Check(), InvalidArgument);
  EXPECT_NO_THROW(RoomIouOptions{}.Check());
}

TEST(RoomOverlap, PrintsItself) {
  EXPECT_EQ((RoomOverlap{.intersection_m2 = 15.0, .union_m2 = 16.0}).ToString(), "IoU 0.938 (∩ 15.00 m², ∪ 16.00 m²)");
}

}  // namespace
}  // namespace asbuilt
