#include "asbuilt/plan/label_points.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "asbuilt/plan/reconstruct.h"
#include "asbuilt/plan/score.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

fs::path RoomDir(const char* room) { return fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public" / room; }

TEST(PointsFromLabelledDepth, PutsWallPointsOnTheTruthWalls) {
  fs::path dir = RoomDir("p01_rect_1door_2win");
  if (!fs::exists(dir)) GTEST_SKIP() << "shared data not present: " << dir;
  Capture capture = ReadCapture(dir / "capture.json");
  capture.frames.resize(1);
  std::vector<ClassPoint> points = PointsFromLabelledDepth(capture, {.stride_px = 8});
  ASSERT_GT(points.size(), 500u);
  Plan truth = ReadPlan(dir / "truth.json");
  int near = 0, walls = 0;
  for (const ClassPoint& p : points) {
    if (p.label != LabelClass::kWall) continue;
    ++walls;
    double best = 1e9;
    for (const PlanWall& w : truth.walls) {
      Vec2 d = (w.end - w.start).normalized();
      best = std::min(best, std::abs(Vec2(-d.y(), d.x()).dot(p.position_m.head<2>() - w.start)));
    }
    near += best < 0.02;  // Skirting boards protrude ~1 cm.
  }
  EXPECT_GT(near, walls * 95 / 100) << near << " of " << walls;
}

TEST(PointsFromLabelledDepth, NamesTheFrameWithoutLabels) {
  Capture capture;
  capture.base_dir = "/nonexistent";
  capture.frames.push_back({.index = 0, .left = "l.png", .right = "r.png"});
  try {
    PointsFromLabelledDepth(capture);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems()[0].field_path, "frames[0]");
  }
}

// The "exact labels" upper bound: plans from back-projected labelled pixels
// of the Blender rooms meet the targets.
TEST(ReconstructPlan, MeetsTheTargetsFromExactBlenderLabels) {
  for (const char* room : {"p01_rect_1door_2win", "p02_L_shape"}) {
    fs::path dir = RoomDir(room);
    if (!fs::exists(dir)) GTEST_SKIP() << "shared data not present: " << dir;
    Capture capture = ReadCapture(dir / "capture.json");
    std::vector<ClassPoint> points = PointsFromLabelledDepth(capture, {.stride_px = 3});
    PlanOptions options{.viewpoint_m = capture.frames[0].position_m};
    PlanResult r = ReconstructPlan(points, options);
    Plan truth = ReadPlan(dir / "truth.json");
    PlanScore s = ScorePlan(r.plan, truth);
    std::printf("%s: %s\n%s\n%s", room, r.summary.BriefReport().c_str(), s.ToString().c_str(), s.Table().c_str());
    EXPECT_EQ(s.walls.matched, s.walls.truth) << room << "\n" << s.Table();
    EXPECT_EQ(s.walls.predicted, s.walls.truth) << room << "\n" << s.Table();
    EXPECT_LE(*s.wall_length.Median(), 0.01) << room;
    EXPECT_LE(*s.wall_length.Max(), 0.03) << room;
    EXPECT_EQ(s.doors.matched, s.doors.truth) << room;
    EXPECT_EQ(s.windows.matched, s.windows.truth) << room;
    EXPECT_LE(*s.opening_width.Median(), 0.02) << room;
  }
}

}  // namespace
}  // namespace asbuilt
