#include "asbuilt/scene/furnish.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

Scene RoomWithDoor() {
  Scene s;
  Room r;
  r.polygon = {{0, 0}, {5, 0}, {5, 4}, {0, 4}};
  r.openings.push_back({.kind = OpeningKind::kDoor, .wall = 0, .offset_m = 2.0, .width_m = 1.0});
  s.rooms.push_back(r);
  s.turn = TurnInPlace{.position_m = {2.5, 2, 1.5}};
  return s;
}

TEST(SceneRng, IsDeterministicAndInRange) {
  SceneRng a(42), b(42);
  for (int i = 0; i < 1000; ++i) {
    double u = a.Uniform(2, 3);
    EXPECT_EQ(u, b.Uniform(2, 3));
    EXPECT_GE(u, 2);
    EXPECT_LT(u, 3);
    int k = a.UniformInt(0, 3);
    b.UniformInt(0, 3);
    EXPECT_GE(k, 0);
    EXPECT_LE(k, 3);
  }
}

TEST(FurnitureByName, KnowsPluralsAndUnknownWords) {
  ASSERT_TRUE(FurnitureByName("desks").has_value());
  EXPECT_EQ(FurnitureByName("desks")->name, "desk");
  EXPECT_EQ(FurnitureByName("bookcases")->name, "bookshelf");
  EXPECT_FALSE(FurnitureByName("giraffe").has_value());
}

TEST(PlaceFurniture, KeepsPiecesInsideClearOfDoorRigAndEachOther) {
  Scene s = RoomWithDoor();
  std::vector<FurnitureSpec> pieces(6, *FurnitureByName("cabinet"));
  pieces.push_back(*FurnitureByName("table"));
  std::vector<std::string> left = PlaceFurniture(s, 0, pieces, 7);
  EXPECT_THAT(left, ::testing::IsEmpty());
  ASSERT_EQ(s.furniture.size(), 7u);
  for (const Furniture& f : s.furniture) {
    double c = std::cos(DegToRad(f.yaw_deg)), sn = std::sin(DegToRad(f.yaw_deg));
    for (double dx : {-0.5, 0.5}) {
      for (double dy : {-0.5, 0.5}) {
        Vec2 corner = f.centre_m + Vec2(c * dx * f.size_m.x() - sn * dy * f.size_m.y(),
                                        sn * dx * f.size_m.x() + c * dy * f.size_m.y());
        EXPECT_TRUE(PointInPolygon(s.rooms[0].polygon, corner)) << f.name;
        // The door (x in [2, 3] on y = 0) keeps 1 m clear in front.
        EXPECT_FALSE(corner.x() > 1.9 && corner.x() < 3.1 && corner.y() < 1.0) << f.name;
      }
    }
    EXPECT_GT((f.centre_m - Vec2(2.5, 2)).norm(), 0.6);
  }
  EXPECT_THAT(ValidateScene(s), ::testing::IsEmpty());
}

TEST(PlaceFurniture, ReportsPiecesThatDoNotFit) {
  Scene s = RoomWithDoor();
  std::vector<FurnitureSpec> pieces(40, *FurnitureByName("wardrobe"));
  std::vector<std::string> left = PlaceFurniture(s, 0, pieces, 1);
  EXPECT_FALSE(left.empty());
  EXPECT_EQ(s.furniture.size() + left.size(), 40u);
}

TEST(PlaceInRows, LaysOutAGridClearOfTheDoorAndRig) {
  Scene s = RoomWithDoor();
  s.rooms[0].polygon = {{0, 0}, {7, 0}, {7, 9}, {0, 9}};
  s.turn->position_m = Vec3(3.5, 4.5, 1.5);
  int left = PlaceInRows(s, 0, *FurnitureByName("desk"), 12);
  EXPECT_EQ(left, 0);
  ASSERT_EQ(s.furniture.size(), 12u);
  for (const Furniture& f : s.furniture) {
    EXPECT_NEAR(f.yaw_deg, 0.0, 1e-12);
    EXPECT_GT((f.centre_m - Vec2(3.5, 4.5)).norm(), 0.6);
  }
  EXPECT_THAT(ValidateScene(s), ::testing::IsEmpty());
  EXPECT_GT(PlaceInRows(s, 0, *FurnitureByName("desk"), 100), 0);  // Reports what did not fit.
}

TEST(AddCeilingLights, SpreadsLightsUnderTheCeiling) {
  Scene s = RoomWithDoor();
  AddCeilingLights(s, 0, 4);
  ASSERT_EQ(s.lights.size(), 4u);
  for (const Light& l : s.lights) {
    EXPECT_NEAR(l.position_m.z(), 2.68, 1e-12);
    EXPECT_TRUE(PointInPolygon(s.rooms[0].polygon, l.position_m.head<2>()));
  }
  Scene auto_count = RoomWithDoor();
  AddCeilingLights(auto_count, 0);
  EXPECT_EQ(auto_count.lights.size(), 3u);  // 20 m² / 8 m² per light, rounded.
  EXPECT_THROW(AddCeilingLights(auto_count, 3), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
