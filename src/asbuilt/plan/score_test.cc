#include "asbuilt/plan/score.h"

#include <filesystem>

#include <gtest/gtest.h>

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

Plan Rectangle(double w, double h) {
  Plan plan;
  std::vector<Vec2> c = {{0, 0}, {w, 0}, {w, h}, {0, h}};
  for (int i = 0; i < 4; ++i) plan.walls.push_back({.start = c[i], .end = c[(i + 1) % 4]});
  plan.openings.push_back({.kind = OpeningKind::kDoor, .wall = 0, .start = {1, 0}, .end = {1.9, 0}, .width = 0.9});
  plan.openings.push_back({.kind = OpeningKind::kWindow, .wall = 2, .start = {3, h}, .end = {2, h}, .width = 1.0});
  plan.rooms.push_back({.polygon = c, .area_m2 = w * h});
  return plan;
}

TEST(ScorePlan, IdenticalPlansScorePerfectly) {
  Plan truth = Rectangle(5, 4);
  PlanScore s = ScorePlan(truth, truth);
  EXPECT_EQ(s.walls.matched, 4);
  EXPECT_DOUBLE_EQ(*s.walls.Recall(), 1.0);
  EXPECT_DOUBLE_EQ(*s.walls.Precision(), 1.0);
  EXPECT_DOUBLE_EQ(*s.wall_length.Max(), 0.0);
  EXPECT_EQ(s.doors.matched, 1);
  EXPECT_EQ(s.windows.matched, 1);
  EXPECT_DOUBLE_EQ(*s.area_relative_error, 0.0);
}

TEST(ScorePlan, MeasuresRelativeLengthWidthAndAreaErrors) {
  Plan truth = Rectangle(5, 4);
  Plan predicted = Rectangle(5.05, 4);  // Walls 0 and 2 are 1 % longer.
  predicted.openings[0].width = 0.918;  // 2 % wider door.
  PlanScore s = ScorePlan(predicted, truth);
  EXPECT_EQ(s.walls.matched, 4);
  EXPECT_NEAR(*s.wall_length.Max(), 0.01, 1e-9);
  EXPECT_NEAR(*s.wall_length.Median(), 0.005, 1e-9);
  EXPECT_NEAR(*s.door_width.Median(), 0.02, 1e-9);
  EXPECT_NEAR(*s.window_width.Max(), 0.0, 1e-9);
  EXPECT_NEAR(*s.area_relative_error, 0.01, 1e-9);
}

TEST(ScorePlan, RejectsWallsTooFarTooSkewedOrNotOverlapping) {
  Plan truth;
  truth.walls.push_back({.start = {0, 0}, .end = {4, 0}});
  Plan far, skew, apart;
  far.walls.push_back({.start = {0, 0.3}, .end = {4, 0.3}});
  skew.walls.push_back({.start = {0, -0.2}, .end = {4, 0.6}});  // 11.3°
  apart.walls.push_back({.start = {3, 0}, .end = {7, 0}});      // Overlap 1 m < 2 m.
  EXPECT_EQ(ScorePlan(far, truth).walls.matched, 0);
  EXPECT_EQ(ScorePlan(skew, truth).walls.matched, 0);
  EXPECT_EQ(ScorePlan(apart, truth).walls.matched, 0);
  Plan near;
  near.walls.push_back({.start = {4.1, 0.2}, .end = {0, 0.2}});  // Reversed direction still matches.
  EXPECT_EQ(ScorePlan(near, truth).walls.matched, 1);
}

TEST(ScorePlan, MatchesOneToOneAndCountsExtrasAgainstPrecision) {
  Plan truth;
  truth.walls.push_back({.start = {0, 0}, .end = {4, 0}});
  Plan predicted;
  predicted.walls.push_back({.start = {0, 0.1}, .end = {4, 0.1}});
  predicted.walls.push_back({.start = {0, 0.01}, .end = {4, 0.01}});
  PlanScore s = ScorePlan(predicted, truth);
  ASSERT_EQ(s.walls.matched, 1);
  EXPECT_EQ(s.wall_matches[0].predicted, 1);  // The closer one wins.
  EXPECT_DOUBLE_EQ(*s.walls.Precision(), 0.5);
  EXPECT_FALSE(s.area_relative_error.has_value());
}

TEST(ScorePlan, OpeningsMatchOnlyTheSameKindWithinTheCentreDistance) {
  Plan truth = Rectangle(5, 4);
  Plan predicted = Rectangle(5, 4);
  predicted.openings[0].kind = OpeningKind::kWindow;  // Wrong kind.
  predicted.openings[1].start += Vec2(0.35, 0);       // Centre 0.35 m off.
  predicted.openings[1].end += Vec2(0.35, 0);
  PlanScore s = ScorePlan(predicted, truth);
  EXPECT_EQ(s.doors.matched, 0);
  EXPECT_EQ(s.windows.matched, 0);
  EXPECT_EQ(s.windows.predicted, 2);
  EXPECT_FALSE(s.opening_width.Median().has_value());
}

TEST(ScorePlan, PrintsJsonAndTable) {
  Plan truth = Rectangle(5, 4);
  PlanScore s = ScorePlan(truth, truth);
  nlohmann::json j = PlanScoreToJson(s);
  EXPECT_EQ(j["walls"]["matched"], 4);
  EXPECT_EQ(j["walls"]["recall"], 1.0);
  EXPECT_EQ(j["room_area"]["relative_error"], 0.0);
  EXPECT_NE(s.Table().find("walls"), std::string::npos);
  EXPECT_EQ(s.ToString().substr(0, 32), "walls 4/4 (precision 100.0 %), l");
  Plan empty;
  nlohmann::json je = PlanScoreToJson(ScorePlan(empty, truth));
  EXPECT_TRUE(je["walls"]["precision"].is_null());
  EXPECT_TRUE(je["wall_length_relative_error"]["median"].is_null());
}

TEST(ScoreOptions, DefaultsAreValidAndBadValuesAreNamed) {
  EXPECT_NO_THROW(ScoreOptions{}.Check());
  try {
    ScoreOptions{.wall_max_distance_m = 0}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "ScoreOptions.wall_max_distance_m = 0, must be > 0");
  }
}

TEST(ScorePlan, BlenderTruthScoresPerfectlyAgainstItself) {
  fs::path p = fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public/p02_L_shape/truth.json";
  if (!fs::exists(p)) GTEST_SKIP() << "shared data not present: " << p;
  Plan truth = ReadPlan(p);
  PlanScore s = ScorePlan(truth, truth);
  EXPECT_EQ(s.walls.matched, 6);
  EXPECT_EQ(s.doors.matched, 1);
  EXPECT_EQ(s.windows.matched, 2);
}

TEST(UncertaintyCalibration, CountsTruthWithinOneAndTwoSigmaAndTheBias) {
  UncertaintyCalibration c;
  EXPECT_FALSE(c.Within(1.0).has_value());
  c.Add(10.05, 10.0, 0.1);          // 0.5σ.
  c.Add(9.85, 10.0, 0.1);           // 1.5σ.
  c.Add(10.3, 10.0, 0.1);           // 3σ.
  c.Add(10.0, 10.0, std::nullopt);  // No ±: within only when exact.
  EXPECT_DOUBLE_EQ(*c.Within(1.0), 0.5);
  EXPECT_DOUBLE_EQ(*c.Within(2.0), 0.75);
  EXPECT_NEAR(*c.MeanSignedRelativeError(), (0.005 - 0.015 + 0.03) / 4, 1e-12);
  EXPECT_EQ(c.ToString(), "n 4: 50.0 % within 1σ, 75.0 % within 2σ, bias +0.50 % (1 without ±)");
}

TEST(ScorePlan, CarriesThePlansSigmasIntoTheMatchesAndTheCalibration) {
  Plan truth, measured;
  truth.walls.push_back({.start = {0, 0}, .end = {4, 0}});
  measured.walls.push_back({.start = {0, 0.01}, .end = {4.03, 0.01}, .length_sigma_m = 0.01});
  truth.rooms.push_back({.polygon = {{0, 0}, {4, 0}, {4, 3}}, .area_m2 = 6.0});
  measured.rooms.push_back({.polygon = {{0, 0}, {4, 0}, {4, 3}}, .area_m2 = 6.1, .area_sigma_m2 = 0.2});
  const PlanScore s = ScorePlan(measured, truth);
  ASSERT_EQ(s.wall_matches.size(), 1u);
  EXPECT_EQ(s.wall_matches[0].predicted_length_sigma_m, 0.01);
  EXPECT_EQ(s.predicted_area_sigma_m2, 0.2);
  UncertaintyCalibration walls, widths, areas;
  AddToCalibration(s, &walls, &widths, &areas);
  EXPECT_DOUBLE_EQ(*walls.Within(2.0), 0.0);  // 3 cm off at ±1 cm.
  EXPECT_DOUBLE_EQ(*walls.Within(3.5), 1.0);
  EXPECT_TRUE(widths.items.empty());
  EXPECT_DOUBLE_EQ(*areas.Within(1.0), 1.0);
}

}  // namespace
}  // namespace asbuilt
