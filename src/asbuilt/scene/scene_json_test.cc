#include "asbuilt/scene/scene_json.h"

#include <unistd.h>

#include <filesystem>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path Example(const char* name) { return fs::path(ASBUILT_SOURCE_DIR) / "examples" / name; }

std::vector<std::string> Messages(const InputError& e) {
  std::vector<std::string> out;
  for (const Problem& p : e.problems()) out.push_back(p.ToString());
  return out;
}

// Every field set away from its default, so a dropped field shows up.
Scene EverythingSet() {
  Scene s;
  s.name = "all";
  s.seed = 18446744073709551615ull;
  s.materials.push_back({.name = "brick",
                         .base_color = Vec3(0.1, 0.2, 0.3),
                         .roughness = 0.123456789,
                         .texture = TextureKind::kTiles,
                         .texture_scale_m = 0.07,
                         .secondary_color = Vec3(0.9, 0.8, 0.7)});
  Room r;
  r.name = "hall";
  r.polygon = {{0.1, 0.2}, {5.3, 0.2}, {5.3, 4.7}, {0.1, 4.7}};
  r.height_m = 2.65;
  r.wall_thickness_m = 0.31;
  r.openings.push_back({.kind = OpeningKind::kDoor,
                        .wall = 1,
                        .offset_m = 0.3,
                        .width_m = 0.85,
                        .height_m = 2.05,
                        .sill_m = 0.0,
                        .open_deg = 75.5,
                        .hinge = HingeSide::kRight,
                        .frame_width_m = 0.04,
                        .glass = false,
                        .material = "brick"});
  r.openings.push_back({.kind = OpeningKind::kWindow,
                        .wall = 2,
                        .offset_m = 1.0 / 3.0,
                        .width_m = 1.1,
                        .height_m = 1.3,
                        .sill_m = 0.95});
  r.wall_material = "brick";
  r.floor_material = "floor";
  r.ceiling_material = "wall";
  r.skirting = false;
  s.rooms.push_back(r);
  s.furniture.push_back({.name = "sofa",
                         .centre_m = {2, 2},
                         .yaw_deg = 12.5,
                         .size_m = Vec3(2, 0.9, 0.8),
                         .elevation_m = 0.01,
                         .material = "brick"});
  s.lights.push_back({.kind = LightKind::kSun,
                      .position_m = Vec3(1, 2, 3),
                      .size_m = Vec2(0.5, 0.25),
                      .color = Vec3(1, 1, 1),
                      .intensity = 3.5,
                      .azimuth_deg = 10,
                      .elevation_deg = 20});
  s.environment = {.sky = false,
                   .sky_color = Vec3(0.1, 0.1, 0.1),
                   .ground_color = Vec3(0.2, 0.2, 0.2),
                   .exterior_objects = false,
                   .ambient = 0.3};
  s.rig = {.width_px = 320,
           .height_px = 240,
           .hfov_deg = 70,
           .fx = 250.5,
           .fy = 251.5,
           .cx = 160.1,
           .cy = 119.9,
           .baseline_m = 0.065};
  s.viewpoints.push_back({.position_m = {1, 1, 1.4}, .yaw_deg = -20, .pitch_deg = 5});
  s.turn = TurnInPlace{.position_m = {2.5, 2.5, 1.5}, .start_deg = 15, .step_deg = 45, .count = 4};
  return s;
}

TEST(SceneJson, RoundTripsExactly) {
  Scene s = EverythingSet();
  ASSERT_THAT(ValidateScene(s), ::testing::IsEmpty());
  fs::path p = fs::temp_directory_path() / ("asbuilt_scene_roundtrip_" + std::to_string(::getpid()) + ".json");
  WriteScene(s, p);
  Scene back = ReadScene(p);
  EXPECT_EQ(SceneToJson(back), SceneToJson(s));
  EXPECT_EQ(back.seed, s.seed);
  EXPECT_EQ(back.rooms[0].openings[1].offset_m, 1.0 / 3.0);
  EXPECT_EQ(back.rig.fy, 251.5);
  // Second generation is byte-identical.
  fs::path p2 = fs::temp_directory_path() / ("asbuilt_scene_roundtrip2_" + std::to_string(::getpid()) + ".json");
  WriteScene(back, p2);
  EXPECT_EQ(ReadFile(p), ReadFile(p2));
}

TEST(SceneJson, ReadsTheClassroomExample) {
  Scene s = ReadScene(Example("classroom.json"));
  ASSERT_EQ(s.rooms.size(), 1u);
  Plan truth = SceneTruth(s);
  EXPECT_DOUBLE_EQ(truth.rooms[0].area_m2, 48.0);
  ASSERT_EQ(truth.openings.size(), 3u);
  EXPECT_EQ(WallCompassName(s.rooms[0], s.rooms[0].openings[0].wall), "east");
  EXPECT_EQ(WallCompassName(s.rooms[0], s.rooms[0].openings[1].wall), "north");
  EXPECT_EQ(ResolveViewpoints(s).size(), 12u);
  EXPECT_EQ(SceneToJson(SceneFromJson(SceneToJson(s), "again")), SceneToJson(s));
}

TEST(SceneJson, WindowsDefaultToAWindowSizeAndSill) {
  nlohmann::json j = {
      {"version", 1},
      {"rooms", {{{"polygon", {{0, 0}, {4, 0}, {4, 4}, {0, 4}}}, {"openings", {{{"kind", "window"}, {"wall", 0}}}}}}}};
  Scene s = SceneFromJson(j, "mini");
  EXPECT_EQ(s.rooms[0].openings[0].sill_m, 0.9);
  EXPECT_EQ(s.rooms[0].openings[0].height_m, 1.2);
  EXPECT_EQ(s.rooms[0].height_m, 2.7);
}

TEST(SceneJson, TypeErrorsNameTheFieldPath) {
  nlohmann::json j = SceneToJson(EverythingSet());
  j["rooms"][0]["openings"][1]["width_m"] = "wide";
  j["rooms"][0]["openings"][0]["kind"] = "hatch";
  j["rooms"][0]["polygon"][2] = {1};
  j["lights"][0]["kind"] = "laser";
  j["materials"][0]["texture"] = "marble";
  j.erase("version");
  try {
    SceneFromJson(j, "scene.json");
    FAIL();
  } catch (const InputError& e) {
    auto m = Messages(e);
    EXPECT_THAT(m, ::testing::Contains("scene.json: version: missing required field"));
    EXPECT_THAT(m, ::testing::Contains("scene.json: rooms[0].openings[1].width_m: expected a number, got \"wide\""));
    EXPECT_THAT(m, ::testing::Contains(
                       "scene.json: rooms[0].openings[0].kind: expected \"door\" or \"window\", got \"hatch\""));
    EXPECT_THAT(m, ::testing::Contains("scene.json: rooms[0].polygon[2]: expected 2 elements, got 1"));
    EXPECT_THAT(m, ::testing::Contains(HasSubstr("scene.json: lights[0].kind: expected \"area\"")));
    EXPECT_THAT(m, ::testing::Contains(HasSubstr("scene.json: materials[0].texture: unknown texture \"marble\"")));
  }
}

TEST(SceneJson, SemanticErrorsComeAfterTypesAreRight) {
  nlohmann::json j = SceneToJson(EverythingSet());
  j["rooms"][0]["openings"][1]["width_m"] = -1;
  try {
    SceneFromJson(j, "scene.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(Messages(e), ::testing::ElementsAre("scene.json: rooms[0].openings[1].width_m: must be > 0, got -1"));
  }
}

TEST(SceneJson, CheckSceneFileReportsBrokenJsonAndUnknownKeys) {
  fs::path p = fs::temp_directory_path() / ("asbuilt_scene_broken_" + std::to_string(::getpid()) + ".json");
  WriteFileAtomic(p, "{\"version\": 1, \"rooms\": [");
  FileReport r = CheckSceneFile(p);
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_THAT(r.errors[0].message, HasSubstr("invalid JSON at line 1"));
  nlohmann::json j = SceneToJson(EverythingSet());
  j["rooms"][0]["colour"] = "red";
  WriteFileAtomic(p, j.dump());
  r = CheckSceneFile(p);
  EXPECT_THAT(r.errors, ::testing::IsEmpty());
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0].field_path, "rooms[0].colour");
}

TEST(SceneJsonSchema, DescribesTheRequiredFields) {
  const nlohmann::json& s = SceneJsonSchema();
  EXPECT_EQ(s["$schema"], "https://json-schema.org/draft/2020-12/schema");
  EXPECT_EQ(s["required"], nlohmann::json({"version", "rooms"}));
  const nlohmann::json& opening = s["properties"]["rooms"]["items"]["properties"]["openings"]["items"];
  EXPECT_EQ(opening["required"], nlohmann::json({"kind", "wall"}));
  // Every key the writer emits is in the schema (additionalProperties is false).
  nlohmann::json j = SceneToJson(EverythingSet());
  for (auto it = j.begin(); it != j.end(); ++it) {
    EXPECT_TRUE(s["properties"].contains(it.key())) << it.key();
  }
  for (auto it = j["rooms"][0]["openings"][0].begin(); it != j["rooms"][0]["openings"][0].end(); ++it) {
    EXPECT_TRUE(opening["properties"].contains(it.key())) << it.key();
  }
}

}  // namespace
}  // namespace asbuilt
