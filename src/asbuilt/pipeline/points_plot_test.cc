#include "asbuilt/pipeline/points_plot.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/plan/sample.h"

namespace asbuilt {
namespace {

Plan PlotRoom(double shift_m) {
  Plan plan;
  std::vector<Vec2> c = {{0, 0}, {5, 0}, {5, 4}, {0, 4}};
  for (Vec2& p : c) p.x() += shift_m;
  for (int i = 0; i < 4; ++i) plan.walls.push_back({.start = c[i], .end = c[(i + 1) % 4], .height = 2.6});
  plan.openings.push_back({.kind = OpeningKind::kDoor,
                           .wall = 0,
                           .start = c[0] + Vec2(1, 0),
                           .end = c[0] + Vec2(1.9, 0),
                           .width = 0.9,
                           .height = 2.0,
                           .sill = 0.0});
  plan.rooms.push_back({.polygon = c, .area_m2 = 20});
  return plan;
}

cv::Mat DecodePlot(const std::string& png) {
  std::vector<unsigned char> bytes(png.begin(), png.end());
  return cv::imdecode(bytes, cv::IMREAD_COLOR);
}

// Pixels of a colour (BGR), within a tolerance per channel.
int CountPixels(const cv::Mat& img, const cv::Vec3b& bgr, int tolerance) {
  int n = 0;
  for (int y = 0; y < img.rows; ++y) {
    for (int x = 0; x < img.cols; ++x) {
      const cv::Vec3b& p = img.at<cv::Vec3b>(y, x);
      if (std::abs(p[0] - bgr[0]) <= tolerance && std::abs(p[1] - bgr[1]) <= tolerance &&
          std::abs(p[2] - bgr[2]) <= tolerance) {
        ++n;
      }
    }
  }
  return n;
}

TEST(PointsPlotPng, DrawsThePlanSheetWithPointsTruthAndRigsOver) {
  const Plan plan = PlotRoom(0.0);
  const std::vector<ClassPoint> points = SamplePointsFromPlan(plan, {}, 3);
  cv::Mat img = DecodePlot(PointsPlotPng(points, plan, PlotRoom(0.3), {Vec2(2.5, 2.0)}));
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(std::max(img.cols, img.rows), kPointsPlotSidePx);
  EXPECT_GT(CountPixels(img, {56, 56, 56}, 2), 1000);  // The sheet's wall poché.
  EXPECT_GT(CountPixels(img, {60, 170, 60}, 10), 50);  // Truth walls, dashed green.
  EXPECT_GT(CountPixels(img, {40, 40, 220}, 10), 30);  // The rig.
  EXPECT_GT(CountPixels(img, {40, 140, 240}, 40), 5);  // Door points.
}

TEST(PointsPlotPng, PointsAloneAreFramedByTheirCentralPart) {
  std::vector<ClassPoint> points;
  for (int i = 0; i < 200; ++i) points.push_back({.position_m = Vec3(10 + 0.01 * i, -3, 0.5)});
  cv::Mat img = DecodePlot(PointsPlotPng(points, Plan{}, std::nullopt, {}));
  ASSERT_FALSE(img.empty());
  EXPECT_LE(std::max(img.cols, img.rows), kPointsPlotSidePx);
}

TEST(PointsPlotPng, NothingToDrawIsEmpty) { EXPECT_EQ(PointsPlotPng({}, Plan{}, std::nullopt, {}), ""); }

}  // namespace
}  // namespace asbuilt
