#include "asbuilt/plan/reconstruct.h"

#include <filesystem>
#include <random>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/plan/sample.h"
#include "asbuilt/plan/score.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

Plan PolygonPlan(const std::vector<Vec2>& corners, double height = 2.7) {
  Plan plan;
  int n = static_cast<int>(corners.size());
  for (int i = 0; i < n; ++i) {
    plan.walls.push_back({.start = corners[i], .end = corners[(i + 1) % n], .thickness = 0.2, .height = height});
  }
  plan.rooms.push_back({.polygon = corners, .area_m2 = PolygonArea(corners)});
  return plan;
}

void AddOpening(Plan& plan, OpeningKind kind, int wall, double offset, double width, double height,
                double sill) {
  const PlanWall& w = plan.walls[wall];
  Vec2 d = (w.end - w.start).normalized();
  plan.openings.push_back({.kind = kind, .wall = wall, .start = w.start + offset * d,
                           .end = w.start + (offset + width) * d, .width = width, .height = height,
                           .sill = sill});
}

Plan Rotated(const Plan& plan, double angle_deg, const Vec2& shift) {
  Eigen::Rotation2Dd r(DegToRad(angle_deg));
  auto f = [&](const Vec2& p) -> Vec2 { return r * p + shift; };
  Plan out = plan;
  for (PlanWall& w : out.walls) {
    w.start = f(w.start);
    w.end = f(w.end);
  }
  for (PlanOpening& o : out.openings) {
    o.start = f(o.start);
    o.end = f(o.end);
  }
  for (PlanRoom& room : out.rooms) {
    for (Vec2& p : room.polygon) p = f(p);
  }
  return out;
}

Plan Rectangle() {
  Plan p = PolygonPlan({{0, 0}, {4.5, 0}, {4.5, 3.6}, {0, 3.6}});
  AddOpening(p, OpeningKind::kDoor, 0, 0.4, 0.9, 2.1, 0.0);
  AddOpening(p, OpeningKind::kWindow, 1, 0.9, 1.2, 1.4, 0.9);
  AddOpening(p, OpeningKind::kWindow, 2, 1.2, 1.6, 1.4, 0.9);
  return p;
}

Plan LShape() {
  Plan p = PolygonPlan({{0, 0}, {6, 0}, {6, 2.6}, {2.6, 2.6}, {2.6, 5}, {0, 5}});
  AddOpening(p, OpeningKind::kDoor, 5, 0.6, 0.9, 2.1, 0.0);
  AddOpening(p, OpeningKind::kWindow, 0, 2.8, 1.5, 1.4, 0.9);
  AddOpening(p, OpeningKind::kWindow, 4, 0.7, 1.2, 1.4, 0.9);
  return p;
}

// Non-Manhattan: a trapezoid with one slanted wall.
Plan Trapezoid() {
  Plan p = PolygonPlan({{0, 0}, {5, 0}, {4, 4}, {0, 4}});
  AddOpening(p, OpeningKind::kDoor, 3, 1.0, 0.8, 2.0, 0.0);
  AddOpening(p, OpeningKind::kWindow, 1, 1.0, 1.2, 1.2, 1.0);
  return p;
}

// Eight walls, two corners cut out; every wall visible from the centre.
Plan EightWalls() {
  Plan p = PolygonPlan({{0, 0}, {5.5, 0}, {5.5, 1}, {7, 1}, {7, 5}, {1.2, 5}, {1.2, 4}, {0, 4}});
  AddOpening(p, OpeningKind::kDoor, 0, 3.0, 1.0, 2.1, 0.0);
  AddOpening(p, OpeningKind::kWindow, 4, 1.5, 1.5, 1.4, 0.9);
  return p;
}

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
  Plan truth = Rectangle();
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
  std::vector<Case> cases = {{"rect", Rectangle()},
                             {"L", LShape()},
                             {"rect rotated 23°", Rotated(Rectangle(), 23, {1.5, -2})},
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
              pool.walls_truth, pool.length.ToString().c_str(), pool.width.ToString().c_str(),
              pool.openings_matched, pool.openings_truth);
}

// A far plain wall's stereo, smeared ±25 cm along its rays, whose points
// (σ 30 cm) lean 12° off the wall: fitted freely, the wall leans. In a
// square room (a Manhattan frame, formed within manhattan_always_deg however
// small the precise walls' σ make the fits' angle errors) the axis explains
// those points within their noise, and the wall is drawn square.
TEST(ReconstructPlan, ANoisyWallLeaningOffASquareRoomsAxisIsDrawnSquare) {
  const Plan truth = PolygonPlan({{0, 0}, {4.5, 0}, {4.5, 3.6}, {0, 3.6}});
  const SampleOptions sample{.sigma_per_m2 = 0.0005, .outlier_fraction = 0};
  std::vector<ClassPoint> points = SamplePointsFromPlan(truth, sample, 3);
  std::erase_if(points, [](const ClassPoint& p) { return p.position_m.x() > 4.3; });
  // Wall 1 (x = 4.5): a cloud leaning 12°, 0.9 m tall.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-0.04, 0.04);
  for (double y = 0.4; y <= 3.2; y += 0.01) {
    for (double z = 0.5; z <= 1.4; z += 0.1) {
      const double x = 4.5 + 0.21 * (y - 1.8) / 1.0 + jitter(rng);
      points.push_back({LabelClass::kWall, Vec3(x, y + jitter(rng), z), 0.3, PointSource::kDense, 0});
    }
  }
  PlanOptions with{.viewpoint_m = SampleViewpoint(truth, sample)};
  PlanOptions without = with;
  without.noisy_snap_max_deg = 0;
  auto wall1_angle = [&](const PlanOptions& o) {
    const PlanScore s = ScorePlan(ReconstructPlan(points, o).plan, truth);
    for (const WallMatch& m : s.wall_matches) {
      if (m.truth == 1) return m.angle_deg;
    }
    return 90.0;
  };
  EXPECT_GT(wall1_angle(without), 5.0);
  EXPECT_LT(wall1_angle(with), 0.5);
}

// A wall seen only at its far end (furniture before the rest, 5.5 m of
// 8 m): its neighbour's corner lies beyond any plausible extension, so the
// ring is closed by a connector — which runs along the wall's own line. It
// is that wall, measured on its line to the corner, not an inferred one.
TEST(ReconstructPlan, AWallSeenOnlyAtItsFarEndReachesItsCorner) {
  const Plan truth = PolygonPlan({{0, 0}, {8, 0}, {8, 3.6}, {0, 3.6}});
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const SampleOptions sample;
    std::vector<ClassPoint> points = SamplePointsFromPlan(truth, sample, seed);
    std::erase_if(points, [](const ClassPoint& p) { return p.position_m.y() < 0.3 && p.position_m.x() < 5.5; });
    PlanOptions options{.viewpoint_m = SampleViewpoint(truth, sample), .seed = seed};
    const PlanResult r = ReconstructPlan(points, options);
    const PlanScore s = ScorePlan(r.plan, truth);
    EXPECT_EQ(r.summary.inferred_walls, 0) << "seed " << seed;
    EXPECT_EQ(s.walls.predicted, 4) << "seed " << seed << "\n" << s.Table();
    EXPECT_EQ(s.walls.matched, 4) << "seed " << seed << "\n" << s.Table();
    EXPECT_LE(*s.wall_length.Max(), 0.01) << "seed " << seed << "\n" << s.Table();
  }
}

// In a Manhattan room a wall whose points fit 4° or 7° off (seen in part, past
// furniture; its σ counts only the points' noise) is snapped square: its
// corners stay put instead of moving by decimetres.
TEST(ReconstructPlan, AWallFittedAFewDegreesOffInAManhattanRoomIsSnappedSquare) {
  for (const double tilt_deg : {4.0, 7.0}) {
    SCOPED_TRACE(fmt::format("tilt {}°", tilt_deg));
    const Plan truth = PolygonPlan({{0, 0}, {6, 0}, {6, 2.6}, {2.6, 2.6}, {2.6, 5}, {0, 5}});
    const SampleOptions sample;
    std::vector<ClassPoint> points = SamplePointsFromPlan(truth, sample, 4);
    const Eigen::Rotation2Dd tilt(DegToRad(tilt_deg));
    for (ClassPoint& p : points) {
      // The east wall (2.6 m), turned about its middle.
      if (p.position_m.x() < 5.8) continue;
      const Vec2 q = tilt * (p.position_m.head<2>() - Vec2(6, 1.3)) + Vec2(6, 1.3);
      p.position_m.head<2>() = q;
    }
    PlanOptions options{.viewpoint_m = SampleViewpoint(truth, sample), .seed = 4};
    const PlanResult r = ReconstructPlan(points, options);
    const PlanScore s = ScorePlan(r.plan, truth);
    EXPECT_TRUE(r.summary.manhattan);
    EXPECT_EQ(s.walls.matched, 6) << s.Table();
    EXPECT_LE(*s.wall_length.Max(), 0.01) << s.Table();
  }
}

// Through a wall's windows the rig sees outside; what it finds there (here
// a line of points 1.9 m behind the wall, between two pieces of it) is not a
// wall of the room: the pieces join into one wall.
TEST(ReconstructPlan, ALineSeenThroughAWallsGapIsNotAWall) {
  const Plan truth = PolygonPlan({{0, 0}, {8.8, 0}, {8.8, 3.1}, {0, 3.1}});
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const SampleOptions sample;
    std::vector<ClassPoint> points = SamplePointsFromPlan(truth, sample, seed);
    std::erase_if(points, [](const ClassPoint& p) {
      return p.position_m.y() < 0.3 && p.position_m.x() > 1.9 && p.position_m.x() < 6.9;
    });
    for (int i = 0; i < 400; ++i) {
      const double x = 3.9 + 1.3 * i / 400.0;
      points.push_back({LabelClass::kWall, Vec3(x, -1.9 + 0.005 * ((i % 5) - 2), 0.0), 0.01, PointSource::kDense, 0});
    }
    PlanOptions options{.viewpoint_m = SampleViewpoint(truth, sample), .seed = seed};
    const PlanResult r = ReconstructPlan(points, options);
    const PlanScore s = ScorePlan(r.plan, truth);
    EXPECT_EQ(s.walls.predicted, 4) << "seed " << seed << "\n" << s.Table();
    EXPECT_EQ(s.walls.matched, 4) << "seed " << seed << "\n" << s.Table();
    EXPECT_LE(*s.wall_length.Max(), 0.01) << "seed " << seed << "\n" << s.Table();
  }
}

// `n` wall points (σ 1 cm) along a → b, scattered by ±2 mm; contacts lie on
// the floor, other points 1 m up.
void AddWallRun(std::vector<ClassPoint>& points, const Vec2& a, const Vec2& b, int n, PointSource source) {
  const double z = source == PointSource::kContact ? 0.0 : 1.0;
  for (int i = 0; i < n; ++i) {
    const Vec2 p = a + (b - a) * (i + 0.5) / n + Vec2(0.002 * (i % 3 - 1), 0.002 * (i % 5 - 2));
    points.push_back({LabelClass::kWall, Vec3(p.x(), p.y(), z), 0.01, source, i % 12});
  }
}

// Vertex points (wall–wall corner columns) of `frames` frames at `corner`,
// a few centimetres apart, as the stereo stage gives them.
void AddVertex(std::vector<ClassPoint>& points, const Vec2& corner, int frames = 2) {
  for (int f = 0; f < frames; ++f) {
    const Vec2 p = corner + Vec2(0.02 * (f - 0.5), -0.015 * (f - 0.5));
    points.push_back({LabelClass::kWall, Vec3(p.x(), p.y(), 1.5), 0.03, PointSource::kVertex, f});
  }
}

// A near plain wall gives no points at all (its floor and ceiling edges are
// out of view) and its neighbours only in part: the ring would close across
// the L's notch. The vertex where the wall meets its neighbour places it.
TEST(ReconstructPlan, AWallWithNoPointsIsPlacedFromTheVertexAtItsEnd) {
  const Plan truth = PolygonPlan({{0, 0}, {6, 0}, {6, 2.6}, {2.6, 2.6}, {2.6, 5}, {0, 5}});
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const SampleOptions sample;
    std::vector<ClassPoint> points = SamplePointsFromPlan(truth, sample, seed);
    std::erase_if(points, [](const ClassPoint& p) {
      const Vec2 q = p.position_m.head<2>();
      return (q.y() > 2.3 && q.y() < 2.9 && q.x() > 2.7) ||  // The notch's wall: nothing.
             (q.x() > 5.7 && q.y() > 1.2) ||                  // Its neighbours: in part.
             (q.x() > 2.3 && q.x() < 2.9 && q.y() < 3.8);
    });
    AddVertex(points, {6, 2.6});
    PlanOptions options{.viewpoint_m = SampleViewpoint(truth, sample), .seed = seed};
    const PlanResult r = ReconstructPlan(points, options);
    const PlanScore s = ScorePlan(r.plan, truth);
    EXPECT_EQ(s.walls.predicted, 6) << "seed " << seed << "\n" << s.Table();
    EXPECT_EQ(s.walls.matched, 6) << "seed " << seed << "\n" << s.Table();
    EXPECT_LE(*s.wall_length.Max(), 0.02) << "seed " << seed << "\n" << s.Table();
  }
}

// bench_rooms seed 10, as the shipped segmenter saw it: an L whose two near
// walls give no points (vertices place them); two walls measured to
// millimetres, square; and two whose contacts the model's label edge (a
// skirting board taken for floor over part of the wall) pushed 10–20 cm out
// in part. Sequential RANSAC cut each of those into two pieces crossing at
// a few degrees, as here (the pieces' ends as the survey's points gave
// them), merged into one line 2.6° off at σ of hundredths of a degree. The
// two kept the room from its Manhattan frame, and the near walls drawn
// through their vertices leaned (max wall error 14 %). Their halves disagree
// with them: their σ widens to that disagreement (PlanOptions::bend_sigmas),
// and the room is drawn square.
TEST(ReconstructPlan, AWallBentByItsContactsDoesNotTurnTheRoom) {
  const Plan truth = PolygonPlan({{2.66, 0}, {7.49, 0}, {7.49, 4.09}, {0, 4.09}, {0, 2.30}, {2.66, 2.30}}, 3.46);
  std::vector<ClassPoint> points;
  std::mt19937_64 rng(10);
  std::normal_distribution<double> noise(0.0, 0.01);
  auto piece = [&](const Vec2& a, const Vec2& b, int n) {
    for (int i = 0; i < n; ++i) {
      const Vec2 p = a + (b - a) * (i + 0.5) / n + Vec2(noise(rng), noise(rng));
      points.push_back({LabelClass::kWall, Vec3(p.x(), p.y(), 0.0), 0.02, PointSource::kContact, i % 12});
    }
  };
  piece({0.0, 2.35}, {0.0, 4.05}, 240);    // West: exact.
  piece({2.66, 0.05}, {2.66, 1.96}, 180);  // The notch: exact.
  piece({3.47, -0.20}, {7.58, -0.01}, 520);  // South, two pieces.
  piece({2.73, -0.03}, {6.39, -0.17}, 160);
  piece({7.51, 0.04}, {7.62, 2.61}, 320);  // East, two pieces.
  piece({7.62, 0.31}, {7.44, 2.67}, 80);
  AddVertex(points, {0, 2.30});
  AddVertex(points, {0, 4.09});
  PlanOptions with{.viewpoint_m = Vec3(4.37, 3.20, 1.30)};
  PlanOptions without = with;
  without.bend_sigmas = 0;
  const PlanResult bent = ReconstructPlan(points, without);
  const PlanResult square = ReconstructPlan(points, with);
  const PlanScore s_bent = ScorePlan(bent.plan, truth), s_square = ScorePlan(square.plan, truth);
  EXPECT_FALSE(bent.summary.manhattan);
  EXPECT_GT(s_bent.wall_length.Max().value_or(1), 0.05) << s_bent.Table();
  EXPECT_TRUE(square.summary.manhattan);
  EXPECT_EQ(s_square.walls.matched, 6) << s_square.Table();
  EXPECT_LE(s_square.wall_length.Max().value_or(1), 0.05) << s_square.Table();
  for (const WallMatch& m : s_square.wall_matches) EXPECT_LT(m.angle_deg, 0.5) << s_square.Table();
}

// bench_rooms seed 15 with exact labels: the stereo smeared around the L's
// inner corner gives a line of two pieces 17° apart, crossing the corner 20°
// off the axis. Its σ, widened for the bend (12°), takes in the axis: it
// snaps square and joins the wall it belongs to, instead of closing the room
// with a slanted wall.
TEST(ReconstructPlan, ABentLineAcrossAnInnerCornerSnapsSquare) {
  const Plan truth = PolygonPlan({{0, 0}, {8.146, 0}, {8.146, 5.193}, {5.485, 5.193}, {5.485, 8.785}, {0, 8.785}});
  std::vector<ClassPoint> points;
  std::mt19937_64 rng(15);
  std::normal_distribution<double> noise(0.0, 1.0);
  auto piece = [&](const Vec2& a, const Vec2& b, int n, double scatter, double sigma) {
    for (int i = 0; i < n; ++i) {
      const Vec2 p = a + (b - a) * (i + 0.5) / n + scatter * Vec2(noise(rng), noise(rng));
      points.push_back({LabelClass::kWall, Vec3(p.x(), p.y(), 1.0), sigma, PointSource::kDense, i % 12});
    }
  };
  piece({0.05, 0}, {8.10, 0}, 3000, 0.01, 0.03);
  piece({8.146, 0.05}, {8.146, 5.15}, 3000, 0.01, 0.03);
  piece({6.20, 5.193}, {8.10, 5.193}, 600, 0.01, 0.03);
  piece({5.485, 6.80}, {5.485, 8.70}, 1500, 0.01, 0.03);
  piece({0.05, 8.785}, {5.40, 8.785}, 3000, 0.01, 0.03);
  piece({0, 0.05}, {0, 8.70}, 3000, 0.01, 0.03);
  piece({5.26, 7.11}, {5.40, 6.00}, 800, 0.02, 0.05);  // The smear: two pieces.
  piece({5.40, 6.00}, {6.10, 5.00}, 800, 0.02, 0.05);
  const PlanResult r = ReconstructPlan(points, {.viewpoint_m = Vec3(2.88, 2.61, 1.56)});
  const PlanScore s = ScorePlan(r.plan, truth);
  EXPECT_TRUE(r.summary.manhattan);
  EXPECT_EQ(s.walls.matched, 6) << s.Table();
  EXPECT_LE(s.wall_length.Max().value_or(1), 0.05) << s.Table();
  for (const WallMatch& m : s.wall_matches) EXPECT_LT(m.angle_deg, 0.5) << s.Table();
}

// bench_rooms seed 28 with exact labels: a small L whose two near plain
// walls (the rig 0.8 and 1.2 m from them) gave no points, only the vertices
// at their far ends. The gap between those vertices runs diagonally across
// the room: two walls are missing, not one, and they meet where the walls
// turning at each vertex cross.
TEST(ReconstructPlan, TwoMissingWallsBetweenVerticesTurnAtTheirCorner) {
  const Plan truth = PolygonPlan({{1.51, 0}, {3.01, 0}, {3.01, 4.22}, {0, 4.22}, {0, 2.26}, {1.51, 2.26}}, 2.94);
  std::vector<ClassPoint> points;
  auto piece = [&](const Vec2& a, const Vec2& b, int n) { AddWallRun(points, a, b, n, PointSource::kContact); };
  piece({1.55, 0.0}, {2.97, 0.0}, 400);   // South.
  piece({0.0, 2.30}, {0.0, 4.18}, 125);   // West.
  piece({1.51, 0.06}, {1.51, 0.84}, 70);  // The notch, in part.
  for (const Vec2& v : {Vec2(3.01, 0.0), Vec2(0.0, 4.22), Vec2(0.0, 2.26), Vec2(1.51, 2.26)}) AddVertex(points, v);
  const PlanResult r = ReconstructPlan(points, {.viewpoint_m = Vec3(2.27, 3.02, 1.42)});
  const PlanScore s = ScorePlan(r.plan, truth);
  EXPECT_EQ(s.walls.predicted, 6) << s.Table();
  EXPECT_EQ(s.walls.matched, 6) << s.Table();
  EXPECT_LE(s.wall_length.Max().value_or(1), 0.03) << s.Table();
  EXPECT_NEAR(r.summary.area_m2, PolygonArea(truth.rooms[0].polygon), 0.3);
}

// bench_rooms seed 8 with exact labels: a wardrobe hides an L wing's wall
// but for its corner column (a vertex), and the wall beside it is seen only
// from 0.6 m beyond. The connector runs through that vertex, not through the
// gap's middle; and a vertex on a neighbour's line 2 m farther on (the east
// wall's, where the line's extension meets it) is not taken for this
// gap's corner.
TEST(ReconstructPlan, AConnectorRunsThroughTheVertexInItsGap) {
  const Plan truth = PolygonPlan({{0, 0}, {4.424, 0}, {4.424, 3.486}, {2.347, 3.486}, {2.347, 2.184}, {0, 2.184}});
  std::vector<ClassPoint> points;
  auto piece = [&](const Vec2& a, const Vec2& b, int n) { AddWallRun(points, a, b, n, PointSource::kDense); };
  piece({0.05, 0.0}, {4.38, 0.0}, 800);     // South.
  piece({4.424, 0.05}, {4.424, 3.44}, 700);  // East.
  piece({4.38, 3.486}, {2.93, 3.486}, 300);  // The wing's north wall, beyond the wardrobe.
  piece({2.30, 2.184}, {0.05, 2.184}, 450);  // North of the main part.
  piece({0.0, 2.14}, {0.0, 0.05}, 400);      // West.
  AddVertex(points, {2.347, 2.489});         // The hidden wall's corner column.
  AddVertex(points, {4.424, 2.150});         // On the east wall, on the extension of y = 2.184.
  const PlanResult r = ReconstructPlan(points, {.viewpoint_m = Vec3(3.395, 1.139, 1.30)});
  const PlanScore s = ScorePlan(r.plan, truth);
  EXPECT_EQ(s.walls.predicted, 6) << s.Table();
  EXPECT_EQ(s.walls.matched, 6) << s.Table();
  EXPECT_LE(s.wall_length.Max().value_or(1), 0.03) << s.Table();
}

// A wall seen only at its far end, with a line seen through its window
// (ground outside) between it and the next wall: the vertex where the two
// walls meet, on both their lines, makes them neighbours.
TEST(ReconstructPlan, AVertexJoinsTwoWallsAcrossALineSeenThroughThem) {
  const Plan truth = PolygonPlan({{0, 0}, {8, 0}, {8, 3.6}, {0, 3.6}});
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const SampleOptions sample;
    std::vector<ClassPoint> points = SamplePointsFromPlan(truth, sample, seed);
    std::erase_if(points, [](const ClassPoint& p) { return p.position_m.y() < 0.3 && p.position_m.x() < 5.5; });
    for (int i = 0; i < 300; ++i) {
      const double x = 1.0 + 2.5 * i / 300.0;
      points.push_back({LabelClass::kWall, Vec3(x, -1.6 - 0.3 * x + 0.005 * ((i % 5) - 2), 0.0), 0.01,
                        PointSource::kDense, 0});
    }
    AddVertex(points, {0, 0});
    PlanOptions options{.viewpoint_m = SampleViewpoint(truth, sample), .seed = seed};
    const PlanResult r = ReconstructPlan(points, options);
    const PlanScore s = ScorePlan(r.plan, truth);
    EXPECT_EQ(s.walls.predicted, 4) << "seed " << seed << "\n" << s.Table();
    EXPECT_EQ(s.walls.matched, 4) << "seed " << seed << "\n" << s.Table();
    EXPECT_LE(*s.wall_length.Max(), 0.01) << "seed " << seed << "\n" << s.Table();
  }
}

TEST(ReconstructPlan, ReportsUncertaintiesThatCoverTheErrors) {
  Plan truth = Rectangle();
  int covered = 0, total = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    SampleOptions sample;
    std::vector<ClassPoint> points = SamplePointsFromPlan(truth, sample, seed);
    PlanOptions options{.viewpoint_m = SampleViewpoint(truth, sample), .seed = seed};
    PlanResult r = ReconstructPlan(points, options);
    PlanScore s = ScorePlan(r.plan, truth);
    for (const WallMatch& m : s.wall_matches) {
      const PlanWall& w = r.plan.walls[m.predicted];
      ASSERT_TRUE(w.length_sigma_m.has_value());
      EXPECT_GT(*w.length_sigma_m, 0.0);
      covered += std::abs(m.predicted_length_m - m.truth_length_m) <= 3 * *w.length_sigma_m;
      ++total;
    }
    ASSERT_TRUE(r.plan.rooms[0].area_sigma_m2.has_value());
    for (const PlanOpening& o : r.plan.openings) EXPECT_GT(o.width_sigma_m.value_or(0), 0.0);
  }
  EXPECT_GE(covered, total * 8 / 10) << covered << " of " << total;
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

// Label-edge (boundary) points of every opening of `plan`: on the wall face
// at the label's edges (the casing's outer edges), every 5 cm in height, each
// moved along its viewing ray by up to ±`depth_error_m` (what stereo depth
// error does), as ComputeFramePoints makes them.
std::vector<ClassPoint> BoundaryPoints(const Plan& plan, const Vec3& view, double depth_error_m) {
  std::vector<ClassPoint> out;
  int k = 0;
  for (const PlanOpening& o : plan.openings) {
    const bool door = o.kind == OpeningKind::kDoor;
    const double casing = door ? 0.07 : 0.05;
    const Vec2 along = (o.end - o.start).normalized();
    const double sill = o.sill.value_or(0.0), top = sill + o.height.value_or(2.0);
    for (const Vec2& edge : {Vec2(o.start - casing * along), Vec2(o.end + casing * along)}) {
      for (double z = sill + 0.05; z < top; z += 0.05, ++k) {
        const Vec3 on_face(edge.x(), edge.y(), z);
        const double error = depth_error_m * ((k % 7) / 3.0 - 1.0);  // −1 … +1 of the bound.
        const Vec3 p = on_face + error * (on_face - view).normalized();
        out.push_back({door ? LabelClass::kDoor : LabelClass::kWindow, p, 0.03, PointSource::kBoundary, 0});
      }
    }
  }
  return out;
}

TEST(ReconstructPlan, OpeningWidthsComeFromLabelEdgesOnTheWall) {
  const Plan truth = Rectangle();
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
        points.push_back({door ? LabelClass::kDoor : LabelClass::kWindow, Vec3(xy.x(), xy.y(), z), 0.005,
                          PointSource::kDense, 0});
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

TEST(ReconstructPlan, TwoWindowsEitherSideOfANarrowPierStayTwo) {
  // Clear openings 0.25 m apart: their labels (casings included) 0.15 m,
  // closer than the gap that splits openings.
  Plan truth = PolygonPlan({{0, 0}, {4.5, 0}, {4.5, 3.6}, {0, 3.6}});
  AddOpening(truth, OpeningKind::kWindow, 2, 0.8, 1.3, 1.4, 0.9);
  AddOpening(truth, OpeningKind::kWindow, 2, 2.35, 1.2, 1.4, 0.9);
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

TEST(ReconstructPlan, AnOpenLeafDoesNotWidenTheDoor) {
  const Plan truth = Rectangle();
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
TEST(ReconstructPlan, AnOpenLeafHidingTheHingeSideGivesTheDoorItsWidth) {
  const Plan truth = Rectangle();
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

TEST(ReconstructPlan, KeepsNonManhattanWallsAtTheirAngle) {
  Plan truth = Trapezoid();
  PlanResult r = ReconstructPlan(SamplePointsFromPlan(truth, {}, 3), {.seed = 3});
  EXPECT_FALSE(r.summary.dominant_directions_deg.empty());
  PlanScore s = ScorePlan(r.plan, truth);
  EXPECT_EQ(s.walls.matched, 4) << s.Table();
  for (const WallMatch& m : s.wall_matches) EXPECT_LT(m.angle_deg, 0.5) << s.Table();
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

TEST(PlanOptions, DefaultsAreValidAndBadValuesAreNamed) {
  EXPECT_NO_THROW(PlanOptions{}.Check());
  try {
    PlanOptions{.epsilon_m = -1}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "PlanOptions.epsilon_m = -1, must be > 0");
  }
}

TEST(PlanSummary, BriefReportSaysWhatWasFound) {
  PlanResult r = ReconstructPlan(SamplePointsFromPlan(Rectangle(), {}, 2), {});
  std::string s = r.summary.BriefReport();
  EXPECT_EQ(s.rfind("4 walls (0 inferred), 3 openings, closed, 16.", 0), 0u) << s;
  EXPECT_NE(s.find("Manhattan"), std::string::npos) << s;
}

TEST(WallPiecesBetweenOpenings, CutsOutEveryOpening) {
  Plan p = Rectangle();
  auto pieces = WallPiecesBetweenOpenings(p, 0);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_NEAR(pieces[0].second, 0.4, 1e-12);
  EXPECT_NEAR(pieces[1].first, 1.3, 1e-12);
  EXPECT_NEAR(pieces[1].second, 4.5, 1e-12);
  EXPECT_EQ(WallPiecesBetweenOpenings(p, 3).size(), 1u);
}

}  // namespace
}  // namespace asbuilt
