#include "asbuilt/plan/fit_plan.h"

#include <cmath>

#include <gtest/gtest.h>

#include "asbuilt/plan/plan_test_rooms.h"
#include "asbuilt/plan/room_iou.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// Contact points of every wall of `truth` (floor, as a camera turning at the
// centre would give them).
PlanInput RoomInput(const Plan& truth, const Vec3& camera) {
  PlanInput input{.source = "test room", .one_camera = true};
  for (const PlanWall& w : truth.walls) {
    AddWallRun(input.points, w.start, w.end, 300, PointSource::kContact);
  }
  input.frames.push_back({.index = 0, .position_m = camera, .camera_m = camera});
  return input;
}

double MaxCornerError(const Plan& plan, const std::vector<Vec2>& truth) {
  double worst = 0;
  for (const Vec2& t : truth) {
    double best = INFINITY;
    for (const Vec2& p : plan.rooms.at(0).polygon) best = std::min(best, (p - t).norm());
    worst = std::max(worst, best);
  }
  return worst;
}

TEST(FitPlan, WithoutConstraintsIsReconstructPlanOnTheResolvedOptions) {
  const PlanInput input = RoomInput(RectangleRoom(), Vec3(2.0, 1.8, 1.5));
  const PlanOptions resolved = ResolvePlanOptions(input, {});
  const PlanResult a = FitPlan(input);
  const PlanResult b = ReconstructPlan(input.points, resolved, input.source);
  EXPECT_EQ(PlanToJson(a.plan).dump(), PlanToJson(b.plan).dump());
  EXPECT_EQ(a.summary.walls, b.summary.walls);
}

TEST(ResolvePlanOptions, DecidesWhatTheInputSays) {
  PlanInput input{.one_camera = true, .ceiling_height_m = 2.5, .ceiling_height_sigma_m = 0.02};
  input.frames = {{.index = 0, .position_m = {1, 1, 1.5}}, {.index = 1, .position_m = {1.02, 1, 1.5}}};
  PlanOptions o = ResolvePlanOptions(input, {});
  ASSERT_TRUE(o.viewpoint_m);
  EXPECT_NEAR(o.viewpoint_m->x(), 1.01, 1e-12);
  EXPECT_TRUE(o.one_viewpoint);
  EXPECT_NEAR(*o.ceiling_scale_sigma, 0.02 / 1.0, 1e-12);
  EXPECT_EQ(*o.contact_scale_sigma, PlanOptions::kSegmentedContactScaleSigma);
  input.exact_labels = true;
  EXPECT_EQ(*ResolvePlanOptions(input, {}).contact_scale_sigma, 0.0);
  // A stereo rig, or frames apart: not one viewpoint.
  input.one_camera = false;
  EXPECT_FALSE(ResolvePlanOptions(input, {}).one_viewpoint);
  input.one_camera = true;
  input.frames[1].position_m.x() = 1.5;
  EXPECT_FALSE(ResolvePlanOptions(input, {}).one_viewpoint);
  // What the caller set stays.
  EXPECT_NEAR(ResolvePlanOptions(input, {.viewpoint_m = Vec3(0, 0, 1)}).viewpoint_m->x(), 0.0, 1e-12);
}

// A camera height known to ±σ_h scales every contact's distance alike: the
// room-wide scale mode gains σ_h / h, in quadrature with the labels' share,
// unless the caller set that mode.
TEST(ResolvePlanOptions, TheCameraHeightsSigmaScalesTheRoom) {
  PlanInput input{.one_camera = true, .exact_labels = true, .camera_height_sigma_m = 0.005};
  input.frames = {{.index = 0, .position_m = {1, 1, 1.6}}};
  EXPECT_NEAR(*ResolvePlanOptions(input, {}).contact_scale_sigma, 0.005 / 1.6, 1e-12);
  input.exact_labels = false;
  EXPECT_NEAR(*ResolvePlanOptions(input, {}).contact_scale_sigma,
              std::hypot(PlanOptions::kSegmentedContactScaleSigma, 0.005 / 1.6), 1e-12);
  EXPECT_EQ(*ResolvePlanOptions(input, {.contact_scale_sigma = 0.01}).contact_scale_sigma, 0.01);
  input.camera_height_sigma_m = NAN;  // Unknown (a plan from points alone): the labels' share only.
  EXPECT_EQ(*ResolvePlanOptions(input, {}).contact_scale_sigma, PlanOptions::kSegmentedContactScaleSigma);
}

// A corner fixed off its place: the walls beside it pass through it, along
// the directions their own points give; the far corners stay.
TEST(FitPlan, AFixedCornerRefitsTheWallsBesideIt) {
  const Plan truth = RectangleRoom();
  const PlanInput input = RoomInput(truth, Vec3(2.0, 1.8, 1.5));
  PlanFitter fitter(input, {});
  const PlanResult base = fitter.Fit();
  ASSERT_EQ(base.plan.walls.size(), 4u);
  EXPECT_LE(MaxCornerError(base.plan, truth.rooms[0].polygon), 0.02);
  PlanConstraints c;
  for (const Vec2& p : base.plan.rooms[0].polygon) c.corners.push_back({.xy_m = p});
  // The hints alone give the survey's plan back.
  EXPECT_LE(MaxCornerError(fitter.Fit(c).plan, base.plan.rooms[0].polygon), 1e-9);
  // Corner 2 fixed 4 cm off along both axes: both its walls move with it, straight along the room's axes.
  c.corners[2] = {.xy_m = base.plan.rooms[0].polygon[2] + Vec2(0.04, 0.04), .fixed = true};
  const PlanResult moved = fitter.Fit(c);
  ASSERT_EQ(moved.plan.walls.size(), 4u);
  EXPECT_LE((moved.plan.rooms[0].polygon[2] - c.corners[2].xy_m).norm(), 1e-9);
  for (const PlanWall& w : moved.plan.walls) {
    const Vec2 d = (w.end - w.start).normalized();
    EXPECT_LE(std::min(std::abs(d.x()), std::abs(d.y())), 1e-4) << "wall not along the room's axes";
  }
  EXPECT_LE((moved.plan.rooms[0].polygon[0] - base.plan.rooms[0].polygon[0]).norm(), 1e-6);
  EXPECT_LT(fitter.Fit(c).summary.seconds, 1.0);
}

TEST(FitPlan, GivenOpeningsGoOnTheirNearestWall) {
  const Plan truth = RectangleRoom();
  PlanFitter fitter(RoomInput(truth, Vec3(2.0, 1.8, 1.5)), {});
  const Vec2 a = truth.walls[0].start, b = truth.walls[0].end;
  PlanConstraints c{.openings = std::vector<PlanUserOpening>{{.kind = OpeningKind::kWindow,
                                                              .start_m = a + 0.2 * (b - a) + Vec2(0, 0.05),
                                                              .end_m = a + 0.4 * (b - a),
                                                              .bottom_m = 0.9,
                                                              .top_m = 2.0}}};
  const PlanResult r = fitter.Fit(c);
  ASSERT_EQ(r.plan.openings.size(), 1u);
  EXPECT_EQ(r.plan.openings[0].kind, OpeningKind::kWindow);
  EXPECT_NEAR(r.plan.openings[0].width, 0.2 * (b - a).norm(), 0.02);
  EXPECT_NEAR(*r.plan.openings[0].sill, 0.9, 1e-12);
  EXPECT_NEAR(*r.plan.openings[0].height, 1.1, 1e-12);
}

TEST(PlanConstraints, RefusesBadConstraintsNamingThem) {
  PlanConstraints c;
  c.corners = {{.xy_m = {0, 0}}, {.xy_m = {1, 0}}};
  EXPECT_THROW(c.Check(), InvalidArgument);
  c.corners = {{.xy_m = {0, 0}}, {.xy_m = {NAN, 0}}, {.xy_m = {0, 1}}};
  EXPECT_THROW(c.Check(), InvalidArgument);
  c = {.ceiling_height_m = -1.0};
  EXPECT_THROW(c.Check(), InvalidArgument);
  c = {.openings = std::vector<PlanUserOpening>{{.bottom_m = 2.0, .top_m = 1.0}}};
  EXPECT_THROW(c.Check(), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
