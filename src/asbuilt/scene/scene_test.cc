#include "asbuilt/scene/scene.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

using ::testing::HasSubstr;

// A 6 × 8 m room (x × y), 3 m high, door on the east wall, two windows north.
Scene SmallClassroom() {
  Scene s;
  s.name = "classroom";
  Room room;
  room.polygon = {{0, 0}, {6, 0}, {6, 8}, {0, 8}};
  room.height_m = 3.0;
  room.openings.push_back({.kind = OpeningKind::kDoor, .wall = 1, .offset_m = 0.5, .width_m = 1.0});
  room.openings.push_back(
      {.kind = OpeningKind::kWindow, .wall = 2, .offset_m = 1.0, .width_m = 1.5, .height_m = 1.4, .sill_m = 0.9});
  room.openings.push_back(
      {.kind = OpeningKind::kWindow, .wall = 2, .offset_m = 3.5, .width_m = 1.5, .height_m = 1.4, .sill_m = 0.9});
  s.rooms.push_back(room);
  s.furniture.push_back({.name = "desk", .centre_m = {3, 3}});
  s.lights.push_back({});
  s.turn = TurnInPlace{.position_m = {3, 4, 1.5}, .step_deg = 30};
  return s;
}

std::vector<std::string> Messages(const std::vector<Problem>& problems) {
  std::vector<std::string> out;
  for (const Problem& p : problems) out.push_back(p.ToString());
  return out;
}

TEST(Scene, SmallClassroomIsValid) {
  EXPECT_THAT(Messages(ValidateScene(SmallClassroom())), ::testing::IsEmpty());
  EXPECT_NO_THROW(CheckScene(SmallClassroom()));
}

TEST(Scene, PrintsItself) {
  EXPECT_EQ(SmallClassroom().ToString(), "Scene(classroom: 1 rooms, 3 openings, 1 furniture, 1 lights, 12 views)");
}

TEST(Materials, BuiltinsResolveAndSceneMaterialsOverrideThem) {
  Scene s;
  for (const char* name : {"wall", "floor", "ceiling", "door", "window_frame", "glass", "furniture", "skirting"}) {
    ASSERT_NE(FindMaterial(s, name), nullptr) << name;
  }
  EXPECT_EQ(FindMaterial(s, "marble"), nullptr);
  s.materials.push_back({.name = "wall", .base_color = Vec3(1, 0, 0)});
  EXPECT_EQ(FindMaterial(s, "wall")->base_color, Vec3(1, 0, 0));
}

TEST(StereoRigSpec, UsesFovUnlessFocalLengthGiven) {
  StereoRigSpec rig{.width_px = 640, .height_px = 480, .hfov_deg = 90};
  PinholeCamera c = rig.Camera();
  EXPECT_NEAR(c.fx, 320.0, 1e-9);
  EXPECT_NEAR(c.cx, 319.5, 1e-12);
  rig.fx = 500.0;
  rig.cy = 200.0;
  c = rig.Camera();
  EXPECT_EQ(c.fx, 500.0);
  EXPECT_EQ(c.fy, 500.0);
  EXPECT_EQ(c.cx, 319.5);
  EXPECT_EQ(c.cy, 200.0);
}

TEST(ResolveViewpoints, ListsViewpointsThenAFullTurn) {
  Scene s = SmallClassroom();
  s.viewpoints.push_back({.position_m = {1, 1, 1.2}, .yaw_deg = 45});
  std::vector<Viewpoint> v = ResolveViewpoints(s);
  ASSERT_EQ(v.size(), 13u);
  EXPECT_EQ(v[0].yaw_deg, 45);
  EXPECT_EQ(v[1].position_m, Vec3(3, 4, 1.5));
  EXPECT_EQ(v[1].yaw_deg, 0);
  EXPECT_EQ(v[12].yaw_deg, 330);
  s.turn->count = 3;
  s.turn->start_deg = 10;
  v = ResolveViewpoints(s);
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v[3].yaw_deg, 70);
}

TEST(SceneTruth, WallsAreInnerFacesAndOpeningsLieOnTheirWall) {
  Plan plan = SceneTruth(SmallClassroom());
  ASSERT_EQ(plan.walls.size(), 4u);
  EXPECT_EQ(plan.walls[1].start, Vec2(6, 0));
  EXPECT_EQ(plan.walls[1].end, Vec2(6, 8));
  EXPECT_EQ(plan.walls[1].height, 3.0);
  EXPECT_EQ(plan.walls[1].thickness, 0.2);
  ASSERT_EQ(plan.openings.size(), 3u);
  const PlanOpening& door = plan.openings[0];
  EXPECT_EQ(door.kind, OpeningKind::kDoor);
  EXPECT_EQ(door.wall, 1);
  EXPECT_TRUE(door.start.isApprox(Vec2(6, 0.5)));
  EXPECT_TRUE(door.end.isApprox(Vec2(6, 1.5)));
  EXPECT_EQ(door.width, 1.0);
  EXPECT_EQ(door.sill, 0.0);
  // The north wall runs from (6, 8) to (0, 8): offsets count from x = 6.
  const PlanOpening& w = plan.openings[2];
  EXPECT_EQ(w.wall, 2);
  EXPECT_TRUE(w.start.isApprox(Vec2(2.5, 8)));
  EXPECT_TRUE(w.end.isApprox(Vec2(1.0, 8)));
  EXPECT_EQ(w.sill, 0.9);
  EXPECT_EQ(w.height, 1.4);
  ASSERT_EQ(plan.rooms.size(), 1u);
  EXPECT_DOUBLE_EQ(plan.rooms[0].area_m2, 48.0);
}

TEST(SceneTruth, NumbersWallsAcrossRooms) {
  Scene s = SmallClassroom();
  Room second;
  second.polygon = {{10, 0}, {14, 0}, {14, 3}, {10, 3}};
  second.openings.push_back({.kind = OpeningKind::kDoor, .wall = 3, .offset_m = 1.0});
  s.rooms.push_back(second);
  Plan plan = SceneTruth(s);
  ASSERT_EQ(plan.walls.size(), 8u);
  EXPECT_EQ(plan.openings.back().wall, 7);
  EXPECT_TRUE(plan.openings.back().start.isApprox(Vec2(10, 2)));
  EXPECT_DOUBLE_EQ(plan.rooms[1].area_m2, 12.0);
}

TEST(WallCompassName, NamesTheOutwardDirection) {
  Room r;
  r.polygon = {{0, 0}, {6, 0}, {6, 8}, {0, 8}};
  EXPECT_EQ(WallCompassName(r, 0), "south");
  EXPECT_EQ(WallCompassName(r, 1), "east");
  EXPECT_EQ(WallCompassName(r, 2), "north");
  EXPECT_EQ(WallCompassName(r, 3), "west");
  Room diamond;
  diamond.polygon = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
  EXPECT_EQ(WallCompassName(diamond, 0), "south-east");
  EXPECT_EQ(WallCompassName(diamond, 1), "north-east");
}

// One rule for the text parser and the MCP tools: each opening centred in one
// of equal bays.
TEST(EvenlySpacedOffsets, CentresEachOpeningInOneOfEqualBays) {
  const std::vector<double> two = {1.5, 1.5};
  const std::vector<double> offsets = EvenlySpacedOffsets(6.0, two);
  ASSERT_EQ(offsets.size(), 2u);
  EXPECT_DOUBLE_EQ(offsets[0], 0.75);  // Centre 1.5 m: a quarter of the wall.
  EXPECT_DOUBLE_EQ(offsets[1], 3.75);  // Centre 4.5 m.
  const std::vector<double> mixed = {0.9, 1.2, 2.0};
  const std::vector<double> m = EvenlySpacedOffsets(9.0, mixed);
  EXPECT_DOUBLE_EQ(m[0] + 0.45, 1.5);
  EXPECT_DOUBLE_EQ(m[1] + 0.6, 4.5);
  EXPECT_DOUBLE_EQ(m[2] + 1.0, 7.5);
  EXPECT_TRUE(EvenlySpacedOffsets(3.0, std::vector<double>{}).empty());
}

// One rule for the text parser and the MCP tools: the walls of that name,
// else the nearest (the longest of equals) within the limit.
TEST(WallFacing, NamedWallsElseTheNearestLongest) {
  Room l;
  l.polygon = {{0, 0}, {4, 0}, {4, 2.5}, {2, 2.5}, {2, 5}, {0, 5}};  // North-east corner cut out.
  EXPECT_EQ(WallsFacing(l, "north"), (std::vector<int>{2, 4}));
  EXPECT_EQ(WallFacing(l, "north"), 2);  // Both 2 m: the first.
  EXPECT_EQ(WallFacing(l, "east"), 1);   // 2.5 m against 2.5 m: the first.
  // No wall faces south-west: south (4 m) and west (5 m) are 45° off; the longer.
  EXPECT_EQ(WallsFacing(l, "south-west"), (std::vector<int>{5}));
  EXPECT_FALSE(WallFacing(l, "south-west", 30.0).has_value());
  EXPECT_FALSE(WallFacing(l, "upwards").has_value());
  EXPECT_FALSE(CompassVector("nord").has_value());
  EXPECT_TRUE(CompassVector("north-east")->isApprox(Vec2(1, 1).normalized()));
  EXPECT_EQ(CompassNames().size(), 8u);
}

TEST(PointInPolygon, HandlesAnLShape) {
  std::vector<Vec2> l = {{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}};
  EXPECT_TRUE(PointInPolygon(l, {1, 3}));
  EXPECT_TRUE(PointInPolygon(l, {3, 1}));
  EXPECT_FALSE(PointInPolygon(l, {3, 3}));
  EXPECT_FALSE(PointInPolygon(l, {-1, 1}));
  EXPECT_TRUE(PolygonCentroid({{0, 0}, {2, 0}, {2, 2}, {0, 2}}).isApprox(Vec2(1, 1)));
}

TEST(SurveySpot, StandsWhereEveryWallIsInView) {
  // A rectangle longer than wide: its centre, exactly.
  std::optional<Vec2> rect = SurveySpot({{0, 0}, {9, 0}, {9, 3}, {0, 3}});
  ASSERT_TRUE(rect);
  EXPECT_TRUE(rect->isApprox(Vec2(4.5, 1.5))) << rect->transpose();
  // An L (wings 4 m wide, 8 m long): the middle of the square where they
  // meet, the only place that sees both wings whole.
  std::optional<Vec2> l = SurveySpot({{0, 0}, {8, 0}, {8, 4}, {4, 4}, {4, 8}, {0, 8}});
  ASSERT_TRUE(l);
  EXPECT_NEAR(l->x(), 2.0, 0.05);
  EXPECT_NEAR(l->y(), 2.0, 0.05);
  // Turned and moved, the spot turns and moves with it.
  const Eigen::Rotation2Dd rot(0.4);
  std::vector<Vec2> turned;
  for (const Vec2& p : std::vector<Vec2>{{0, 0}, {8, 0}, {8, 4}, {4, 4}, {4, 8}, {0, 8}})
    turned.push_back(rot * p + Vec2(3, -1));
  std::optional<Vec2> t = SurveySpot(turned);
  ASSERT_TRUE(t);
  EXPECT_LT((*t - (rot * Vec2(2, 2) + Vec2(3, -1))).norm(), 0.08);
  // A U (two wings joined by a bar) has no spot that sees all of it.
  EXPECT_FALSE(SurveySpot({{0, 0}, {6, 0}, {6, 4}, {4, 4}, {4, 1}, {2, 1}, {2, 4}, {0, 4}}));
  EXPECT_FALSE(SurveySpot({{0, 0}, {1, 0}}));
}

TEST(ValidateScene, RejectsOpenAndSelfIntersectingPolygons) {
  Scene s = SmallClassroom();
  s.rooms[0].polygon = {{0, 0}, {6, 0}, {6, 8}, {0, 8}, {0, 0}};
  EXPECT_THAT(Messages(ValidateScene(s, "x.json")),
              ::testing::Contains(HasSubstr("x.json: rooms[0].polygon[4]: repeats the first point")));
  s.rooms[0].polygon = {{0, 0}, {6, 8}, {6, 0}, {0, 8}};  // Bow tie.
  EXPECT_THAT(Messages(ValidateScene(s)),
              ::testing::Contains("scene: rooms[0].polygon: self-intersecting: wall 0 crosses wall 2"));
  s.rooms[0].polygon = {{0, 0}, {6, 0}};
  EXPECT_THAT(Messages(ValidateScene(s)),
              ::testing::Contains("scene: rooms[0].polygon: needs at least 3 points, got 2"));
}

TEST(ValidateScene, RejectsClockwisePolygons) {
  Scene s = SmallClassroom();
  s.rooms[0].polygon = {{0, 0}, {0, 8}, {6, 8}, {6, 0}};
  EXPECT_THAT(Messages(ValidateScene(s)), ::testing::Contains(HasSubstr("rooms[0].polygon: points are clockwise")));
}

TEST(ValidateScene, RejectsOpeningsOutsideTheirWallOrOverlapping) {
  Scene s = SmallClassroom();
  s.rooms[0].openings[0].offset_m = 7.5;  // East wall is 8 m long.
  s.rooms[0].openings[2].offset_m = 2.0;  // Overlaps window 1 (1.0 … 2.5) by 0.5 m.
  auto m = Messages(ValidateScene(s));
  EXPECT_THAT(m, ::testing::Contains("scene: rooms[0].openings[0]: outside its wall: offset 7.5 + width 1 = 8.5 > "
                                     "wall 1 length 8.000"));
  EXPECT_THAT(m, ::testing::Contains("scene: rooms[0].openings[2]: overlaps openings[1] on wall 2 (by 0.500 m)"));
}

TEST(ValidateScene, RejectsOpeningsAboveTheWallAndNonPositiveSizes) {
  Scene s = SmallClassroom();
  s.rooms[0].openings[1].sill_m = 2.0;  // 2.0 + 1.4 > 3.0.
  s.rooms[0].openings[2].width_m = 0;
  s.rooms[0].openings[0].wall = 4;
  s.rooms[0].height_m = -3;
  auto m = Messages(ValidateScene(s));
  EXPECT_THAT(m, ::testing::Contains("scene: rooms[0].openings[2].width_m: must be > 0, got 0"));
  EXPECT_THAT(m, ::testing::Contains("scene: rooms[0].height_m: must be > 0, got -3"));
  EXPECT_THAT(m, ::testing::Contains("scene: rooms[0].openings[0].wall: wall index 4 out of range (room has 4 walls)"));
  s.rooms[0].height_m = 3;
  EXPECT_THAT(Messages(ValidateScene(s)),
              ::testing::Contains("scene: rooms[0].openings[1]: above the wall: sill 2 + height 1.4 = "
                                  "3.4 > room height 3"));
}

TEST(ValidateScene, RejectsUnknownMaterialsAndBadFurniture) {
  Scene s = SmallClassroom();
  s.rooms[0].wall_material = "marble";
  s.furniture[0].size_m = Vec3(1, -1, 1);
  auto m = Messages(ValidateScene(s));
  EXPECT_THAT(m, ::testing::Contains(HasSubstr("rooms[0].wall_material: unknown material \"marble\"")));
  EXPECT_THAT(m, ::testing::Contains("scene: furniture[0].size_m[1]: must be > 0, got -1"));
}

TEST(ValidateScene, RejectsARigOutsideEveryRoom) {
  Scene s = SmallClassroom();
  s.turn->position_m = Vec3(7, 4, 1.5);
  s.viewpoints.push_back({.position_m = {3, 4, 3.5}});
  auto m = Messages(ValidateScene(s));
  EXPECT_THAT(m, ::testing::Contains(HasSubstr("scene: turn.position_m: rig at [7, 4, 1.5] is outside every room")));
  EXPECT_THAT(m, ::testing::Contains(HasSubstr("scene: viewpoints[0].position_m: rig at [3, 4, 3.5] is outside")));
}

TEST(ValidateScene, RejectsBadRigAndDuplicateMaterials) {
  Scene s = SmallClassroom();
  s.rig.baseline_m = 0;
  s.rig.hfov_deg = 190;
  s.materials = {{.name = "a"}, {.name = "a", .roughness = 2}};
  auto m = Messages(ValidateScene(s));
  EXPECT_THAT(m, ::testing::Contains("scene: rig.baseline_m: must be > 0, got 0"));
  EXPECT_THAT(m, ::testing::Contains("scene: rig.hfov_deg: must be in (0, 180), got 190"));
  EXPECT_THAT(m, ::testing::Contains("scene: materials[1].name: duplicate name \"a\" (also materials[0])"));
  EXPECT_THAT(m, ::testing::Contains("scene: materials[1].roughness: must be in [0, 1], got 2"));
  EXPECT_THROW(CheckScene(s), InputError);
}

TEST(ValidateScene, AcceptsRotatedAndLShapedRooms) {
  Scene s;
  Room l;
  l.polygon = {{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}};
  l.openings.push_back({.kind = OpeningKind::kDoor, .wall = 3, .offset_m = 0.0, .width_m = 0.9});
  s.rooms.push_back(l);
  Room rotated;
  double c = std::cos(0.5), sn = std::sin(0.5);
  for (Vec2 p : {Vec2(0, 0), Vec2(3, 0), Vec2(3, 2), Vec2(0, 2)}) {
    rotated.polygon.push_back(Vec2(10 + c * p.x() - sn * p.y(), sn * p.x() + c * p.y()));
  }
  rotated.openings.push_back(
      {.kind = OpeningKind::kWindow, .wall = 0, .offset_m = 1, .width_m = 1.0, .height_m = 1.0, .sill_m = 1.0});
  s.rooms.push_back(rotated);
  s.turn = TurnInPlace{.position_m = {1, 1, 1.5}};
  EXPECT_THAT(Messages(ValidateScene(s)), ::testing::IsEmpty());
  Plan plan = SceneTruth(s);
  EXPECT_NEAR(plan.rooms[0].area_m2, 12.0, 1e-12);
  EXPECT_NEAR(plan.rooms[1].area_m2, 6.0, 1e-12);
  EXPECT_NEAR(plan.openings[1].width, 1.0, 1e-12);
  EXPECT_NEAR((plan.openings[1].end - plan.openings[1].start).norm(), 1.0, 1e-12);
}

TEST(DescribeScene, SummarisesRoomOpeningsAndViews) {
  std::string d = DescribeScene(SmallClassroom());
  EXPECT_THAT(d, HasSubstr("classroom: 6.00 × 8.00 m room (48.00 m²), 3.00 m high, 1 door, 2 windows"));
  EXPECT_THAT(d, HasSubstr("door 1.00 × 2.10 m on the east wall (wall 1)"));
  EXPECT_THAT(d, HasSubstr("window 1.50 × 1.40 m on the north wall (wall 2)"));
  EXPECT_THAT(d, HasSubstr("1 piece of furniture, 1 light, 12 views"));
}

}  // namespace
}  // namespace asbuilt
