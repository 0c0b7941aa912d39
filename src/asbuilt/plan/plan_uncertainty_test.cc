// Plan stage 5, ± (plan_uncertainty.h), on its own and through ReconstructPlan.
#include "asbuilt/plan/plan_uncertainty.h"

#include <gtest/gtest.h>

#include "asbuilt/plan/plan_test_rooms.h"
#include "asbuilt/plan/reconstruct.h"
#include "asbuilt/plan/sample.h"
#include "asbuilt/plan/score.h"

namespace asbuilt {
namespace {

// A 4 × 3 m room whose wall 1 (x = 4, 3 m long) alone has an offset σ of
// 1 cm: moving it lengthens its two neighbours by as much and changes its
// own length and the opposite wall's not at all; the area moves by its
// length times its offset.
TEST(PropagateRingSigmas, AnOffsetSigmaMovesTheNeighboursAndTheArea) {
  auto line = [](const Vec2& c, double theta_deg) {
    WallLine l;
    l.c = c;
    l.theta = DegToRad(theta_deg);
    return l;
  };
  std::vector<WallLine> ring = {line({2, 0}, 0), line({4, 1.5}, 90), line({2, 3}, 180), line({0, 1.5}, 270)};
  ring[1].var_rho = 0.01 * 0.01;
  const RingSigmas s = PropagateRingSigmas(WallPoints{}, ring, {});
  ASSERT_EQ(s.wall_length_m.size(), 4u);
  EXPECT_NEAR(s.wall_length_m[0], 0.01, 1e-9);
  EXPECT_NEAR(s.wall_length_m[1], 0.0, 1e-9);
  EXPECT_NEAR(s.wall_length_m[2], 0.01, 1e-9);
  EXPECT_NEAR(s.wall_length_m[3], 0.0, 1e-9);
  EXPECT_NEAR(s.area_m2, 0.03, 1e-9);
}

// What a wall's points share does not average out: however many precise
// points a wall has, its offset keeps shared_sigma_fraction of their σ.
TEST(PropagateRingSigmas, AWallKeepsTheShareOfItsPointsSigmaTheyAllShare) {
  WallPoints walls;
  for (int i = 0; i < 1000; ++i) walls.points.push_back({Vec2(4, 0.003 * i), 1.0, 1e4, 0.01, 0.05, 1.0, true});
  std::vector<WallLine> ring = {WallLine{.c = {2, 0}, .theta = 0}, WallLine{.c = {4, 1.5}, .theta = kPi / 2},
                                WallLine{.c = {2, 3}, .theta = kPi}, WallLine{.c = {0, 1.5}, .theta = 1.5 * kPi}};
  for (int i = 0; i < 1000; ++i) ring[1].members.push_back(i);
  const RingSigmas s = PropagateRingSigmas(walls, ring, {.shared_sigma_fraction = 0.5});
  EXPECT_NEAR(s.wall_length_m[0], 0.005, 1e-9);
  EXPECT_NEAR(s.wall_length_m[2], 0.005, 1e-9);
  EXPECT_NEAR(s.area_m2, 3 * 0.005, 1e-9);
}

// A wall whose floor contacts lie 2 cm out and whose ceiling contacts lie
// 2 cm in (a label edge off at one of them) is off by about half that
// disagreement, however many contacts it has: with equal weights its offset
// σ becomes (4 cm)²/2 · (½² + ½²) = (2 cm)², above the shared floor.
TEST(PropagateRingSigmas, FloorAndCeilingContactsThatDisagreeWidenTheWallsOffset) {
  WallPoints walls;
  for (int i = 0; i < 1000; ++i) {
    const bool floor = i % 2 == 0;
    walls.points.push_back({Vec2(floor ? 4.02 : 3.98, 0.003 * i), floor ? 0.0 : 2.6, 1e4, 0.01, 0.05, 1.0, true});
  }
  std::vector<WallLine> ring = {WallLine{.c = {2, 0}, .theta = 0}, WallLine{.c = {4, 1.5}, .theta = kPi / 2},
                                WallLine{.c = {2, 3}, .theta = kPi}, WallLine{.c = {0, 1.5}, .theta = 1.5 * kPi}};
  for (int i = 0; i < 1000; ++i) ring[1].members.push_back(i);
  const RingSigmas s = PropagateRingSigmas(walls, ring, {.shared_sigma_fraction = 0.5});
  EXPECT_NEAR(s.wall_length_m[0], 0.02, 1e-6);
  EXPECT_NEAR(s.wall_length_m[2], 0.02, 1e-6);
  // Floor contacts alone show no disagreement: the shared share of σ stays.
  for (WallPoint& p : walls.points) p.z = 0.0;
  EXPECT_NEAR(PropagateRingSigmas(walls, ring, {.shared_sigma_fraction = 0.5}).wall_length_m[0], 0.005, 1e-6);
}

// A room-wide scale error s of the contacts about the rig moves every
// contact-placed wall by s times its distance from the rig, all together: a
// 4 × 3 m room seen from its centre gets σ = s · length on every wall and
// 2 s · area on the area. Without a viewpoint there is no such term.
TEST(PropagateRingSigmas, AContactScaleErrorMovesAllContactWallsTogether) {
  WallPoints walls;
  std::vector<WallLine> ring = {WallLine{.c = {2, 0}, .theta = 0}, WallLine{.c = {4, 1.5}, .theta = kPi / 2},
                                WallLine{.c = {2, 3}, .theta = kPi}, WallLine{.c = {0, 1.5}, .theta = 1.5 * kPi}};
  for (std::size_t l = 0; l < ring.size(); ++l) {
    walls.points.push_back({ring[l].c, 0.0, 1e4, 0.01, 0.05, 1.0, true});
    ring[l].members = {static_cast<int>(l)};
  }
  const PlanOptions o{.shared_sigma_fraction = 0, .contact_scale_sigma = 0.01, .viewpoint_m = Vec3(2, 1.5, 1.5)};
  const RingSigmas s = PropagateRingSigmas(walls, ring, o);
  EXPECT_NEAR(s.wall_length_m[0], 0.04, 1e-6);
  EXPECT_NEAR(s.wall_length_m[1], 0.03, 1e-6);
  EXPECT_NEAR(s.area_m2, 2 * 0.01 * 12, 1e-6);
  EXPECT_NEAR(PropagateRingSigmas(walls, ring, {.shared_sigma_fraction = 0, .contact_scale_sigma = 0.01}).area_m2, 0,
              1e-9);
}

// The ceiling's height H is estimated; a ceiling contact's distance is
// proportional to H − h, so its relative error moves every ceiling-placed
// wall out together (bench_rooms seed 22: H 33 mm high, every wall 3 % long
// at ± 1 %). Walls placed by ceiling contacts alone take the whole mode, a
// wall of half floor, half ceiling contacts half of it, floor-only walls none.
TEST(PropagateRingSigmas, TheCeilingHeightsErrorMovesCeilingContactWallsTogether) {
  std::vector<WallLine> ring = {WallLine{.c = {2, 0}, .theta = 0}, WallLine{.c = {4, 1.5}, .theta = kPi / 2},
                                WallLine{.c = {2, 3}, .theta = kPi}, WallLine{.c = {0, 1.5}, .theta = 1.5 * kPi}};
  auto room = [&](double z) {
    WallPoints walls;
    for (std::size_t l = 0; l < ring.size(); ++l) {
      walls.points.push_back({ring[l].c, z, 1e4, 0.01, 0.05, 1.0, true});
      ring[l].members = {static_cast<int>(l)};
    }
    return walls;
  };
  const PlanOptions o{.shared_sigma_fraction = 0,
                      .contact_scale_sigma = 0.0,
                      .ceiling_scale_sigma = 0.01,
                      .viewpoint_m = Vec3(2, 1.5, 1.5)};
  const RingSigmas ceiling = PropagateRingSigmas(room(2.6), ring, o);
  EXPECT_NEAR(ceiling.wall_length_m[0], 0.04, 1e-6);
  EXPECT_NEAR(ceiling.wall_length_m[1], 0.03, 1e-6);
  EXPECT_NEAR(ceiling.area_m2, 2 * 0.01 * 12, 1e-6);
  EXPECT_NEAR(PropagateRingSigmas(room(0.0), ring, o).area_m2, 0, 1e-9);
  // Half the weight on the ceiling: half the mode.
  WallPoints half = room(0.0);
  for (std::size_t l = 0; l < ring.size(); ++l) {
    half.points.push_back({ring[l].c, 2.6, 1e4, 0.01, 0.05, 1.0, true});
    ring[l].members.push_back(static_cast<int>(ring.size() + l));
  }
  EXPECT_NEAR(PropagateRingSigmas(half, ring, o).wall_length_m[0], 0.02, 1e-6);
}

// Auto options resolve by the labels' origin; set ones stay.
TEST(PlanOptions, ForLabelsResolvesTheAutoSigmasByTheLabelsOrigin) {
  const PlanOptions exact = PlanOptions{}.ForLabels(true), segmented = PlanOptions{}.ForLabels(false);
  EXPECT_EQ(exact.contact_scale_sigma, 0.0);
  EXPECT_EQ(exact.label_edge_sigma_mrad, 0.0);
  EXPECT_EQ(segmented.contact_scale_sigma, PlanOptions::kSegmentedContactScaleSigma);
  EXPECT_EQ(segmented.label_edge_sigma_mrad, PlanOptions::kSegmentedLabelEdgeSigmaMrad);
  EXPECT_EQ(PlanOptions{.contact_scale_sigma = 0.02}.ForLabels(true).contact_scale_sigma, 0.02);
}

TEST(PlanUncertainty, ReportsUncertaintiesThatCoverTheErrors) {
  Plan truth = RectangleRoom();
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

}  // namespace
}  // namespace asbuilt
