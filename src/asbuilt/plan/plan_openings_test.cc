// Plan stage 6, openings (plan_openings.h), on their own and through
// ReconstructPlan.
#include "asbuilt/plan/plan_openings.h"

#include <cmath>
#include <utility>

#include <gtest/gtest.h>

#include "asbuilt/plan/plan_test_rooms.h"
#include "asbuilt/plan/reconstruct.h"
#include "asbuilt/plan/sample.h"
#include "asbuilt/plan/score.h"

namespace asbuilt {
namespace {

// Rows of a window label's points on the wall y = 0, x from 1.0 to 2.2 m
// every cm, z from `bottom` up `height` every `step` metres.
struct WindowRows {
  double bottom, height, step;
};
std::vector<ClassPoint> WindowPoints(const WindowRows& rows) {
  std::vector<ClassPoint> points;
  const int n = static_cast<int>(std::lround(rows.height / rows.step));
  for (int i = 0; i <= 120; ++i) {
    for (int k = 0; k <= n; ++k) {
      points.push_back(
          {LabelClass::kWindow, Vec3(1.0 + 0.01 * i, 0.0, rows.bottom + rows.step * k), 0.005, PointSource::kDense, 0});
    }
  }
  return points;
}

// A window's label on a wall's face, 1.2 m wide from 0.85 to 2.35 m up,
// casing included: the opening is the clear one inside the casing.
TEST(FindOpenings, GivesTheClearOpeningInsideTheLabel) {
  const std::vector<ClassPoint> points = WindowPoints({0.85, 1.5, 0.05});
  std::vector<const ClassPoint*> pointers;
  for (const ClassPoint& p : points) pointers.push_back(&p);
  const std::vector<PlanWall> walls = {{.start = {0, 0}, .end = {4, 0}}, {.start = {4, 0}, .end = {4, 3}}};
  const PlanOptions o;
  const FoundOpenings found = FindOpenings(pointers, walls, Vec2(2, 1.5), o);
  EXPECT_EQ(found.door_leaves, 0);
  ASSERT_EQ(found.openings.size(), 1u);
  const PlanOpening& w = found.openings[0];
  EXPECT_EQ(w.kind, OpeningKind::kWindow);
  EXPECT_EQ(w.wall, 0);
  EXPECT_NEAR(w.start.x(), 1.0 + o.window_casing_m, 1e-9);
  EXPECT_NEAR(w.end.x(), 2.2 - o.window_casing_m, 1e-9);
  EXPECT_NEAR(w.width, 1.2 - 2 * o.window_casing_m, 1e-9);
  EXPECT_NEAR(w.sill.value_or(0), 0.85 + o.window_casing_m, 1e-9);
  EXPECT_NEAR(w.height.value_or(0), 1.5 - 2 * o.window_casing_m, 1e-9);
  EXPECT_GT(w.width_sigma_m.value_or(0), 0.0);
}

// Where an opening's points stop without a label edge (occluders, a
// recessed frame) each edge takes extent_edge_sigma_m more; label_edge_sigma_mrad
// (for label edges) leaves such edges alone.
TEST(FindOpenings, EdgesWithoutLabelEdgesTakeTheExtentEdgeSigma) {
  const std::vector<ClassPoint> points = WindowPoints({0.85, 1.5, 0.05});
  std::vector<const ClassPoint*> pointers;
  for (const ClassPoint& p : points) pointers.push_back(&p);
  const std::vector<PlanWall> walls = {{.start = {0, 0}, .end = {4, 0}}};
  const auto sigma = [&](const PlanOptions& o) {
    const FoundOpenings found = FindOpenings(pointers, walls, Vec2(2, 1.5), o);
    return found.openings.size() == 1 ? found.openings[0].width_sigma_m.value_or(-1) : -1.0;
  };
  const double plain = sigma({.extent_edge_sigma_m = 0, .label_edge_sigma_mrad = 0});
  ASSERT_GT(plain, 0.0);
  EXPECT_NEAR(sigma({.extent_edge_sigma_m = 0.05, .label_edge_sigma_mrad = 0}),
              std::hypot(plain, 0.05 * std::sqrt(2.0)), 1e-9);
  EXPECT_NEAR(sigma({.extent_edge_sigma_m = 0, .label_edge_sigma_mrad = 5}), plain, 1e-9);
}

// Glass seen through a window 1.0–2.2 m along the wall y = 0 from (2, 1.5),
// 15 cm behind the face, every cm of the face's opening and 5 cm up: where
// the opening's points stop behind the face, that is the clear opening's
// edge, not the outer side of a casing on the face, so no casing comes off.
// With the casing's label on the face beyond both ends it does.
TEST(FindOpenings, AnEdgeSeenThroughTheOpeningIsTheClearOpeningsOwn) {
  const Vec3 view(2, 1.5, 1.4);
  std::vector<ClassPoint> points;
  for (int i = 0; i <= 120; ++i) {
    const double x_face = 1.0 + 0.01 * i, x_glass = view.x() + (x_face - view.x()) * 1.65 / 1.5;
    for (int k = 0; k <= 24; ++k) {
      points.push_back({LabelClass::kWindow, Vec3(x_glass, -0.15, 1.0 + 0.05 * k), 0.005, PointSource::kDense, 0});
    }
  }
  const std::vector<PlanWall> walls = {{.start = {0, 0}, .end = {4, 0}}};
  PlanOptions o;
  o.viewpoint_m = view;
  const auto find = [&](const std::vector<ClassPoint>& pts) {
    std::vector<const ClassPoint*> pointers;
    for (const ClassPoint& p : pts) pointers.push_back(&p);
    return FindOpenings(pointers, walls, view.head<2>(), o).openings;
  };
  std::vector<PlanOpening> found = find(points);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_NEAR(found[0].start.x(), 1.0, 0.01);
  EXPECT_NEAR(found[0].end.x(), 2.2, 0.01);
  for (int i = 0; i <= 5; ++i) {
    for (int k = 0; k <= 24; ++k) {
      for (double x : {0.95 + 0.01 * i, 2.2 + 0.01 * i}) {
        points.push_back({LabelClass::kWindow, Vec3(x, 0.0, 1.0 + 0.05 * k), 0.005, PointSource::kDense, 0});
      }
    }
  }
  found = find(points);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_NEAR(found[0].start.x(), 1.0, 0.01);
  EXPECT_NEAR(found[0].end.x(), 2.2, 0.01);
}

// A window label strip thinner than its two casings (a sill or a lintel
// edge seen as window) leaves no clear height: no opening, never a negative
// height that plan.json would refuse.
TEST(FindOpenings, AStripThinnerThanItsCasingsIsNoOpening) {
  const std::vector<ClassPoint> points = WindowPoints({1.00, 0.04, 0.02});
  std::vector<const ClassPoint*> pointers;
  for (const ClassPoint& p : points) pointers.push_back(&p);
  const std::vector<PlanWall> walls = {{.start = {0, 0}, .end = {4, 0}}};
  const PlanOptions o;
  ASSERT_LT(0.04, 2 * o.window_casing_m);
  EXPECT_TRUE(FindOpenings(pointers, walls, Vec2(2, 1.5), o).openings.empty());
}

// Door labels from x0 to x1 on the wall y = 0, every 2 cm, from the floor to
// `top`.
std::vector<ClassPoint> DoorPoints(double x0, double x1, double top) {
  std::vector<ClassPoint> points;
  for (double x = x0; x <= x1 + 1e-9; x += 0.02) {
    for (double z = 0.0; z <= top + 1e-9; z += 0.05) {
      points.push_back({LabelClass::kDoor, Vec3(x, 0.0, z), 0.005, PointSource::kDense, 0});
    }
  }
  return points;
}

// Door labels that stay near the floor (a rug, a misread floor) are no door.
TEST(FindOpenings, DoorLabelsNearTheFloorAreNoDoor) {
  const std::vector<PlanWall> walls = {{.start = {0, 0}, .end = {4, 0}}};
  const PlanOptions o;
  for (const double top : {0.3, 2.1}) {
    const std::vector<ClassPoint> points = DoorPoints(1.0, 1.9, top);
    std::vector<const ClassPoint*> pointers;
    for (const ClassPoint& p : points) pointers.push_back(&p);
    EXPECT_EQ(FindOpenings(pointers, walls, Vec2(2, 1.5), o).openings.size(), top > o.min_door_height_m ? 1u : 0u)
        << top;
  }
}

// A door label painted down a plain wall from the ceiling to 1 m, with the
// wall seen below it, is no door; a doorway with wall only beside it stays,
// and so does the band when no wall points are given.
TEST(FindOpenings, ADoorBandWithWallSeenBelowItIsNoDoor) {
  const std::vector<PlanWall> walls = {{.start = {0, 0}, .end = {4, 0}}};
  const PlanOptions o;
  const auto wall_points = [](double x0, double x1, double z0, double z1) {
    WallPoints wall;
    for (double x = x0; x <= x1 + 1e-9; x += 0.02) {
      for (double z = z0; z <= z1 + 1e-9; z += 0.05) {
        wall.points.push_back(
            {.p = {x, 0.0}, .z = z, .w = 1e4, .sigma = 0.01, .thr = 0.05, .vote = 1.0, .contact = false});
      }
    }
    return wall;
  };
  std::vector<ClassPoint> band;
  for (const ClassPoint& p : DoorPoints(1.0, 1.9, 2.4)) {
    if (p.position_m.z() >= 1.0) band.push_back(p);
  }
  std::vector<const ClassPoint*> band_pointers;
  for (const ClassPoint& p : band) band_pointers.push_back(&p);
  const WallPoints below = wall_points(1.0, 1.9, 0.0, 0.95);
  EXPECT_TRUE(FindOpenings(band_pointers, walls, Vec2(2, 1.5), o, &below).openings.empty());
  EXPECT_EQ(FindOpenings(band_pointers, walls, Vec2(2, 1.5), o).openings.size(), 1u);
  PlanOptions never = o;
  never.door_wall_below_share = 1.0;
  EXPECT_EQ(FindOpenings(band_pointers, walls, Vec2(2, 1.5), never, &below).openings.size(), 1u);

  const std::vector<ClassPoint> doorway = DoorPoints(1.0, 1.9, 2.1);
  std::vector<const ClassPoint*> doorway_pointers;
  for (const ClassPoint& p : doorway) doorway_pointers.push_back(&p);
  WallPoints beside = wall_points(0.0, 0.98, 0.0, 2.5);
  const WallPoints right = wall_points(1.92, 4.0, 0.0, 2.5);
  beside.points.insert(beside.points.end(), right.points.begin(), right.points.end());
  EXPECT_EQ(FindOpenings(doorway_pointers, walls, Vec2(2, 1.5), o, &beside).openings.size(), 1u);
}

// A well-seen label edge on one side and a handful of stray ones inside the
// door on the other (an open leaf's outline): the stray side is where the
// door's points stop, not where the strays are.
TEST(FindOpenings, AHandfulOfStrayLabelEdgesInsideADoorIsNotItsEdge) {
  const std::vector<PlanWall> walls = {{.start = {0, 0}, .end = {4, 0}}};
  std::vector<ClassPoint> points = DoorPoints(1.0, 1.9, 2.1);
  for (int i = 0; i < 40; ++i) {
    points.push_back({LabelClass::kDoor, Vec3(1.9, 0.0, 0.05 * i), 0.005, PointSource::kBoundary, 0});
  }
  for (int i = 0; i < 4; ++i) {
    points.push_back({LabelClass::kDoor, Vec3(1.35, 0.0, 0.5 * i), 0.005, PointSource::kBoundary, 0});
  }
  std::vector<const ClassPoint*> pointers;
  for (const ClassPoint& p : points) pointers.push_back(&p);
  PlanOptions o;
  o.viewpoint_m = Vec3(2, 1.5, 1.5);
  const FoundOpenings found = FindOpenings(pointers, walls, Vec2(2, 1.5), o);
  ASSERT_EQ(found.openings.size(), 1u);
  EXPECT_NEAR(found.openings[0].start.x(), 1.0 + o.door_casing_m, 0.02);
  EXPECT_NEAR(found.openings[0].end.x(), 1.9 - o.door_casing_m, 0.02);
  o.max_own_beyond_label_edge = 1.0;  // Never: the strays' median is the edge.
  const FoundOpenings trusting = FindOpenings(pointers, walls, Vec2(2, 1.5), o);
  ASSERT_EQ(trusting.openings.size(), 1u);
  EXPECT_NEAR(trusting.openings[0].start.x(), 1.35 + o.door_casing_m, 0.02);
}

// A window's frame read as door over part of the window: the opening with
// fewer points goes; a door under a transom window stays with it.
TEST(FindOpenings, ADoorAndAWindowFillingOneStretchOfWallAreOneOpening) {
  const std::vector<PlanWall> walls = {{.start = {0, 0}, .end = {4, 0}}};
  std::vector<ClassPoint> points = WindowPoints({0.85, 1.5, 0.05});  // x 1.0–2.2, every cm.
  const std::vector<ClassPoint> frame = DoorPoints(1.6, 2.2, 1.6);
  points.insert(points.end(), frame.begin(), frame.end());
  std::vector<const ClassPoint*> pointers;
  for (const ClassPoint& p : points) pointers.push_back(&p);
  const FoundOpenings found = FindOpenings(pointers, walls, Vec2(2, 1.5), {});
  ASSERT_EQ(found.openings.size(), 1u);
  EXPECT_EQ(found.openings[0].kind, OpeningKind::kWindow);

  std::vector<ClassPoint> transom = WindowPoints({2.15, 0.4, 0.05});  // Above a door 2.1 m high.
  const std::vector<ClassPoint> door = DoorPoints(1.2, 2.0, 2.1);
  transom.insert(transom.end(), door.begin(), door.end());
  pointers.clear();
  for (const ClassPoint& p : transom) pointers.push_back(&p);
  EXPECT_EQ(FindOpenings(pointers, walls, Vec2(2, 1.5), {}).openings.size(), 2u);
}

// Fewer than min_opening_points points are no opening.
TEST(FindOpenings, NeedsEnoughPoints) {
  std::vector<ClassPoint> points;
  for (int i = 0; i <= 10; ++i) {
    for (const double z : {1.0, 1.5}) {
      points.push_back({LabelClass::kDoor, Vec3(1.0 + 0.1 * i, 0.0, z), 0.005, PointSource::kDense, 0});
    }
  }
  std::vector<const ClassPoint*> pointers;
  for (const ClassPoint& p : points) pointers.push_back(&p);
  const std::vector<PlanWall> walls = {{.start = {0, 0}, .end = {4, 0}}};
  EXPECT_TRUE(FindOpenings(pointers, walls, Vec2(2, 1.5), {.min_opening_points = 23}).openings.empty());
  EXPECT_EQ(FindOpenings(pointers, walls, Vec2(2, 1.5), {.min_opening_points = 22}).openings.size(), 1u);
}

// Label-edge points of a window on the wall y = 0 at x = `a` and `b`, every
// 5 cm from 1.0 to 2.0 m up, σ 5 cm; each is the point at `ahead_m` in front
// of the face on the ray from `view` through where the edge meets the face.
std::vector<ClassPoint> EdgePoints(double a, double b, const Vec3& view, double ahead_m) {
  std::vector<ClassPoint> points;
  for (const double x : {a, b}) {
    for (double z = 1.0; z <= 2.0; z += 0.05) {
      const Vec3 on_face(x, 0, z), ray = on_face - view;
      points.push_back({LabelClass::kWindow, on_face + ahead_m / ray.y() * ray, 0.05, PointSource::kBoundary, 0});
    }
  }
  return points;
}

// Label edges with none of the opening's own points beside them are no
// opening, whatever leaf stands nearby: a door's open leaf swung back along
// the next wall outlines itself against that wall so, and the leaf would
// give the phantom door a width.
TEST(FindOpenings, LabelEdgesAloneAreNoOpening) {
  const Vec3 view(2, 1.5, 1.5);
  std::vector<ClassPoint> points;
  for (double z = 0.1; z <= 2.0; z += 0.05) {
    points.push_back({LabelClass::kDoor, Vec3(1.0, 0, z), 0.05, PointSource::kBoundary, 0});
  }
  const double leaf_deg = 70.0;
  const Vec2 hinge(0.93, 0), leaf(std::cos(DegToRad(leaf_deg)), std::sin(DegToRad(leaf_deg)));
  for (double s = 0.05; s < 0.8; s += 0.01) {
    for (double z = 0.1; z < 1.3; z += 0.1) {
      const Vec2 xy = hinge + s * leaf;
      points.push_back({LabelClass::kDoor, Vec3(xy.x(), xy.y(), z), 0.01, PointSource::kDense, 0});
    }
  }
  std::vector<const ClassPoint*> pointers;
  for (const ClassPoint& p : points) pointers.push_back(&p);
  const std::vector<PlanWall> walls = {{.start = {0, 0}, .end = {4, 0}}};
  const PlanOptions o{.viewpoint_m = view};
  EXPECT_TRUE(FindOpenings(pointers, walls, view.head<2>(), o).openings.empty());
  // With the door's own points beside the edge it is a door.
  std::vector<ClassPoint> own;
  for (double x = 1.0; x < 1.5; x += 0.01) {
    for (double z = 0.1; z <= 2.0; z += 0.1)
      own.push_back({LabelClass::kDoor, Vec3(x, 0, z), 0.005, PointSource::kDense, 0});
  }
  for (const ClassPoint& p : own) pointers.push_back(&p);
  EXPECT_EQ(FindOpenings(pointers, walls, view.head<2>(), o).openings.size(), 1u);
}

// A far wall's label edges scatter in front of its face by their depth
// noise: within 3σ they still place the edge. Here a cupboard hides the
// window's last 20 cm, its points stop at 2.0 m, and the label edge at
// 2.2 m, 6 cm in front of the face (σ 5 cm), gives the width.
TEST(FindOpenings, ALabelEdgeInFrontOfTheFaceByItsNoiseStillPlacesTheEdge) {
  const Vec3 view(2, 1.5, 1.5);
  std::vector<ClassPoint> points = WindowPoints({0.85, 1.5, 0.05});
  std::erase_if(points, [](const ClassPoint& p) { return p.position_m.x() > 2.0; });
  const std::vector<ClassPoint> edges = EdgePoints(1.0, 2.2, view, 0.06);
  points.insert(points.end(), edges.begin(), edges.end());
  std::vector<const ClassPoint*> pointers;
  for (const ClassPoint& p : points) pointers.push_back(&p);
  const std::vector<PlanWall> walls = {{.start = {0, 0}, .end = {4, 0}}};
  const PlanOptions o{.casing_depth_m = 0, .viewpoint_m = view};
  const FoundOpenings found = FindOpenings(pointers, walls, view.head<2>(), o);
  ASSERT_EQ(found.openings.size(), 1u);
  EXPECT_NEAR(found.openings[0].width, 1.2 - 2 * o.window_casing_m, 0.002);
}

// Seen obliquely, the far edge's casing hides its own outer side: the
// label ends at the casing's front corner, 1.5 cm before the face, and its
// ray meets the face (edge − foot)·p/(h − p) farther out. That edge is moved
// back; its σ grows with the obliquity.
TEST(FindOpenings, AFarLabelEdgeSeenPastItsCasingIsMovedBack) {
  const Vec3 view(-1, 1.5, 1.5);  // Off to the window's start side: its end edge is the far one.
  const double p = 0.015, seen_b = 2.2 + (2.2 - view.x()) * p / (view.y() - p);
  std::vector<ClassPoint> points = WindowPoints({0.85, 1.5, 0.05});
  const std::vector<ClassPoint> edges = EdgePoints(1.0, seen_b, view, 0.0);
  points.insert(points.end(), edges.begin(), edges.end());
  std::vector<const ClassPoint*> pointers;
  for (const ClassPoint& q : points) pointers.push_back(&q);
  const std::vector<PlanWall> walls = {{.start = {0, 0}, .end = {4, 0}}};
  const auto width = [&](double casing_depth_m) {
    const PlanOptions o{.casing_depth_m = casing_depth_m, .viewpoint_m = view};
    const FoundOpenings found = FindOpenings(pointers, walls, view.head<2>(), o);
    return found.openings.size() == 1 ? found.openings[0] : PlanOpening{};
  };
  const PlanOpening plain = width(0.0), corrected = width(p);
  EXPECT_GT(plain.width, 1.1 + 0.025);
  EXPECT_NEAR(corrected.width, 1.1, 0.002);
  EXPECT_GT(corrected.width_sigma_m.value_or(0), plain.width_sigma_m.value_or(1));
}

// A label edge off by an angle δ seen from the viewpoint lands range²/h · δ
// along the wall (h: the viewpoint's distance from it): a window seen
// head-on from 2 m gains little, one seen obliquely from 4 m away much more.
TEST(FindOpenings, ALabelEdgesSigmaGrowsWithRangeSquaredOverDistance) {
  const auto added_var = [](const Vec3& view) {
    std::vector<ClassPoint> points = WindowPoints({0.85, 1.5, 0.05});
    const std::vector<ClassPoint> edges = EdgePoints(1.0, 2.2, view, 0.0);
    points.insert(points.end(), edges.begin(), edges.end());
    std::vector<const ClassPoint*> pointers;
    for (const ClassPoint& q : points) pointers.push_back(&q);
    const std::vector<PlanWall> walls = {{.start = {-5, 0}, .end = {5, 0}}};
    const auto sigma = [&](double mrad) {
      const PlanOptions o{.casing_depth_m = 0, .label_edge_sigma_mrad = mrad, .viewpoint_m = view};
      const FoundOpenings found = FindOpenings(pointers, walls, view.head<2>(), o);
      return found.openings.size() == 1 ? found.openings[0].width_sigma_m.value_or(0) : 0.0;
    };
    return std::pow(sigma(5), 2) - std::pow(sigma(0), 2);
  };
  const auto expected = [](const Vec3& view) {
    double var = 0;
    for (const double x : {1.0, 2.2})
      var += std::pow(0.005 * (std::pow(x - view.x(), 2) + std::pow(view.y(), 2)) / view.y(), 2);
    return var;
  };
  const Vec3 head_on(1.6, 2, 1.5), oblique(-2, 1, 1.5);
  EXPECT_NEAR(added_var(head_on), expected(head_on), 1e-7);
  EXPECT_NEAR(added_var(oblique), expected(oblique), 1e-6);
  EXPECT_GT(added_var(oblique), 20 * added_var(head_on));
}

TEST(PlanOpenings, OpeningWidthsComeFromLabelEdgesOnTheWall) {
  const Plan truth = RectangleRoom();
  SampleOptions sample{.outlier_fraction = 0};
  std::vector<ClassPoint> points = SamplePointsFromPlan(truth, sample, 4);
  const Vec3 view = SampleViewpoint(truth, sample);
  // Stray opening points 12 cm beyond each label edge on the face (frames
  // and casings seen past the edge, depth noise): they stretch the extent.
  for (const PlanOpening& o : truth.openings) {
    const bool door = o.kind == OpeningKind::kDoor;
    const Vec2 along = (o.end - o.start).normalized();
    const double casing = door ? 0.07 : 0.05;
    for (double z = 1.0; z < 1.5; z += 0.02) {
      for (const Vec2& xy : {Vec2(o.start - (casing + 0.12) * along), Vec2(o.end + (casing + 0.12) * along)}) {
        points.push_back(
            {door ? LabelClass::kDoor : LabelClass::kWindow, Vec3(xy.x(), xy.y(), z), 0.005, PointSource::kDense, 0});
      }
    }
  }
  const PlanOptions options{.viewpoint_m = view};
  const PlanScore without = ScorePlan(ReconstructPlan(points, options).plan, truth);
  const std::vector<ClassPoint> edges = BoundaryPoints(truth, view, 0.08);
  points.insert(points.end(), edges.begin(), edges.end());
  const PlanResult r = ReconstructPlan(points, options);
  const PlanScore with = ScorePlan(r.plan, truth);
  EXPECT_EQ(with.doors.matched + with.windows.matched, 3) << with.Table();
  EXPECT_GT(without.opening_width.Median().value_or(0), 0.1) << without.Table();
  EXPECT_LE(with.opening_width.Max().value_or(1), 0.005) << with.Table();
  for (const PlanOpening& o : r.plan.openings) EXPECT_LT(o.width_sigma_m.value_or(1), 0.03);
}

TEST(PlanOpenings, TwoWindowsEitherSideOfANarrowPierStayTwo) {
  // Clear openings 0.25 m apart: their labels (casings included) 0.15 m,
  // closer than the gap that splits openings.
  Plan truth = PolygonPlan({{0, 0}, {4.5, 0}, {4.5, 3.6}, {0, 3.6}});
  AddPlanOpening(truth, OpeningKind::kWindow, 2, 0.8, 1.3, 1.4, 0.9);
  AddPlanOpening(truth, OpeningKind::kWindow, 2, 2.35, 1.2, 1.4, 0.9);
  SampleOptions sample{.outlier_fraction = 0};
  const Vec3 view = SampleViewpoint(truth, sample);
  std::vector<ClassPoint> points = SamplePointsFromPlan(truth, sample, 5);
  const PlanOptions options{.viewpoint_m = view};
  // Without the label edges at the pier, the windows' points alone cannot
  // tell a pier from something standing in front of one wide window.
  const PlanScore merged = ScorePlan(ReconstructPlan(points, options).plan, truth);
  EXPECT_LT(merged.windows.matched, 2) << merged.Table();
  const std::vector<ClassPoint> edges = BoundaryPoints(truth, view, 0.08);
  points.insert(points.end(), edges.begin(), edges.end());
  const PlanScore split = ScorePlan(ReconstructPlan(points, options).plan, truth);
  EXPECT_EQ(split.windows.predicted, 2) << split.Table();
  EXPECT_EQ(split.windows.matched, 2) << split.Table();
  EXPECT_LE(split.opening_width.Max().value_or(1), 0.01) << split.Table();
}

TEST(PlanOpenings, AnOpenLeafDoesNotWidenTheDoor) {
  const Plan truth = RectangleRoom();
  SampleOptions sample{.outlier_fraction = 0};
  std::vector<ClassPoint> points = SamplePointsFromPlan(truth, sample, 5);
  const Vec3 view = SampleViewpoint(truth, sample);
  const double before = ScorePlan(ReconstructPlan(points, {.viewpoint_m = view}).plan, truth).door_width.Max().value();
  // The leaf, 0.9 m wide, hinged at the door's start and swung 70° into the
  // room; noisy points (σ 10 cm, as stereo gives them at 3 m).
  const PlanOpening& door = truth.openings[0];
  const PlanWall& wall = truth.walls[door.wall];
  const Vec2 along = (wall.end - wall.start).normalized(), inward(-along.y(), along.x());
  const Vec2 leaf = std::cos(DegToRad(70.0)) * along + std::sin(DegToRad(70.0)) * inward;
  for (double s = 0.02; s < 0.9; s += 0.01) {
    for (double z = 0.1; z < 2.0; z += 0.1) {
      const Vec2 xy = door.start + s * leaf;
      points.push_back({LabelClass::kDoor, Vec3(xy.x(), xy.y(), z), 0.1, PointSource::kDense, 0});
    }
  }
  const PlanScore s = ScorePlan(ReconstructPlan(points, {.viewpoint_m = view}).plan, truth);
  EXPECT_EQ(s.doors.matched, 1) << s.Table();
  EXPECT_EQ(s.doors.predicted, 1) << s.Table();
  EXPECT_LE(s.door_width.Max().value_or(1), before + 0.02) << s.Table();
}

// An open leaf hides its hinge-side jamb from the rig: no label edge is seen
// there and the door's points stop short. A leaf is as wide as its clear
// opening, so the width is the leaf's, measured from the edge that is seen.
TEST(PlanOpenings, AnOpenLeafHidingTheHingeSideGivesTheDoorItsWidth) {
  const Plan truth = RectangleRoom();
  const PlanOpening& door = truth.openings[0];
  const PlanWall& wall = truth.walls[door.wall];
  const Vec2 along = (wall.end - wall.start).normalized(), inward(-along.y(), along.x());
  SampleOptions sample{.outlier_fraction = 0};
  const Vec3 view = SampleViewpoint(truth, sample);
  std::vector<ClassPoint> points = SamplePointsFromPlan(truth, sample, 6);
  // Hidden by the leaf: the door's points within 35 cm of the hinge (at the
  // door's start), and that side's label edge.
  std::erase_if(points, [&](const ClassPoint& p) {
    return p.label == LabelClass::kDoor && along.dot(p.position_m.head<2>() - door.start) < 0.35;
  });
  for (const ClassPoint& p : BoundaryPoints(truth, view, 0.02)) {
    const double t = along.dot(p.position_m.head<2>() - door.start);
    if (p.label != LabelClass::kDoor || t > 0.5) points.push_back(p);
  }
  const PlanScore hidden = ScorePlan(ReconstructPlan(points, {.viewpoint_m = view}).plan, truth);
  // The leaf: as wide as the opening, hinged at its start, swung 70° into the
  // room; points σ 1 cm, 1.2 m tall.
  const double width = (door.end - door.start).norm();
  const Vec2 leaf = std::cos(DegToRad(70.0)) * along + std::sin(DegToRad(70.0)) * inward;
  for (double s = 0.03; s < width; s += 0.01) {
    for (double z = 0.1; z < 1.3; z += 0.1) {
      const Vec2 xy = door.start + s * leaf + 0.01 * std::sin(37 * s + 11 * z) * Vec2(-leaf.y(), leaf.x());
      points.push_back({LabelClass::kDoor, Vec3(xy.x(), xy.y(), z), 0.01, PointSource::kDense, 0});
    }
  }
  const PlanResult r = ReconstructPlan(points, {.viewpoint_m = view});
  const PlanScore s = ScorePlan(r.plan, truth);
  EXPECT_GT(hidden.door_width.Max().value_or(1), 0.2) << hidden.Table();
  EXPECT_EQ(r.summary.door_leaves, 1);
  EXPECT_EQ(s.doors.matched, 1) << s.Table();
  EXPECT_LE(s.door_width.Max().value_or(1), 0.03) << s.Table();
}

}  // namespace
}  // namespace asbuilt
