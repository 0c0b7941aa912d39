#include "asbuilt/home/placement.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "asbuilt/home/home_plan.h"
#include "asbuilt/home/synthetic_home.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

using Pose = Eigen::Isometry2d;

struct Door {
  int room, wall;
  double offset, width;
};

// A small home in its own frame: a hall with four rooms off it, 0.10 m
// partitions, a door from each room into the hall and one between the two
// east rooms (a loop, so the partition thickness is measured).
struct TestHome {
  std::vector<std::string> names = {"hall", "east", "northeast", "kitchen", "bath"};
  std::vector<std::vector<Vec2>> outlines = {
      {{0, 0}, {1.5, 0}, {1.5, 6}, {0, 6}},
      {{1.6, 0}, {5.6, 0}, {5.6, 3}, {1.6, 3}},
      {{1.6, 3.1}, {5.6, 3.1}, {5.6, 6}, {1.6, 6}},
      {{-4.1, 0}, {-0.1, 0}, {-0.1, 4}, {-4.1, 4}},
      {{-2.6, 4.1}, {-0.1, 4.1}, {-0.1, 6}, {-2.6, 6}},
  };
  // Walls run counter-clockwise from vertex k to k + 1; offsets from the wall's start.
  std::vector<Door> doors = {
      {0, 1, 1.0, 0.80}, {1, 3, 1.2, 0.80},  // hall east wall y 1.0–1.8 = east's west wall (from (1.6,3) down).
      {0, 1, 4.0, 0.80}, {2, 3, 1.2, 0.80},  // hall y 4.0–4.8 = northeast's west wall (from (1.6,6) down).
      {0, 3, 3.2, 0.80}, {3, 1, 2.0, 0.80},  // hall west wall y 2.8–2.0 = kitchen east wall y 2.0–2.8.
      {0, 3, 0.3, 0.70}, {4, 1, 0.9, 0.70},  // hall y 5.7–5.0 = bath east wall y 5.0–5.7.
      {1, 2, 0.8, 0.80}, {2, 0, 2.4, 0.80},  // east's north wall x 4.8–4.0 = northeast's south wall x 4.0–4.8.
  };
  double thickness = 0.10;

  Plan RoomPlan(int r) const {
    Plan p;
    const auto& o = outlines[r];
    for (std::size_t k = 0; k < o.size(); ++k) p.walls.push_back({.start = o[k], .end = o[(k + 1) % o.size()]});
    for (const Door& d : doors) {
      if (d.room != r) continue;
      const PlanWall& w = p.walls[d.wall];
      const Vec2 dir = (w.end - w.start).normalized();
      p.openings.push_back({.kind = OpeningKind::kDoor,
                            .wall = d.wall,
                            .start = w.start + d.offset * dir,
                            .end = w.start + (d.offset + d.width) * dir,
                            .width = d.width,
                            .height = 2.0});
    }
    p.rooms.push_back({.polygon = o, .area_m2 = std::abs(PolygonArea(o))});
    return p;
  }
};

Plan Moved(Plan p, const Pose& t) {
  for (PlanWall& w : p.walls) {
    w.start = t * w.start;
    w.end = t * w.end;
  }
  for (PlanOpening& o : p.openings) {
    o.start = t * o.start;
    o.end = t * o.end;
  }
  for (PlanRoom& r : p.rooms) {
    for (Vec2& q : r.polygon) q = t * q;
  }
  return p;
}

Pose RandomPose(std::mt19937& rng) {
  std::uniform_real_distribution<double> yaw(-std::numbers::pi, std::numbers::pi), shift(-5, 5);
  Pose t = Pose::Identity();
  t.linear() = Eigen::Rotation2Dd(yaw(rng)).toRotationMatrix();
  t.translation() = Vec2(shift(rng), shift(rng));
  return t;
}

// Each room as its own survey sees it: in a frame of its own.
struct Surveyed {
  std::vector<HomeRoomInput> rooms;
  std::vector<Pose> truth;  // floor_from_room
  std::vector<std::vector<Vec2>> outlines;
};
Surveyed Survey(const TestHome& home, unsigned seed) {
  std::mt19937 rng(seed);
  Surveyed s;
  for (std::size_t r = 0; r < home.names.size(); ++r) {
    const Pose floor_from_room = RandomPose(rng);
    s.rooms.push_back(
        {.name = home.names[r], .plan = Moved(home.RoomPlan(static_cast<int>(r)), floor_from_room.inverse())});
    s.truth.push_back(floor_from_room);
    s.outlines.push_back(home.outlines[r]);
  }
  return s;
}

TEST(PlaceRooms, PlacesEveryRoomOfASmallHomeAndMeasuresThePartition) {
  const TestHome home;
  for (unsigned seed : {1u, 2u, 3u}) {
    const Surveyed s = Survey(home, seed);
    const PlacementResult result = PlaceRooms(s.rooms);
    ASSERT_EQ(result.best.Placed(), 5) << result.best.ToString(s.rooms);
    const HomeScore score = ScoreHome(s.rooms, result.best, s.truth, s.outlines,
                                      HomeScoreOptions{.position_tolerance_m = 0.01, .yaw_tolerance_deg = 0.1});
    EXPECT_EQ(score.within, 5) << result.best.ToString(s.rooms);
    EXPECT_GT(score.floor_iou, 0.99);
    EXPECT_EQ(result.best.loops, 1);
    EXPECT_NEAR(result.best.wall_thickness_m, home.thickness, 0.02);
    EXPECT_LT(result.seconds, 10.0);  // Not a timing target (bench/): only that it ends.
    // The first room is the home frame.
    EXPECT_TRUE(result.best.rooms[0].floor_from_room.isApprox(Pose::Identity(), 1e-9));
  }
}

TEST(PlaceRooms, KeepsOtherPlacementsToPickFrom) {
  const Surveyed s = Survey(TestHome{}, 4);
  const PlacementResult result = PlaceRooms(s.rooms);
  ASSERT_FALSE(result.alternatives.empty());
  EXPECT_LE(result.alternatives.front().score, result.best.score);
}

TEST(PlaceRooms, APersonsLinksWin) {
  const Surveyed s = Survey(TestHome{}, 5);
  // "The kitchen's door is not the hall's west door": it is then placed by
  // another door, or not at all; never by that one.
  PlacementConstraints no;
  no.different.push_back({{0, 2}, {3, 0}});
  const PlacementResult without = PlaceRooms(s.rooms, {}, no);
  for (const RoomLink& l : without.best.links) {
    EXPECT_FALSE((l.a == OpeningRef{0, 2} && l.b == OpeningRef{3, 0}) ||
                 (l.a == OpeningRef{3, 0} && l.b == OpeningRef{0, 2}));
  }
  // "The bath's door is the hall's west door": the bath is placed there.
  PlacementConstraints yes;
  yes.same.push_back({{0, 2}, {4, 0}});
  const PlacementResult forced = PlaceRooms(s.rooms, {}, yes);
  ASSERT_TRUE(forced.best.rooms[4].placed);
  EXPECT_NE(forced.best.rooms[4].placed_by.find("(by hand)"), std::string::npos);
  // "The kitchen is here": it stays where it was put, the others around it.
  const Eigen::Isometry2d kitchen = s.truth[0].inverse() * s.truth[3];
  PlacementConstraints held;
  held.fixed.push_back({3, TransformPose(kitchen)});
  const PlacementResult moved = PlaceRooms(s.rooms, {}, held);
  EXPECT_TRUE(moved.best.rooms[3].floor_from_room.isApprox(kitchen, 1e-9));
  EXPECT_EQ(moved.best.rooms[3].placed_by, "moved by hand");
  EXPECT_EQ(moved.best.Placed(), 5);
  EXPECT_THROW(PlaceRooms(s.rooms, {}, PlacementConstraints{.fixed = {{3, {}}, {3, {}}}}), InvalidArgument);
  EXPECT_THROW(PlaceRooms(s.rooms, {}, PlacementConstraints{.same = {{{0, 0}, {0, 1}}}}), InvalidArgument);
  EXPECT_THROW(PlaceRooms(s.rooms, {}, PlacementConstraints{.same = {{{0, 9}, {1, 0}}}}), InvalidArgument);
}

// The hall is the room the home grows from. A person who drags it away
// moves the hall; the east rooms, which hang together by their own door,
// stay where they were (before the fix the whole home followed the hall).
TEST(PlaceRooms, MovingTheFirstRoomMovesThatRoomNotTheHome) {
  const Surveyed s = Survey(TestHome{}, 6);
  const PlacementResult before = PlaceRooms(s.rooms);
  ASSERT_EQ(before.best.Placed(), 5);
  PlacementConstraints c;
  for (const RoomPlacement& p : before.best.rooms) c.previous.push_back(TransformPose(p.floor_from_room));
  Pose hall = before.best.rooms[0].floor_from_room;
  hall.translation() += Vec2(20, 0);
  c.fixed.push_back({0, TransformPose(hall)});
  const PlacementResult after = PlaceRooms(s.rooms, {}, c);
  EXPECT_TRUE(after.best.rooms[0].floor_from_room.isApprox(hall, 1e-9));
  for (int r : {1, 2}) {
    ASSERT_TRUE(after.best.rooms[r].placed) << s.rooms[r].name;
    const Pose moved = before.best.rooms[r].floor_from_room.inverse() * after.best.rooms[r].floor_from_room;
    EXPECT_LT(moved.translation().norm(), 0.02) << s.rooms[r].name << ": " << after.best.rooms[r].placed_by;
  }
}

TEST(PlaceRooms, ARoomWithoutADoorIsNotGuessedUnlessHinted) {
  Surveyed s = Survey(TestHome{}, 6);
  HomeRoomInput store{.name = "store", .plan = TestHome{}.RoomPlan(0)};
  store.plan.openings.clear();
  s.rooms.push_back(store);
  PlacementResult result = PlaceRooms(s.rooms);
  EXPECT_EQ(result.best.Placed(), 5);
  EXPECT_FALSE(result.best.rooms[5].placed);
  EXPECT_EQ(result.best.rooms[5].placed_by, "not placed: no door seen");
  const Plan plan = HomePlan(s.rooms, result.best);
  ASSERT_EQ(plan.rooms.size(), 6u);
  EXPECT_FALSE(plan.rooms[5].pose.has_value());
  EXPECT_EQ(plan.verdict->verdict, "check");
  // Drawn beside the plan: right of every placed room.
  double placed_max_x = -1e9, beside_min_x = 1e9;
  for (std::size_t r = 0; r < 5; ++r) {
    for (const Vec2& p : plan.rooms[r].polygon) placed_max_x = std::max(placed_max_x, p.x());
  }
  for (const Vec2& p : plan.rooms[5].polygon) beside_min_x = std::min(beside_min_x, p.x());
  EXPECT_GT(beside_min_x, placed_max_x + 0.5);
  // With hints for it and the hall (the first room), it is placed by its hint.
  s.rooms[0].hint = PlanPose{{10, 0}, 0};
  s.rooms[5].hint = PlanPose{{3, 3}, 90};
  result = PlaceRooms(s.rooms);
  ASSERT_TRUE(result.best.rooms[5].placed);
  EXPECT_EQ(result.best.rooms[5].placed_by, "hint");
  EXPECT_TRUE(result.best.rooms[0].floor_from_room.isApprox(PoseTransform(*s.rooms[0].hint), 1e-9));
  EXPECT_NEAR(result.best.rooms[5].floor_from_room.translation().x(), 3, 1e-9);
  EXPECT_NEAR(YawOf(result.best.rooms[5].floor_from_room), std::numbers::pi / 2, 1e-9);
}

TEST(PlaceRooms, OneRoomIsAOneRoomHome) {
  const Surveyed s = Survey(TestHome{}, 7);
  const std::vector<HomeRoomInput> one = {s.rooms[1]};
  const PlacementResult result = PlaceRooms(one);
  ASSERT_EQ(result.best.Placed(), 1);
  EXPECT_EQ(result.best.rooms[0].placed_by, "first room");
  EXPECT_THROW(PlaceRooms({}), InvalidArgument);
}

TEST(HomePlan, MergesPartitionsAndWritesEachDoorOnce) {
  const TestHome home;
  const Surveyed s = Survey(home, 8);
  const PlacementResult result = PlaceRooms(s.rooms);
  ASSERT_EQ(result.best.Placed(), 5);
  const Plan plan = HomePlan(s.rooms, result.best);
  ASSERT_EQ(plan.rooms.size(), 5u);
  EXPECT_EQ(*plan.rooms[3].name, "kitchen");
  ASSERT_TRUE(plan.rooms[3].pose.has_value());
  EXPECT_NE(plan.rooms[3].placed_by->find("door"), std::string::npos);
  // Ten door faces, five doors: each once, naming its two rooms.
  ASSERT_EQ(plan.openings.size(), 5u);
  for (const PlanOpening& o : plan.openings) {
    ASSERT_TRUE(o.rooms.has_value());
    EXPECT_NE(o.rooms->first, o.rooms->second);
    ASSERT_GE(o.wall, 0);
    ASSERT_LT(o.wall, static_cast<int>(plan.walls.size()));
  }
  // 20 faces; the partitions whose shorter face the longer covers are one
  // wall each, with the measured thickness.
  EXPECT_LT(plan.walls.size(), 20u);
  int partitions = 0;
  for (const PlanWall& w : plan.walls) {
    if (!w.thickness) continue;
    ++partitions;
    EXPECT_NEAR(*w.thickness, home.thickness, 0.02);
  }
  EXPECT_GE(partitions, 4);
  // plan.json keeps names, poses, links.
  const Plan back = PlanFromJson(PlanToJson(plan), "home plan.json");
  ASSERT_EQ(back.rooms.size(), 5u);
  EXPECT_EQ(*back.rooms[0].name, "hall");
  EXPECT_NEAR(back.rooms[3].pose->yaw_deg, plan.rooms[3].pose->yaw_deg, 1e-9);
  EXPECT_EQ(back.openings[0].rooms, plan.openings[0].rooms);
}

}  // namespace
}  // namespace asbuilt

namespace asbuilt {
namespace {

// Random homes (home/synthetic_home.h): the share of rooms placed within
// 10 cm and 1°, with doors measured to 1 cm, and with a tenth of the door
// faces missed by the rooms' surveys.
double ShareWithin(const SyntheticHomeOptions& o, int homes, double* iou_min = nullptr) {
  int within = 0, rooms = 0;
  double worst = 1.0;
  for (int seed = 1; seed <= homes; ++seed) {
    const SyntheticHome home = MakeSyntheticHome(static_cast<unsigned>(seed), o);
    const PlacementResult result = PlaceRooms(home.rooms);
    const HomeScore score = ScoreHome(home.rooms, result.best, home.floor_from_room, home.outlines);
    within += score.within;
    rooms += score.rooms;
    worst = std::min(worst, score.floor_iou);
    if (std::getenv("ASBUILT_HOME_TEST_VERBOSE")) {
      std::fprintf(stderr, "home %d: %s, %d doors\n%s\n", seed, score.ToString().c_str(), home.doors,
                   result.best.ToString(home.rooms).c_str());
      if (std::getenv("ASBUILT_HOME_TEST_VERBOSE")[0] == '2' && score.within < score.rooms) {
        std::vector<Eigen::Isometry2d> found;
        std::vector<char> all(home.rooms.size(), 1), placed;
        for (const RoomPlacement& p : result.best.rooms) {
          found.push_back(p.floor_from_room);
          placed.push_back(p.placed);
        }
        std::vector<std::string> dt, df;
        std::fprintf(stderr, "truth %.2f\n", FitScore(home.rooms, home.floor_from_room, all, {}, &dt));
        for (auto& l : dt) std::fprintf(stderr, "   %s\n", l.c_str());
        std::fprintf(stderr, "found %.2f\n", FitScore(home.rooms, found, placed, {}, &df));
        for (auto& l : df) std::fprintf(stderr, "   %s\n", l.c_str());
      }
    }
  }
  if (iou_min) *iou_min = worst;
  return static_cast<double>(within) / rooms;
}

// Floors a little under today's figures on these 10 homes, among those the
// weights were chosen on (docs/home.md; held-out homes: bench_home), so that
// a change that places fewer rooms is seen.
TEST(PlaceRooms, PlacesMostRoomsOfRandomHomes) {
  double worst = 0;
  const double exact = ShareWithin({}, 10, &worst);
  EXPECT_GE(exact, 0.97);
  const double missed = ShareWithin({.missed_door = 0.1}, 10, &worst);
  EXPECT_GE(missed, 0.85);
}

// Home 20 with a fifth of the door faces missed: the search links a door
// whose other side was missed to another door that fits, and two rooms
// follow it; cutting that link and joining the part beyond it back by a
// one-sided link puts every room right.
TEST(PlaceRooms, SwappingALinkUndoesADoorLinkedWrongWhereItsOtherSideWasMissed) {
  const SyntheticHome home = MakeSyntheticHome(20, {.missed_door = 0.2});
  const HomeScore before =
      ScoreHome(home.rooms, PlaceRooms(home.rooms, {.improve = 0}).best, home.floor_from_room, home.outlines);
  ASSERT_LT(before.within, before.rooms);  // What the swaps are there to mend.
  const PlacementResult result = PlaceRooms(home.rooms);
  const HomeScore after = ScoreHome(home.rooms, result.best, home.floor_from_room, home.outlines);
  EXPECT_EQ(after.within, after.rooms) << result.best.ToString(home.rooms);
  EXPECT_GT(after.floor_iou, 0.95);
  // Every room is reached from the first by the links, each placed by one.
  for (std::size_t r = 1; r < result.best.rooms.size(); ++r) {
    const RoomPlacement& p = result.best.rooms[r];
    ASSERT_GE(p.link, 0) << p.placed_by;
    const RoomLink& l = result.best.links[static_cast<std::size_t>(p.link)];
    EXPECT_EQ(l.b.room, static_cast<int>(r)) << p.placed_by;
  }
}

}  // namespace
}  // namespace asbuilt
