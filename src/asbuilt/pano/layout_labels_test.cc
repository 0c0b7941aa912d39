#include "asbuilt/pano/layout_labels.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/pano/pano_views.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

// A 4 × 4 m room around the camera (1.5 m high), ceiling 2.5 m: a door on
// the +Y wall (x −0.5…0.5, 0–2 m), a window on the −X wall (y −0.5…0.5,
// 1–2 m) and a passage on the −Y wall (x 0.5…1.5, 0–2.5 m).
ZindPanorama SquareRoom() {
  ZindPanorama p;
  p.pano_id = "pano_test";
  p.camera_height_m = 1.5;
  p.ceiling_height_m = 2.5;
  p.layout_raw.vertices_m = {{-2, -2}, {2, -2}, {2, 2}, {-2, 2}};  // Walls 0: −Y, 1: +X, 2: +Y, 3: −X.
  p.layout_raw.openings = {
      {.kind = ZindOpeningKind::kDoor, .start_m = {0.5, 2}, .end_m = {-0.5, 2}, .bottom_m = 0, .top_m = 2, .wall = 2},
      {.kind = ZindOpeningKind::kWindow,
       .start_m = {-2, 0.5},
       .end_m = {-2, -0.5},
       .bottom_m = 1,
       .top_m = 2,
       .wall = 3},
      {.kind = ZindOpeningKind::kOpening,
       .start_m = {0.5, -2},
       .end_m = {1.5, -2},
       .bottom_m = 0,
       .top_m = 2.5,
       .wall = 0},
  };
  return p;
}

// The label at the pixel where `point` (pano frame) appears in `view`.
int LabelAt(const cv::Mat& labels, const PanoView& view, const Vec3& point, double camera_height_m) {
  const Vec3 in_camera = view.WorldFromCamera().transpose() * (point - Vec3(0, 0, camera_height_m));
  const std::optional<Vec2> px = ProjectFromCamera(view.camera, in_camera);
  EXPECT_TRUE(px.has_value());
  const int u = static_cast<int>(std::lround(px->x())), v = static_cast<int>(std::lround(px->y()));
  EXPECT_TRUE(u >= 0 && v >= 0 && u < labels.cols && v < labels.rows) << point.transpose();
  return labels.at<std::uint8_t>(v, u);
}

TEST(LayoutLabels, LabelsWallsDoorsWindowsAndPassagesWhereTheyAre) {
  const ZindPanorama room = SquareRoom();
  const PanoView north{.yaw_deg = 0};  // Looks along +Y, at the door's wall.
  const cv::Mat labels = AsMat(LayoutLabels(room, north));
  ASSERT_EQ(labels.size(), cv::Size(640, 480));
  EXPECT_EQ(LabelAt(labels, north, {0, 2, 1.0}, 1.5), 2);    // Door.
  EXPECT_EQ(LabelAt(labels, north, {0, 2, 2.2}, 1.5), 1);    // Wall above the door.
  EXPECT_EQ(LabelAt(labels, north, {1.2, 2, 1.0}, 1.5), 1);  // Wall beside it.
  const PanoView down{.yaw_deg = 0, .pitch_deg = -40};       // A level view sees no floor in this room.
  EXPECT_EQ(LabelAt(AsMat(LayoutLabels(room, down)), down, {0.3, 1.2, 0}, 1.5), 0);  // Floor.
  EXPECT_EQ(LabelAt(AsMat(LayoutLabels(room, down)), down, {0.3, 2, 0.3}, 1.5), 2);  // Door.
  EXPECT_EQ(labels.at<std::uint8_t>(0, 320), 0);  // Ceiling (the top row looks 31° up).
  const PanoView west{.yaw_deg = 90};             // Looks along −X.
  const cv::Mat w = AsMat(LayoutLabels(room, west));
  EXPECT_EQ(LabelAt(w, west, {-2, 0, 1.5}, 1.5), 3);  // Window.
  EXPECT_EQ(LabelAt(w, west, {-2, 0, 0.5}, 1.5), 1);  // Wall below the sill.
  EXPECT_EQ(LabelAt(w, west, {-2, 1.5, 0.5}, 1.5), 1);
  const PanoView south{.yaw_deg = 180};
  const cv::Mat s = AsMat(LayoutLabels(room, south));
  EXPECT_EQ(LabelAt(s, south, {1.0, -2, 1.0}, 1.5), kPassageLabel);
  EXPECT_EQ(LabelAt(s, south, {-1.0, -2, 1.0}, 1.5), 1);
  // Every pixel is one of the five ids.
  for (const cv::Mat* m : {&labels, &w, &s}) {
    for (int v = 0; v < m->rows; ++v)
      for (int u = 0; u < m->cols; ++u) {
        const int l = m->at<std::uint8_t>(v, u);
        ASSERT_TRUE(l <= 3 || l == 255) << l;
      }
  }
}

TEST(LayoutLabels, NearestWallHidesTheWallsBehindIt) {
  // A room with a notch (x 1…2, y 1…2) cut from its east side, and a door on
  // the east wall behind the notch (x = 2, y 2.5…3.5), hidden from the camera.
  ZindPanorama room = SquareRoom();
  room.layout_raw.vertices_m = {{-2, -2}, {2, -2}, {2, 1}, {1, 1}, {1, 2}, {2, 2}, {2, 4}, {-2, 4}};
  room.layout_raw.openings = {
      {.kind = ZindOpeningKind::kDoor, .start_m = {2, 2.5}, .end_m = {2, 3.5}, .bottom_m = 0, .top_m = 2.5, .wall = 5}};
  // Towards (2, 3, 1.5): through the notch's wall (x = 1, y = 1.5) first.
  EXPECT_EQ(LayoutLabelOfRay(room, room.layout_raw, Vec3(2, 3, 0)), 1);
  // Steeply up: the notch's wall at 1.8 m distance, 3.5 m high: the ceiling first.
  EXPECT_EQ(LayoutLabelOfRay(room, room.layout_raw, Vec3(1, 1.5, 2)), 0);
  EXPECT_EQ(LayoutLabelOfRay(room, room.layout_raw, Vec3(0, 0, 1)), 0);   // Straight up.
  EXPECT_EQ(LayoutLabelOfRay(room, room.layout_raw, Vec3(0, 0, -1)), 0);  // Straight down.
  // With the notch gone the door is seen.
  room.layout_raw.vertices_m = {{-2, -2}, {2, -2}, {2, 4}, {-2, 4}};
  room.layout_raw.openings[0].wall = 1;
  EXPECT_EQ(LayoutLabelOfRay(room, room.layout_raw, Vec3(2, 3, 0)), 2);
}

TEST(LayoutLabels, EquirectLabelsAgreeWithTheViews) {
  const ZindPanorama room = SquareRoom();
  const cv::Mat equirect = AsMat(LayoutLabelsEquirect(room, 720, 360));
  // The door's centre (0, 2, 1): yaw 0 → left edge column, below the horizon.
  const Vec2 door = EquirectPixelFromDirection(Vec3(0, 2, 1.0 - 1.5), 720, 360);
  EXPECT_EQ(equirect.at<std::uint8_t>(static_cast<int>(std::lround(door.y())), 0), 2);
  const Vec2 window = EquirectPixelFromDirection(Vec3(-2, 0, 0), 720, 360);  // Yaw +90°: 3/4 across.
  EXPECT_EQ(
      equirect.at<std::uint8_t>(static_cast<int>(std::lround(window.y())), static_cast<int>(std::lround(window.x()))),
      3);
  EXPECT_NEAR(window.x(), 539.5, 1e-9);
}

// The real check of the pano frame (formats/zind.h) and of the views: on the
// sample tour's bonus room, the closed wooden door's label must fall on the
// orange-brown wood in the photo, not on the white wall beside it (a mirror
// or a wrong yaw would put it there).
TEST(LayoutLabels, PutTheBonusRoomsWoodenDoorOnTheWoodInThePhoto) {
  const fs::path tour_dir = fs::path(ASBUILT_SHARED_DATA_DIR) / "zind_sample_tour";
  if (!fs::exists(tour_dir / "zind_data.json")) GTEST_SKIP() << "shared data not present: " << tour_dir;
  const ZindTour tour = ReadZindTour(tour_dir);
  const ZindPanorama& room = *tour.Find("pano_15");
  const ZindOpening& door = room.layout_raw.openings[1];  // 0.81 m, closed, wood.
  ASSERT_NEAR(door.Width(), 0.81, 0.01);
  const Vec2 centre = 0.5 * (door.start_m + door.end_m);
  const PanoView view{.yaw_deg = RadToDeg(std::atan2(-centre.x(), centre.y()))};
  const cv::Mat photo = AsMat(RenderPanoView(ReadEquirect(room.image), view));
  const cv::Mat labels = AsMat(LayoutLabels(room, view));
  // Mean red − blue over door pixels and over wall pixels.
  double sum[4] = {0, 0, 0, 0};
  int n[4] = {0, 0, 0, 0};
  for (int v = 0; v < labels.rows; ++v)
    for (int u = 0; u < labels.cols; ++u) {
      const int l = labels.at<std::uint8_t>(v, u);
      if (l > 3) continue;
      const cv::Vec3b p = photo.at<cv::Vec3b>(v, u);
      sum[l] += p[2] - p[0];
      ++n[l];
    }
  ASSERT_GT(n[2], 20000);
  ASSERT_GT(n[1], 20000);
  const double door_warmth = sum[2] / n[2], wall_warmth = sum[1] / n[1];
  EXPECT_GT(door_warmth, 60) << "wall " << wall_warmth;
  EXPECT_GT(door_warmth, wall_warmth + 30) << "door " << door_warmth;
  // The door is in the middle of the view, standing on the floor.
  EXPECT_EQ(labels.at<std::uint8_t>(240, 320), 2);
}

TEST(DrawLabelOverlay, ColoursLabelledPixelsOnly) {
  const cv::Mat image(2, 3, CV_8UC3, cv::Scalar(100, 100, 100));
  const cv::Mat labels = (cv::Mat_<std::uint8_t>(2, 3) << 0, 1, 2, 3, 255, 0);
  const cv::Mat out = AsMat(DrawLabelOverlay(AsImage(image), AsImage(labels), 0.5));
  EXPECT_EQ(out.at<cv::Vec3b>(0, 0), cv::Vec3b(100, 100, 100));
  EXPECT_EQ(out.at<cv::Vec3b>(0, 1), cv::Vec3b(177, 114, 50));
  EXPECT_EQ(out.at<cv::Vec3b>(1, 0), cv::Vec3b(50, 50, 177));
  EXPECT_EQ(out.at<cv::Vec3b>(1, 1), cv::Vec3b(114, 114, 114));
  EXPECT_THROW(DrawLabelOverlay(AsImage(image), AsImage(cv::Mat(3, 3, CV_8U))), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
