#include "asbuilt/mcp/plan_preview.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/util/error.h"

namespace asbuilt::mcp {
namespace {

Scene RoomWithDoorAndWindow() {
  Scene s;
  Room r;
  r.polygon = {{0, 0}, {6, 0}, {6, 8}, {0, 8}};
  r.openings.push_back({.kind = OpeningKind::kDoor, .wall = 1, .offset_m = 1, .width_m = 1});
  r.openings.push_back(
      {.kind = OpeningKind::kWindow, .wall = 2, .offset_m = 2, .width_m = 1.5, .height_m = 1.2, .sill_m = 0.9});
  s.rooms.push_back(r);
  s.furniture.push_back({.name = "table", .centre_m = Vec2(3, 4)});
  s.turn = TurnInPlace{.position_m = Vec3(3, 3, 1.5), .step_deg = 45};
  return s;
}

cv::Mat Decode(const std::string& png) {
  std::vector<unsigned char> bytes(png.begin(), png.end());
  return cv::imdecode(bytes, cv::IMREAD_COLOR);
}

TEST(RenderPlanPreviewPng, DrawsWallsFloorAndOpenings) {
  Scene s = RoomWithDoorAndWindow();
  std::string png = RenderPlanPreviewPng(s, {.width_px = 400});
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  cv::Mat img = Decode(png);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 400);
  // Aspect follows the room (6.4 × 8.4 m with walls): taller than wide.
  EXPECT_GT(img.rows, img.cols);
  // Dark wall pixels and window-blue pixels are present.
  int dark = 0, window = 0;
  for (int y = 0; y < img.rows; ++y) {
    for (int x = 0; x < img.cols; ++x) {
      cv::Vec3b c = img.at<cv::Vec3b>(y, x);
      if (c[0] < 70 && c[1] < 70 && c[2] < 70) ++dark;
      if (c[0] > 220 && c[1] > 200 && c[2] < 180) ++window;
    }
  }
  EXPECT_GT(dark, 1000);
  EXPECT_GT(window, 20);
}

TEST(RenderPlanPreviewPng, EmptySceneStillGivesAPicture) {
  cv::Mat img = Decode(RenderPlanPreviewPng(Scene{}, {.width_px = 256}));
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 256);
}

TEST(PlanPreviewOptions, DefaultsAreValidAndBadWidthIsNamed) {
  EXPECT_NO_THROW(PlanPreviewOptions{}.Check());
  try {
    PlanPreviewOptions{.width_px = 10}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "PlanPreviewOptions.width_px = 10, must be in 64..4096");
  }
}

}  // namespace
}  // namespace asbuilt::mcp
