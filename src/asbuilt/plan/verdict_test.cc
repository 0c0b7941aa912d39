#include "asbuilt/plan/verdict.h"

#include <cmath>

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// A 4 × 3 m room seen from a level camera 1.5 m above (0.5, 0.2): a floor
// and a ceiling contact (ceiling 2.6 m) every 0.25° of the turn.
constexpr double kX0 = -2.0, kX1 = 2.0, kY0 = -1.5, kY1 = 1.5, kCeiling = 2.6;
const Vec3 kCamera(0.5, 0.2, 1.5);

Plan BoxPlan(double east_x = kX1) {
  Plan p;
  const std::vector<Vec2> c = {{kX0, kY0}, {east_x, kY0}, {east_x, kY1}, {kX0, kY1}};
  for (int i = 0; i < 4; ++i) p.walls.push_back({.start = c[i], .end = c[(i + 1) % 4], .length_sigma_m = 0.01});
  p.rooms.push_back({.polygon = c, .area_m2 = PolygonArea(c), .area_sigma_m2 = 0.02});
  return p;
}

PlanInput BoxInput() {
  PlanInput in{.source = "box", .one_camera = true, .ceiling_height_m = kCeiling, .ceiling_height_sigma_m = 0.005};
  in.frames.push_back({.index = 0, .position_m = kCamera, .camera_m = kCamera});
  for (double deg = 0; deg < 360; deg += 0.25) {
    const Vec2 d(std::cos(DegToRad(deg)), std::sin(DegToRad(deg)));
    double t = INFINITY;
    if (d.x() > 1e-9) t = std::min(t, (kX1 - kCamera.x()) / d.x());
    if (d.x() < -1e-9) t = std::min(t, (kX0 - kCamera.x()) / d.x());
    if (d.y() > 1e-9) t = std::min(t, (kY1 - kCamera.y()) / d.y());
    if (d.y() < -1e-9) t = std::min(t, (kY0 - kCamera.y()) / d.y());
    const Vec2 xy = kCamera.head<2>() + t * d;
    for (double z : {0.0, kCeiling}) {
      in.points.push_back({.label = LabelClass::kWall,
                           .position_m = Vec3(xy.x(), xy.y(), z),
                           .sigma_m = 0.01,
                           .source = PointSource::kContact,
                           .frame = 0});
    }
  }
  return in;
}

PlanResult Fit(const Plan& plan) {
  PlanResult r{.plan = plan};
  r.summary.closed = true;
  r.summary.manhattan = true;
  r.summary.area_m2 = plan.rooms.at(0).area_m2;
  r.summary.wall_inferred.assign(plan.walls.size(), false);
  return r;
}

TEST(JudgePlan, APlanWhereThePhotoPutsTheWallsIsGood) {
  const PlanVerdict v = JudgePlan(BoxInput(), Fit(BoxPlan()));
  EXPECT_EQ(v.verdict, Verdict::kGood) << v.BriefReport();
  EXPECT_NEAR(v.agreement, 1.0, 1e-9);
  EXPECT_NEAR(v.coverage, 1.0, 1e-9);
  EXPECT_GE(v.confidence, 0.95);
  for (const WallVerdict& w : v.walls) EXPECT_EQ(w.verdict, Verdict::kGood) << v.BriefReport();
}

TEST(JudgePlan, AWallWhereThePhotoSaysNothingIsDoubtedWithItsNeighbours) {
  // The east wall drawn 0.6 m short of where its floor and ceiling edges are.
  const PlanVerdict v = JudgePlan(BoxInput(), Fit(BoxPlan(kX1 - 0.6)));
  ASSERT_EQ(v.walls.size(), 4u);
  EXPECT_NE(v.verdict, Verdict::kGood) << v.BriefReport();
  EXPECT_EQ(v.walls[1].verdict, Verdict::kUnreliable) << v.BriefReport();
  ASSERT_FALSE(v.walls[1].reasons.empty());
  EXPECT_NE(v.walls[1].reasons[0].find("beyond it"), std::string::npos) << v.walls[1].reasons[0];
  EXPECT_NE(v.walls[0].verdict, Verdict::kGood);  // Its length ends at the doubted wall.
  EXPECT_NE(v.walls[2].verdict, Verdict::kGood);
  EXPECT_EQ(v.walls[3].verdict, Verdict::kGood);
  EXPECT_LT(v.confidence, 0.8);
}

TEST(JudgePlan, AWallConfirmedByAPersonIsGood) {
  VerdictContext context;
  context.confirmed_walls = {false, true, false, false};
  const PlanVerdict v = JudgePlan(BoxInput(), Fit(BoxPlan(kX1 - 0.6)), {}, context);
  EXPECT_EQ(v.walls[1].verdict, Verdict::kGood);
  EXPECT_EQ(v.walls[1].reasons, std::vector<std::string>{"placed by a person"});
}

TEST(JudgePlan, NoWallsIsUnreliable) {
  const PlanVerdict v = JudgePlan(BoxInput(), PlanResult{});
  EXPECT_EQ(v.verdict, Verdict::kUnreliable);
  EXPECT_EQ(v.confidence, 0.0);
}

TEST(JudgePlan, AnImplausibleCeilingNamesTheCameraHeight) {
  PlanInput in = BoxInput();
  in.ceiling_height_m = 1.7;
  const PlanVerdict v = JudgePlan(in, Fit(BoxPlan()));
  EXPECT_EQ(v.verdict, Verdict::kUnreliable);
  EXPECT_NE(v.BriefReport().find("camera height"), std::string::npos) << v.BriefReport();
}

TEST(JudgePlan, ADoorOfNoDoorsHeightUnderAPlausibleCeilingIsMisread) {
  PlanResult fit = Fit(BoxPlan());
  fit.plan.openings.push_back({.kind = OpeningKind::kDoor,
                               .wall = 0,
                               .start = {-1.0, kY0},
                               .end = {-0.1, kY0},
                               .width = 0.9,
                               .height = 1.1,
                               .sill = 0.0});
  const PlanVerdict v = JudgePlan(BoxInput(), fit);
  EXPECT_EQ(v.verdict, Verdict::kCheck);
  EXPECT_NE(v.BriefReport().find("a misread door"), std::string::npos) << v.BriefReport();
  EXPECT_EQ(v.BriefReport().find("camera height"), std::string::npos) << v.BriefReport();
}

// The south wall drawn as two, 5 cm apart, joined by a jog: each piece may
// be one wall with the other, and its length's ± says so.
TEST(JudgePlan, AWallEndingAtAJogMayRunOnPastIt) {
  Plan p;
  const std::vector<Vec2> c = {{kX0, kY0}, {0.0, kY0}, {0.0, kY0 + 0.05}, {kX1, kY0 + 0.05}, {kX1, kY1}, {kX0, kY1}};
  for (std::size_t i = 0; i < c.size(); ++i) {
    p.walls.push_back({.start = c[i], .end = c[(i + 1) % c.size()], .length_sigma_m = 0.01});
  }
  p.rooms.push_back({.polygon = c, .area_m2 = PolygonArea(c), .area_sigma_m2 = 0.02});
  const PlanVerdict v = JudgePlan(BoxInput(), Fit(p));
  ASSERT_EQ(v.walls.size(), 6u);
  for (int w : {0, 2}) {
    EXPECT_EQ(v.walls[w].verdict, Verdict::kCheck) << w << ": " << v.walls[w].Why();
    EXPECT_NEAR(v.walls[w].evidence.run_on_m, 2.0, 1e-9) << w;
    EXPECT_NE(v.walls[w].Why().find("jog"), std::string::npos) << v.walls[w].Why();
  }
  EXPECT_EQ(v.walls[3].evidence.run_on_m, 0.0);  // Its neighbours are no jogs.
  EXPECT_EQ(v.walls[1].evidence.run_on_m, 0.0);  // The jog itself is judged as a jog.
  MarkPlan(v, p);
  ASSERT_TRUE(p.walls[0].length_sigma_m);
  EXPECT_GE(*p.walls[0].length_sigma_m, 2.0);
  ASSERT_TRUE(p.walls[3].length_sigma_m);
  EXPECT_LT(*p.walls[3].length_sigma_m, 0.2);
}

// A misread floor edge can step more than once: the jog is every short
// wall up to the next longer one.
TEST(JudgePlan, AJogOfSeveralShortWallsIsStillAJog) {
  Plan p;
  const std::vector<Vec2> c = {{kX0, kY0},        {0.0, kY0}, {0.1, kY0 + 0.05}, {0.1, kY0 + 0.08},
                               {kX1, kY0 + 0.08}, {kX1, kY1}, {kX0, kY1}};
  for (std::size_t i = 0; i < c.size(); ++i) {
    p.walls.push_back({.start = c[i], .end = c[(i + 1) % c.size()], .length_sigma_m = 0.01});
  }
  p.rooms.push_back({.polygon = c, .area_m2 = PolygonArea(c), .area_sigma_m2 = 0.02});
  const PlanVerdict v = JudgePlan(BoxInput(), Fit(p));
  ASSERT_EQ(v.walls.size(), 7u);
  EXPECT_NEAR(v.walls[0].evidence.run_on_m, 2.0, 1e-9);  // 0.1 along it in the jog, then 1.9.
  EXPECT_NEAR(v.walls[3].evidence.run_on_m, 2.1, 1e-9);
  EXPECT_EQ(v.walls[0].verdict, Verdict::kCheck);
}

// A short piece at an odd angle beside a wall is a misread floor edge, not
// a jog of the room: where the wall ends is in doubt, even with no wall
// parallel to it beyond, and its ± takes in how far it may run on.
TEST(JudgePlan, AShortPieceAtAnOddAngleLeavesItsNeighboursEndInDoubt) {
  Plan p;
  const std::vector<Vec2> c = {{kX0, kY0}, {1.0, kY0}, {1.15, kY0 + 0.2}, {1.15, kY1}, {kX0, kY1}};
  for (std::size_t i = 0; i < c.size(); ++i) {
    p.walls.push_back({.start = c[i], .end = c[(i + 1) % c.size()], .length_sigma_m = 0.01});
  }
  p.rooms.push_back({.polygon = c, .area_m2 = PolygonArea(c), .area_sigma_m2 = 0.02});
  const PlanVerdict v = JudgePlan(BoxInput(), Fit(p));
  ASSERT_EQ(v.walls.size(), 5u);
  EXPECT_EQ(v.walls[0].own, Verdict::kGood) << v.walls[0].Why();
  EXPECT_EQ(v.walls[0].verdict, Verdict::kCheck);
  EXPECT_NE(v.walls[0].Why().find("odd angle"), std::string::npos) << v.walls[0].Why();
  // It may run on as far as the pieces beyond its end reach along it (the
  // 0.15 m piece; the wall after it runs across), not past its start, where
  // a wall the photo confirms stands square to it.
  EXPECT_EQ(v.walls[0].evidence.run_on_m, 0.0);  // Nothing parallel beyond: no jog's run-on.
  EXPECT_NEAR(v.walls[0].evidence.doubtful_reach_m, 0.15, 1e-9);
  MarkPlan(v, p);
  ASSERT_TRUE(p.walls[0].length_sigma_m);
  EXPECT_GE(*p.walls[0].length_sigma_m, 0.1);
}

TEST(JudgePlan, AGrosslyUnsureSegmenterMakesAPlanCheck) {
  const PlanInput in = BoxInput();
  const PlanResult fit = Fit(BoxPlan());
  auto judged = [&](double label_confidence) {
    VerdictContext context;
    context.label_confidence = label_confidence;
    return JudgePlan(in, fit, {}, context);
  };
  const PlanVerdict sure = judged(0.95), lost = judged(0.70);
  EXPECT_EQ(sure.verdict, Verdict::kGood) << sure.BriefReport();
  EXPECT_DOUBLE_EQ(sure.confidence, JudgePlan(in, fit).confidence);
  EXPECT_EQ(lost.verdict, Verdict::kCheck);
  EXPECT_NE(lost.BriefReport().find("segmenter was unsure"), std::string::npos) << lost.BriefReport();
  EXPECT_DOUBLE_EQ(lost.label_confidence, 0.70);
  EXPECT_EQ(judged(NAN).verdict, Verdict::kGood);  // Given or exact labels: nothing to doubt.
}

TEST(TiltFromCeilingSamples, RecoversALeanAndIgnoresTopsOfFurniture) {
  // Samples as a camera leaning 1.2° toward bearing 60° gives them: each
  // column's rays seem ε = g·u higher than they are.
  const PlanInput in = BoxInput();
  const double lean = DegToRad(1.2), toward = DegToRad(60.0);
  const Vec2 g(lean * std::cos(toward), lean * std::sin(toward));
  std::vector<CeilingSample> samples;
  for (const ClassPoint& p : in.points) {
    if (p.position_m.z() > 0.1) continue;
    const Vec2 rel = p.position_m.head<2>() - kCamera.head<2>();
    const double d = rel.norm(), h = kCamera.z();
    const double eps = g.dot(rel / d);
    const double beta = std::atan2(h, d) - eps, alpha = std::atan2(kCeiling - h, d) + eps;
    const double d_seen = h / std::tan(beta);
    samples.push_back({.floor_m = p.position_m, .frame = 0, .height_m = h + d_seen * std::tan(alpha)});
  }
  // A sideboard's top taken for the floor edge along a quarter of the turn.
  for (std::size_t i = 0; i < samples.size() / 4; ++i) samples[i].height_m += 1.2 + 0.001 * i;
  const LabelTilt t = TiltFromCeilingSamples(in, samples);
  EXPECT_NEAR(t.tilt_deg, 1.2, 0.05);
  EXPECT_NEAR(t.toward_deg, 60.0, 3.0);
  EXPECT_NEAR(t.ceiling_m, kCeiling, 0.02);
  EXPECT_TRUE(t.Found());
  EXPECT_LT(t.sigma_deg, 0.1);
}

TEST(TiltFromCeilingSamples, TooFewSamplesSayNothing) {
  const LabelTilt t = TiltFromCeilingSamples(BoxInput(), {{.floor_m = Vec3(1, 1, 0), .frame = 0, .height_m = 2.5}});
  EXPECT_FALSE(t.Found());
  EXPECT_TRUE(std::isnan(t.tilt_deg));
}

TEST(MarkPlan, AnUnreliableWallLosesItsPlusMinus) {
  const PlanVerdict v = JudgePlan(BoxInput(), Fit(BoxPlan(kX1 - 0.6)));
  Plan plan = BoxPlan(kX1 - 0.6);
  MarkPlan(v, plan);
  ASSERT_TRUE(plan.verdict);
  EXPECT_EQ(plan.verdict->verdict, VerdictName(v.verdict));
  EXPECT_EQ(plan.walls[1].verdict, "unreliable");
  EXPECT_FALSE(plan.walls[1].length_sigma_m);
  EXPECT_EQ(plan.walls[3].verdict, "good");
  ASSERT_TRUE(plan.walls[3].length_sigma_m);
  EXPECT_NEAR(*plan.walls[3].length_sigma_m, 0.01, 1e-3);  // Its neighbours' points lie on them.
  // Walls 0 and 2 end at wall 1, whose points lie 0.6 m beyond it: their ± takes that in.
  ASSERT_TRUE(plan.walls[0].length_sigma_m && plan.walls[2].length_sigma_m);
  EXPECT_GT(*plan.walls[0].length_sigma_m, 0.4);
  EXPECT_LT(*plan.walls[0].length_sigma_m, 0.8);
  EXPECT_GT(*plan.walls[2].length_sigma_m, 0.4);
}

TEST(VerdictOptions, BoundsAreChecked) {
  VerdictOptions o;
  o.good_agreement = 0.5;  // Below the unreliable bound.
  EXPECT_THROW(o.Check(), InvalidArgument);
  o = {};
  o.bin_deg = 0;
  EXPECT_THROW(o.Check(), InvalidArgument);
  o = {};
  o.check_label_confidence = 1.5;
  EXPECT_THROW(o.Check(), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
