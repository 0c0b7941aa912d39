#include "asbuilt/formats/plan_file.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

Plan RectangleWithDoor() {
  Plan plan;
  std::vector<Vec2> corners = {{0, 0}, {6, 0}, {6, 8}, {0, 8}};
  for (int i = 0; i < 4; ++i) {
    plan.walls.push_back({.start = corners[i], .end = corners[(i + 1) % 4], .thickness = 0.2, .height = 3.0});
  }
  plan.openings.push_back({.kind = OpeningKind::kDoor,
                           .wall = 1,
                           .start = {6, 3.5},
                           .end = {6, 4.5},
                           .width = 1.0,
                           .height = 2.1,
                           .sill = 0.0,
                           .width_sigma_m = 0.01});
  plan.rooms.push_back({.polygon = corners, .area_m2 = 48.0});
  return plan;
}

TEST(PlanFile, RoundTripsExactly) {
  fs::path p = fs::temp_directory_path() / "asbuilt_plan_roundtrip.json";
  Plan plan = RectangleWithDoor();
  WritePlan(plan, p);
  Plan back = ReadPlan(p);
  EXPECT_EQ(PlanToJson(plan), PlanToJson(back));
  EXPECT_EQ(back.ToString(), "Plan(4 walls, 1 openings, 1 rooms, 48.00 m²)");
}

TEST(PlanFile, ReadsBlenderRoomsTruth) {
  fs::path p = fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public/p02_L_shape/truth.json";
  if (!fs::exists(p)) GTEST_SKIP() << "shared data not present: " << p;
  Plan plan = ReadPlan(p);
  EXPECT_EQ(plan.walls.size(), 6u);
  ASSERT_EQ(plan.rooms.size(), 1u);
  EXPECT_NEAR(PolygonArea(plan.rooms[0].polygon), 21.84, 1e-6);
  EXPECT_NEAR(plan.rooms[0].area_m2, 21.84, 1e-6);
}

TEST(PlanFile, RejectsBadFieldsWithPaths) {
  nlohmann::json j = PlanToJson(RectangleWithDoor());
  j["openings"][0]["wall"] = 7;
  j["openings"][0]["kind"] = "hatch";
  j["walls"][2]["thickness"] = -0.2;
  try {
    PlanFromJson(j, "truth.json");
    FAIL();
  } catch (const InputError& e) {
    ASSERT_EQ(e.problems().size(), 3u);
    EXPECT_EQ(e.problems()[0].ToString(), "truth.json: walls[2].thickness: must be > 0, got -0.2");
    EXPECT_EQ(e.problems()[1].ToString(),
              "truth.json: openings[0].kind: expected \"door\" or \"window\", got \"hatch\"");
    EXPECT_EQ(e.problems()[2].ToString(), "truth.json: openings[0].wall: wall index 7 out of range (plan has 4 walls)");
  }
}

TEST(PlanFile, CarriesTheVerdictAndRejectsUnknownWords) {
  Plan plan = RectangleWithDoor();
  plan.verdict = PlanVerdictNote{.verdict = "check", .confidence = 0.62, .reasons = {"wall 2 seen along 30 %"}};
  plan.walls[2].verdict = "unreliable";
  const Plan back = PlanFromJson(PlanToJson(plan), "plan.json");
  ASSERT_TRUE(back.verdict);
  EXPECT_EQ(back.verdict->verdict, "check");
  EXPECT_EQ(back.verdict->confidence, 0.62);
  EXPECT_EQ(back.verdict->reasons, std::vector<std::string>{"wall 2 seen along 30 %"});
  EXPECT_EQ(back.walls[2].verdict, "unreliable");
  EXPECT_FALSE(back.walls[0].verdict);
  nlohmann::json j = PlanToJson(plan);
  j["verdict"]["verdict"] = "fine";
  j["verdict"]["confidence"] = 1.5;
  j["walls"][1]["verdict"] = "maybe";
  try {
    PlanFromJson(j, "plan.json");
    FAIL();
  } catch (const InputError& e) {
    ASSERT_EQ(e.problems().size(), 3u);
    EXPECT_EQ(e.problems()[0].ToString(),
              "plan.json: verdict.verdict: expected \"good\", \"check\" or \"unreliable\", got \"fine\"");
    EXPECT_EQ(e.problems()[1].ToString(), "plan.json: verdict.confidence: 1.5 is above 1");
    EXPECT_EQ(e.problems()[2].ToString(),
              "plan.json: walls[1].verdict: expected \"good\", \"check\" or \"unreliable\", got \"maybe\"");
  }
}

TEST(PlanFile, RejectsDegeneratePolygonAndZeroLengthWall) {
  nlohmann::json j = PlanToJson(RectangleWithDoor());
  j["walls"][0]["end"] = j["walls"][0]["start"];
  j["rooms"][0]["polygon"] = {{0, 0}, {1, 1}};
  try {
    PlanFromJson(j, "plan.json");
    FAIL();
  } catch (const InputError& e) {
    ASSERT_EQ(e.problems().size(), 2u);
    EXPECT_EQ(e.problems()[0].ToString(), "plan.json: walls[0]: start and end coincide (zero-length wall)");
    EXPECT_EQ(e.problems()[1].ToString(), "plan.json: rooms[0].polygon: expected at least 3 elements, got 2");
  }
}

TEST(PolygonArea, IsSignedCounterClockwisePositive) {
  std::vector<Vec2> square = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  EXPECT_DOUBLE_EQ(PolygonArea(square), 4.0);
  std::reverse(square.begin(), square.end());
  EXPECT_DOUBLE_EQ(PolygonArea(square), -4.0);
}

}  // namespace
}  // namespace asbuilt
