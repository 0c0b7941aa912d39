// End-to-end tests of ReconstructPlan: whole rooms, accuracy targets, errors,
// the summary. Tests of one stage's behaviour sit in plan_<stage>_test.cc.
#include "asbuilt/plan/reconstruct.h"

#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/plan/plan_test_rooms.h"
#include "asbuilt/plan/sample.h"
#include "asbuilt/plan/score.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

struct Pooled {
  RelativeErrors length, width;
  std::vector<double> area;
  int walls_truth = 0, walls_matched = 0, walls_predicted = 0;
  int openings_truth = 0, openings_matched = 0;
  std::string worst;
};

void Pool(Pooled& pool, const PlanScore& s, const std::string& name) {
  pool.length.values.insert(pool.length.values.end(), s.wall_length.values.begin(), s.wall_length.values.end());
  pool.width.values.insert(pool.width.values.end(), s.opening_width.values.begin(), s.opening_width.values.end());
  if (s.area_relative_error) pool.area.push_back(*s.area_relative_error);
  pool.walls_truth += s.walls.truth;
  pool.walls_matched += s.walls.matched;
  pool.walls_predicted += s.walls.predicted;
  pool.openings_truth += s.doors.truth + s.windows.truth;
  pool.openings_matched += s.doors.matched + s.windows.matched;
  if (s.walls.matched < s.walls.truth) pool.worst += name + ": " + s.ToString() + "\n";
}

PlanScore RunOne(const Plan& truth, std::uint64_t seed, const SampleOptions& sample = {}) {
  std::vector<ClassPoint> points = SamplePointsFromPlan(truth, sample, seed);
  PlanOptions options;
  options.viewpoint_m = SampleViewpoint(truth, sample);
  options.seed = seed;
  PlanResult r = ReconstructPlan(points, options);
  return ScorePlan(r.plan, truth);
}

TEST(ReconstructPlan, RecoversANoiselessRectangleExactly) {
  Plan truth = RectangleRoom();
  SampleOptions sample{.sigma_base_m = 0, .sigma_per_m2 = 0, .outlier_fraction = 0};
  std::vector<ClassPoint> points = SamplePointsFromPlan(truth, sample, 1);
  PlanResult r = ReconstructPlan(points, {});
  PlanScore s = ScorePlan(r.plan, truth);
  EXPECT_EQ(s.walls.matched, 4) << s.Table();
  EXPECT_EQ(s.walls.predicted, 4);
  EXPECT_LT(*s.wall_length.Max(), 1e-4) << s.Table();
  EXPECT_EQ(s.doors.matched, 1);
  EXPECT_EQ(s.windows.matched, 2);
  EXPECT_LT(*s.opening_width.Max(), 0.01) << s.Table();
  EXPECT_NEAR(r.plan.rooms[0].area_m2, 16.2, 0.01);
  EXPECT_TRUE(r.summary.closed);
  EXPECT_TRUE(r.summary.manhattan);
  EXPECT_GT(PolygonArea(r.plan.rooms[0].polygon), 0);  // Counter-clockwise.
}

// The targets, over many seeds and room shapes: wall length median
// ≤ 1 %, max ≤ 3 %; opening width median ≤ 2 %; wall recall 100 %.
TEST(ReconstructPlan, MeetsTheAccuracyTargetsOnNoisyRoomsWithOutliers) {
  struct Case {
    std::string name;
    Plan plan;
  };
  std::vector<Case> cases = {{"rect", RectangleRoom()},
                             {"L", LShape()},
                             {"rect rotated 23°", Rotated(RectangleRoom(), 23, {1.5, -2})},
                             {"L rotated -61°", Rotated(LShape(), -61, {-3, 4})},
                             {"trapezoid rotated 7°", Rotated(Trapezoid(), 7, {0, 0})},
                             {"8 walls rotated 40°", Rotated(EightWalls(), 40, {2, 2})}};
  Pooled pool;
  for (const Case& c : cases) {
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      PlanScore s = RunOne(c.plan, seed);
      Pool(pool, s, fmt::format("{} seed {}", c.name, seed));
      EXPECT_EQ(s.walls.matched, s.walls.truth) << c.name << " seed " << seed << "\n" << s.Table();
      EXPECT_EQ(s.walls.predicted, s.walls.truth) << c.name << " seed " << seed << "\n" << s.Table();
    }
  }
  EXPECT_EQ(pool.walls_matched, pool.walls_truth) << pool.worst;
  EXPECT_LE(*pool.length.Median(), 0.01) << pool.length.ToString();
  EXPECT_LE(*pool.length.Max(), 0.03) << pool.length.ToString();
  EXPECT_LE(*pool.width.Median(), 0.02) << pool.width.ToString();
  EXPECT_GE(pool.openings_matched, pool.openings_truth * 95 / 100);
  std::printf("sampled rooms: walls %d/%d, length %s, opening width %s, openings %d/%d\n", pool.walls_matched,
              pool.walls_truth, pool.length.ToString().c_str(), pool.width.ToString().c_str(), pool.openings_matched,
              pool.openings_truth);
}

TEST(ReconstructPlan, UsesTheBlenderTruthPlansAsTruth) {
  for (const char* room : {"p01_rect_1door_2win", "p02_L_shape"}) {
    fs::path p = fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public" / room / "truth.json";
    if (!fs::exists(p)) GTEST_SKIP() << "shared data not present: " << p;
    Plan truth = ReadPlan(p);
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      PlanScore s = RunOne(truth, seed, {.viewpoint_m = Vec3(2.1, 1.6, 1.45)});
      EXPECT_EQ(s.walls.matched, s.walls.truth) << room << "\n" << s.Table();
      EXPECT_LE(*s.wall_length.Max(), 0.03) << room << "\n" << s.Table();
      EXPECT_EQ(s.doors.matched + s.windows.matched, 3) << room << "\n" << s.Table();
    }
  }
}

TEST(ReconstructPlan, FailsClearlyWithoutEnoughWallPoints) {
  std::vector<ClassPoint> points(10);
  try {
    ReconstructPlan(points, {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("10 wall points"), std::string::npos) << e.what();
  }
}

// One straight wall is no room: an input error naming the source.
TEST(ReconstructPlan, FailsClearlyWithFewerThanTwoWallLines) {
  std::vector<ClassPoint> points;
  AddWallRun(points, {0, 0}, {4, 0}, 400, PointSource::kDense);
  try {
    ReconstructPlan(points, {}, "one_wall.txt");
    FAIL();
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("one_wall.txt"), std::string::npos) << what;
    EXPECT_NE(what.find("found 1 wall line(s) in 400 wall points"), std::string::npos) << what;
  }
}

TEST(PlanOptions, DefaultsAreValidAndBadValuesAreNamed) {
  EXPECT_NO_THROW(PlanOptions{}.Check());
  try {
    PlanOptions{.epsilon_m = -1}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "PlanOptions.epsilon_m = -1, must be > 0");
  }
}

// The bounds come from PlanOptionFields(), the one statement of each: the
// list's and Check()'s once disagreed (min_wall_fraction 0.2 passed the flag
// and failed Check), and the list's own bounds were not checked for a
// library caller.
TEST(PlanOptions, CheckReadsTheBoundsOfTheFieldList) {
  auto problem = [](const PlanOptions& o) -> std::string {
    try {
      o.Check();
      return "";
    } catch (const InvalidArgument& e) {
      return e.what();
    }
  };
  EXPECT_EQ(problem({.min_wall_fraction = 0.2}), "PlanOptions.min_wall_fraction = 0.2, must be in [0, 0.2)");
  EXPECT_EQ(problem({.min_wall_fraction = 0.19}), "");
  EXPECT_EQ(problem({.min_wall_points = 2}), "PlanOptions.min_wall_points = 2, must be >= 3");
  EXPECT_EQ(problem({.parallel_max_deg = 90}), "PlanOptions.parallel_max_deg = 90, must be in (0, 90)");
  EXPECT_EQ(problem({.casing_depth_m = 0.5}), "PlanOptions.casing_depth_m = 0.5, must be in [0, 0.1]");
  EXPECT_EQ(problem({.epsilon_m = NAN}), "PlanOptions.epsilon_m = nan, must be > 0");
  EXPECT_EQ(problem({.viewpoint_m = Vec3(NAN, 0, 0)}), "PlanOptions.viewpoint_m = [nan, 0, 0], must be finite");
  EXPECT_EQ(problem({.contact_scale_sigma = 0.6}), "PlanOptions.contact_scale_sigma = 0.6, must be in [0, 0.5]");
}

TEST(PlanSummary, BriefReportSaysWhatWasFound) {
  PlanResult r = ReconstructPlan(SamplePointsFromPlan(RectangleRoom(), {}, 2), {});
  std::string s = r.summary.BriefReport();
  EXPECT_EQ(s.rfind("4 walls (0 inferred), 3 openings, closed, 16.", 0), 0u) << s;
  EXPECT_NE(s.find("Manhattan"), std::string::npos) << s;
}

TEST(WallPiecesBetweenOpenings, CutsOutEveryOpening) {
  Plan p = RectangleRoom();
  auto pieces = WallPiecesBetweenOpenings(p, 0);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_NEAR(pieces[0].second, 0.4, 1e-12);
  EXPECT_NEAR(pieces[1].first, 1.3, 1e-12);
  EXPECT_NEAR(pieces[1].second, 4.5, 1e-12);
  EXPECT_EQ(WallPiecesBetweenOpenings(p, 3).size(), 1u);
}

}  // namespace
}  // namespace asbuilt
