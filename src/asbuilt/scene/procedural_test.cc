#include "asbuilt/scene/procedural.h"

#include <unistd.h>

#include <filesystem>
#include <set>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "asbuilt/scene/scene_json.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

TEST(RandomSceneOptions, DefaultsAreValidAndBadOnesThrow) {
  EXPECT_NO_THROW(RandomSceneOptions{}.Check());
  EXPECT_THROW(RandomSceneOptions{.max_side_m = 2.0}.Check(), InvalidArgument);
  EXPECT_THROW(RandomSceneOptions{.min_openings = 0}.Check(), InvalidArgument);
  EXPECT_THROW(RandomSceneOptions{.l_shape_probability = 1.5}.Check(), InvalidArgument);
}

TEST(RandomScene, IsAlwaysValid) {
  for (std::uint64_t seed = 0; seed < 400; ++seed) {
    Scene s = RandomScene({}, seed);
    ASSERT_THAT(ValidateScene(s), ::testing::IsEmpty()) << "seed " << seed;
    ASSERT_GE(s.rooms[0].openings.size(), 1u) << "seed " << seed;
    ASSERT_LE(s.rooms[0].openings.size(), 4u) << "seed " << seed;
    EXPECT_EQ(s.rooms[0].openings[0].kind, OpeningKind::kDoor) << "seed " << seed;
  }
}

TEST(RandomScene, IsDeterministicPerSeed) {
  for (std::uint64_t seed : {0ull, 1ull, 77ull, 123456789ull}) {
    EXPECT_EQ(SceneToJson(RandomScene({}, seed)), SceneToJson(RandomScene({}, seed)));
  }
  EXPECT_NE(SceneToJson(RandomScene({}, 1)), SceneToJson(RandomScene({}, 2)));
}

TEST(RandomScene, CoversTheVarietyTheDatasetNeeds) {
  int l_shaped = 0, rotated = 0, shared_wall = 0, corner_door = 0, against_wall = 0, sun = 0, windows = 0;
  const int n = 200;
  for (std::uint64_t seed = 0; seed < n; ++seed) {
    Scene s = RandomScene({}, seed);
    const Room& r = s.rooms[0];
    l_shaped += r.polygon.size() == 6;
    Vec2 d = WallEnd(r, 0) - WallStart(r, 0);
    rotated += std::abs(d.x()) > 1e-9 && std::abs(d.y()) > 1e-9;
    std::set<int> walls;
    bool shared = false;
    for (const Opening& o : r.openings) {
      shared = shared || !walls.insert(o.wall).second;
      windows += o.kind == OpeningKind::kWindow;
      double length = WallLength(r, o.wall);
      if (o.kind == OpeningKind::kDoor && (o.offset_m < 0.16 || o.offset_m + o.width_m > length - 0.16)) {
        ++corner_door;
      }
    }
    shared_wall += shared;
    // A piece whose back is within 5 cm of a wall occludes it.
    bool wall_piece = false;
    for (const Furniture& f : s.furniture) {
      for (int w = 0; w < WallCount(r); ++w) {
        Vec2 a = WallStart(r, w), b = WallEnd(r, w);
        Vec2 dir = (b - a).normalized();
        Vec2 inward(-dir.y(), dir.x());
        double dist = (f.centre_m - a).dot(inward);
        wall_piece = wall_piece || std::abs(dist - 0.5 * f.size_m.y() - 0.02) < 0.05;
      }
    }
    against_wall += wall_piece;
    for (const Light& l : s.lights) sun += l.kind == LightKind::kSun;
  }
  EXPECT_GT(l_shaped, n / 8);
  EXPECT_GT(rotated, n / 8);
  EXPECT_GT(shared_wall, n / 10);
  EXPECT_GT(corner_door, n / 10);
  EXPECT_GT(against_wall, n / 2);
  EXPECT_GT(sun, n / 3);
  EXPECT_GT(windows, n / 2);
}

TEST(RandomScene, SurveyRigStandsWhereItSeesEveryWall) {
  for (std::uint64_t seed = 0; seed < 60; ++seed) {
    const Scene random = RandomScene({}, seed);
    const Scene survey = RandomScene({.rig_spot = RigSpot::kSurvey}, seed);
    ASSERT_THAT(ValidateScene(survey), ::testing::IsEmpty()) << "seed " << seed;
    // The same room, openings and pieces; only the rig (and where the
    // furniture keeps clear of it) differs.
    EXPECT_EQ(survey.rooms[0].polygon, random.rooms[0].polygon) << "seed " << seed;
    EXPECT_EQ(survey.rooms[0].openings.size(), random.rooms[0].openings.size()) << "seed " << seed;
    EXPECT_EQ(survey.lights.size(), random.lights.size()) << "seed " << seed;
    const Vec2 spot = survey.turn->position_m.head<2>();
    EXPECT_TRUE(spot.isApprox(*SurveySpot(survey.rooms[0].polygon))) << "seed " << seed;
    // In view of every wall: on the inner side of every wall's line.
    const Room& r = survey.rooms[0];
    for (int w = 0; w < WallCount(r); ++w) {
      EXPECT_GT(-WallOutwardNormal(r, w).dot(spot - WallStart(r, w)), 0.5) << "seed " << seed << " wall " << w;
    }
  }
  EXPECT_EQ(ParseRigSpot("survey"), RigSpot::kSurvey);
  EXPECT_STREQ(RigSpotName(ParseRigSpot("random")), "random");
  EXPECT_THROW(ParseRigSpot("middle"), InvalidArgument);
}

TEST(WriteRandomScenes, WritesOneValidFilePerSeed) {
  fs::path dir = fs::temp_directory_path() / ("asbuilt_random_scenes_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  int calls = 0;
  RandomScenesSummary s = WriteRandomScenes({}, 10, 5, dir, [&](const ProgressUpdate&) { ++calls; });
  EXPECT_EQ(s.written, 5);
  EXPECT_EQ(calls, 5);
  EXPECT_EQ(s.rectangular + s.l_shaped, 5);
  EXPECT_THAT(s.BriefReport(), ::testing::StartsWith("5 scenes in "));
  Scene third = ReadScene(dir / "scene_0002.json");
  EXPECT_EQ(SceneToJson(third), SceneToJson(RandomScene({}, 12)));
  EXPECT_THROW(WriteRandomScenes({}, 0, 0, dir), InvalidArgument);
}

RandomSceneOptions AllLevers() {
  RandomSceneOptions o;
  o.styled_door_probability = 1.0;
  o.open_door_probability = 0.5;
  o.neutral_wall_probability = 1.0;
  o.window_sun_probability = 1.0;
  o.kitchen_probability = 1.0;
  o.wall_details_probability = 1.0;
  o.window_dressing_probability = 1.0;
  o.glazed_door_probability = 0.5;
  o.ceiling_like_walls_probability = 0.5;
  o.wall_art_probability = 1.0;
  return o;
}

TEST(RandomScene, LeversAddToTheSameRoomAndStayValid) {
  std::set<std::string> added;
  int suns_through_windows = 0;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    Scene plain = RandomScene({}, seed);
    Scene levered;
    ASSERT_NO_THROW(levered = RandomScene(AllLevers(), seed)) << "seed " << seed;
    EXPECT_TRUE(ValidateScene(levered).empty()) << "seed " << seed;
    const Room &a = plain.rooms[0], &b = levered.rooms[0];
    ASSERT_EQ(a.polygon, b.polygon) << "seed " << seed;
    ASSERT_EQ(a.openings.size(), b.openings.size());
    for (std::size_t k = 0; k < a.openings.size(); ++k) {
      if (b.openings[k].glazed) {  // A patio door may be wider and taller, never narrower.
        EXPECT_GE(b.openings[k].width_m, a.openings[k].width_m);
        EXPECT_GE(b.openings[k].height_m, a.openings[k].height_m);
        continue;
      }
      EXPECT_EQ(a.openings[k].offset_m, b.openings[k].offset_m);
      EXPECT_EQ(a.openings[k].width_m, b.openings[k].width_m);
      EXPECT_EQ(a.openings[k].height_m, b.openings[k].height_m);
    }
    ASSERT_GE(levered.furniture.size(), plain.furniture.size());
    for (std::size_t k = 0; k < plain.furniture.size(); ++k) {
      EXPECT_EQ(plain.furniture[k].centre_m, levered.furniture[k].centre_m) << "seed " << seed;
    }
    for (std::size_t k = plain.furniture.size(); k < levered.furniture.size(); ++k) {
      added.insert(levered.furniture[k].name);
    }
    for (const Light& l : levered.lights) suns_through_windows += l.kind == LightKind::kSun && l.intensity >= 2.0;
    for (const Opening& o : b.openings) {
      if (o.kind == OpeningKind::kDoor) {
        EXPECT_THAT(o.material, testing::AnyOf("door_white", "door_wood", "door_frame_dark"));
      }
    }
  }
  for (const char* name : {"kitchen units", "worktop", "wall units", "fridge", "radiator", "socket", "switch",
                           "curtain", "blind", "sink", "tap", "picture", "picture frame", "mirror", "tv"}) {
    EXPECT_TRUE(added.contains(name)) << name;
  }
  EXPECT_GT(suns_through_windows, 10);
}

TEST(RandomScene, GlassDoorsCeilingsLikeWallsAndWallArtDoWhatTheySay) {
  RandomSceneOptions o;
  o.glazed_door_probability = 1.0;
  o.ceiling_like_walls_probability = 1.0;
  o.wall_art_probability = 1.0;
  int doors = 0, widened = 0, art = 0;
  for (std::uint64_t seed = 0; seed < 30; ++seed) {
    Scene plain = RandomScene({}, seed), scene = RandomScene(o, seed);
    EXPECT_TRUE(ValidateScene(scene).empty()) << "seed " << seed;
    const Room& room = scene.rooms[0];
    for (std::size_t k = 0; k < room.openings.size(); ++k) {
      const Opening& op = room.openings[k];
      EXPECT_EQ(op.glazed, op.kind == OpeningKind::kDoor) << "seed " << seed;  // Every door, no window.
      doors += op.kind == OpeningKind::kDoor;
      widened += op.width_m > plain.rooms[0].openings[k].width_m;
      if (op.glazed && op.width_m > plain.rooms[0].openings[k].width_m) {
        EXPECT_GE(op.width_m, 1.4);
      }
    }
    // The ceiling is the walls' own material (same paint, same photo).
    EXPECT_EQ(room.ceiling_material, room.wall_material);
    EXPECT_GE(scene.environment.ambient, 0.15);
    // Art hangs on the walls (its back within 1 cm of a wall face), above the floor, clear of openings.
    for (const Furniture& f : scene.furniture) {
      if (f.name != "picture" && f.name != "mirror" && f.name != "tv") continue;
      ++art;
      EXPECT_GE(f.elevation_m, 0.9);
      double nearest = 1e9;
      for (int w = 0; w < WallCount(room); ++w) {
        Vec2 a = WallStart(room, w), d = (WallEnd(room, w) - a).normalized();
        Vec2 r = f.centre_m - a;
        double along = r.dot(d);
        if (along < 0 || along > WallLength(room, w)) continue;
        nearest = std::min(nearest, std::abs(r.dot(Vec2(-d.y(), d.x())) - 0.5 * f.size_m.y()));
      }
      EXPECT_LT(nearest, 0.011) << f.name << " seed " << seed;
    }
  }
  EXPECT_GT(doors, 30);
  EXPECT_GT(widened, 5);  // Patio doors.
  EXPECT_GT(art, 30);
}

TEST(RandomScene, LeversOffLeaveTheSceneAsItWas) {
  RandomSceneOptions off;  // Every lever at its default, 0.
  EXPECT_EQ(off.kitchen_probability, 0.0);
  Scene scene = RandomScene(off, 7);
  for (const Furniture& f : scene.furniture) {
    EXPECT_THAT(f.name, testing::Not(testing::AnyOf("kitchen units", "socket", "curtain", "radiator")));
  }
  for (const Material& m : scene.materials)
    EXPECT_THAT(m.name, testing::AnyOf("wall", "floor", "ceiling", "furniture"));
  RandomSceneOptions bad;
  bad.kitchen_probability = 1.5;
  EXPECT_THROW(bad.Check(), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
