#include "asbuilt/pano/pano_layout.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "asbuilt/formats/points_file.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// A rectangular room seen from a level camera: its plan corners (min, max)
// in a frame turned by rotation_deg from the pano frame.
struct BoxRoom {
  Vec2 min_m{-1.7, -2.3};
  Vec2 max_m{2.9, 1.6};
  double rotation_deg = 20.0;
  double camera_height_m = 1.4;
  double ceiling_height_m = 2.5;

  // Horizontal distance from the camera (the origin) to the wall along a
  // horizontal direction.
  double WallDistance(const Vec2& direction) const {
    const double a = DegToRad(-rotation_deg);
    const Vec2 d(std::cos(a) * direction.x() - std::sin(a) * direction.y(),
                 std::sin(a) * direction.x() + std::cos(a) * direction.y());
    double t = 1e9;
    for (int axis = 0; axis < 2; ++axis) {
      if (d[axis] > 1e-12) t = std::min(t, max_m[axis] / d[axis]);
      if (d[axis] < -1e-12) t = std::min(t, min_m[axis] / d[axis]);
    }
    return t;
  }

  // The room as an equirectangular photo: dark floor, light walls (each its
  // own shade), a white ceiling, a little noise.
  cv::Mat Render(int width_px, unsigned seed) const {
    const int rows = width_px / 2;
    cv::Mat out(rows, width_px, CV_8UC3);
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 3.0);
    for (int y = 0; y < rows; ++y) {
      for (int x = 0; x < width_px; ++x) {
        const Vec3 ray = DirectionFromEquirectPixel(Vec2(x, y), width_px, rows);
        const Vec2 horizontal = ray.head<2>().normalized();
        const double d = WallDistance(horizontal);
        const double slope = ray.z() / ray.head<2>().norm();
        cv::Vec3d bgr;
        if (slope < -camera_height_m / d) {
          bgr = {40, 70, 110};
        } else if (slope > (ceiling_height_m - camera_height_m) / d) {
          bgr = {235, 238, 240};
        } else {
          const double shade = 170 + 25 * std::abs(horizontal.x());
          bgr = {shade, shade + 5, shade + 10};
        }
        for (int c = 0; c < 3; ++c) out.at<cv::Vec3b>(y, x)[c] = cv::saturate_cast<uchar>(bgr[c] + noise(rng));
      }
    }
    return out;
  }
};

TEST(PanoLayoutOptions, DefaultsAreValid) { EXPECT_NO_THROW(PanoLayoutOptions{}.Check()); }

TEST(PanoLayoutOptions, CheckNamesTheBadField) {
  try {
    PanoLayoutOptions{.distance_bins = 2}.Check();
    FAIL() << "no throw";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("PanoLayoutOptions.distance_bins = 2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(PanoLayoutOptions{.jump_cost = -1}.Check(), InvalidArgument);
}

TEST(EstimatePanoLayout, RecoversABoxRoomsWallsAndCeilingFromItsEdges) {
  const BoxRoom room;
  const cv::Mat photo = room.Render(1024, 7);
  const PanoLayout layout = EstimatePanoLayout(photo, room.camera_height_m, cv::Mat(), {});
  EXPECT_NEAR(layout.ceiling_height_m, room.ceiling_height_m, 0.05) << layout.BriefReport();
  // The direction is as sharp as the distance bins (2 % apart) let it be.
  EXPECT_NEAR(layout.wall_direction_deg, room.rotation_deg, 1.0);
  ASSERT_EQ(layout.Columns(), 1024);
  std::vector<double> errors;
  for (int x = 0; x < layout.Columns(); ++x) {
    const Vec3 ray = DirectionFromEquirectPixel(Vec2(x, 255.5), 1024, 512);
    const double truth = room.WallDistance(ray.head<2>().normalized());
    errors.push_back(std::abs(layout.distance_m[x] / truth - 1.0));
  }
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.02) << "median relative distance error";
  EXPECT_LT(errors[errors.size() * 95 / 100], 0.06) << "95th percentile (columns at the room's corners)";
}

TEST(EstimatePanoLayout, ClosesABoxRoomIntoItsFourCorners) {
  const BoxRoom room;
  const PanoLayout layout =
      EstimatePanoLayout(room.Render(1024, 11), room.camera_height_m, cv::Mat(), {.close_polygon = true});
  ASSERT_EQ(layout.polygon_m.size(), 4u) << layout.BriefReport();
  const double a = DegToRad(room.rotation_deg);
  for (const Vec2& box :
       {room.min_m, Vec2(room.max_m.x(), room.min_m.y()), room.max_m, Vec2(room.min_m.x(), room.max_m.y())}) {
    const Vec2 corner(std::cos(a) * box.x() - std::sin(a) * box.y(), std::sin(a) * box.x() + std::cos(a) * box.y());
    double nearest = 1e9;
    for (const Vec2& p : layout.polygon_m) nearest = std::min(nearest, (p - corner).norm());
    EXPECT_LT(nearest, 0.08) << "corner " << corner.transpose();
  }
  // Every column's distance is then the polygon's.
  EXPECT_EQ(std::count(layout.supported.begin(), layout.supported.end(), true), layout.Columns());
}

TEST(EstimatePanoLayout, BridgesColumnsThePhotoDoesNotShowWithTheWallsBesideThem) {
  const BoxRoom room;
  cv::Mat photo = room.Render(1024, 5);
  // An open door leaf right before the lens hides 40° of the turn from
  // floor to ceiling: no edge there.
  photo(cv::Rect(300, 0, 114, 512)).setTo(cv::Scalar(60, 110, 170));
  auto gap_error = [&](const PanoLayout& layout) {
    double worst = 0.0;
    for (int x = 310; x < 404; ++x) {
      const Vec3 ray = DirectionFromEquirectPixel(Vec2(x, 255.5), 1024, 512);
      const double truth = room.WallDistance(ray.head<2>().normalized());
      worst = std::max(worst, std::abs(layout.distance_m[x] / truth - 1.0));
    }
    return worst;
  };
  const PanoLayout shown = EstimatePanoLayout(photo, room.camera_height_m, cv::Mat(), {});
  EXPECT_FALSE(shown.supported[357]) << "the hidden columns are not shown";
  const PanoLayout bridged =
      EstimatePanoLayout(photo, room.camera_height_m, cv::Mat(), {.close_polygon = true, .polygon_gaps_only = true});
  ASSERT_FALSE(bridged.polygon_m.empty()) << bridged.BriefReport();
  EXPECT_TRUE(bridged.supported[357]);
  EXPECT_LT(gap_error(bridged), 0.05) << "the walls beside the gap carry through it";
}

TEST(EstimatePanoLayout, FreePathsFindTheRoomToo) {
  const BoxRoom room{.rotation_deg = 0.0};
  const PanoLayout layout =
      EstimatePanoLayout(room.Render(1024, 3), room.camera_height_m, cv::Mat(), {.manhattan = false});
  EXPECT_NEAR(layout.ceiling_height_m, room.ceiling_height_m, 0.05);
  EXPECT_TRUE(std::isnan(layout.wall_direction_deg));
  int close = 0;
  for (int x = 0; x < layout.Columns(); ++x) {
    const Vec3 ray = DirectionFromEquirectPixel(Vec2(x, 255.5), 1024, 512);
    close += std::abs(layout.distance_m[x] / room.WallDistance(ray.head<2>().normalized()) - 1.0) < 0.05;
  }
  EXPECT_GT(close, 0.9 * layout.Columns());
}

TEST(EstimatePanoLayout, RefusesAPanoramaThatIsNotTwoToOne) {
  const cv::Mat square(256, 256, CV_8UC3, cv::Scalar(128, 128, 128));
  EXPECT_THROW(EstimatePanoLayout(square, 1.4, cv::Mat(), {}), InvalidArgument);
  const cv::Mat photo(256, 512, CV_8UC3, cv::Scalar(128, 128, 128));
  EXPECT_THROW(EstimatePanoLayout(photo, std::nan(""), cv::Mat(), {}), InvalidArgument);
}

TEST(LayoutViewLabels, DrawsTheWallBandAndKeepsOpeningsInsideIt) {
  PanoLayout layout{.camera_height_m = 1.4, .ceiling_height_m = 2.5, .distance_m = std::vector<double>(512, 2.0)};
  const PanoView view{.camera = {.width_px = 64, .height_px = 128, .fx = 32, .fy = 32, .cx = 31.5, .cy = 63.5}};
  cv::Mat segmented(128, 64, CV_8UC1, cv::Scalar(static_cast<int>(LabelClass::kWindow)));
  const cv::Mat labels = LayoutViewLabels(layout, view, segmented);
  // Column 31.5 looks straight ahead: the wall 2 m away spans elevations
  // −atan(1.4/2) … atan(1.1/2), rows cy + fy·tan.
  const int floor_row = static_cast<int>(63.5 + 32 * 1.4 / 2.0), ceiling_row = static_cast<int>(63.5 - 32 * 1.1 / 2.0);
  EXPECT_EQ(labels.at<uchar>(63, 31), static_cast<uchar>(LabelClass::kWindow));
  EXPECT_EQ(labels.at<uchar>(floor_row + 2, 31), static_cast<uchar>(LabelClass::kBackground));
  EXPECT_EQ(labels.at<uchar>(ceiling_row - 2, 31), static_cast<uchar>(LabelClass::kBackground));
  const cv::Mat plain = LayoutViewLabels(layout, view, cv::Mat());
  EXPECT_EQ(plain.at<uchar>(63, 31), static_cast<uchar>(LabelClass::kWall));
}

TEST(EquirectFromViewLabels, EachPixelTakesTheViewThatSeesIt) {
  const std::vector<PanoView> views =
      TurnInPlaceViews({.width_px = 64, .height_px = 64, .fx = 32, .views = 4, .yaw_step_deg = 90});
  std::vector<cv::Mat> labels;
  for (int i = 0; i < 4; ++i) labels.emplace_back(64, 64, CV_8UC1, cv::Scalar(i));
  const cv::Mat gathered = EquirectFromViewLabels(views, labels, 128);
  // Column u looks at yaw −2π(u + 0.5)/W: u ≈ 0 is view 0, u ≈ 96 (yaw 90°) view 1.
  EXPECT_EQ(gathered.at<uchar>(32, 0), 0);
  EXPECT_EQ(gathered.at<uchar>(32, 96), 1);
  EXPECT_EQ(gathered.at<uchar>(32, 64), 2);
  EXPECT_EQ(gathered.at<uchar>(0, 0), kLabelIgnore) << "the zenith is outside every view";
}

}  // namespace
}  // namespace asbuilt
