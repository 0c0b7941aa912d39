#include "asbuilt/pano/perspective.h"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

constexpr int kW = 2048, kH = 1024;

Vec3 YawDirection(double yaw_deg) { return ForwardFromYaw(DegToRad(yaw_deg)); }

TEST(EquirectPixel, LeftEdgeLooksAlongPlusYAndColumnsTurnClockwise) {
  // Yaw 0 (+Y) at the left edge; yaw −90° (+X, clockwise) a quarter across;
  // yaw 180° (−Y) in the middle; yaw +90° (−X) three quarters across.
  EXPECT_NEAR(EquirectPixelFromDirection(YawDirection(0), kW, kH).x(), -0.5, 1e-9);
  EXPECT_NEAR(EquirectPixelFromDirection(Vec3(1, 0, 0), kW, kH).x(), kW / 4.0 - 0.5, 1e-9);
  EXPECT_NEAR(EquirectPixelFromDirection(Vec3(0, -1, 0), kW, kH).x(), kW / 2.0 - 0.5, 1e-9);
  EXPECT_NEAR(EquirectPixelFromDirection(Vec3(-1, 0, 0), kW, kH).x(), 3 * kW / 4.0 - 0.5, 1e-9);
  // The horizon is the middle row; straight up the top edge.
  EXPECT_NEAR(EquirectPixelFromDirection(Vec3(1, 0, 0), kW, kH).y(), kH / 2.0 - 0.5, 1e-9);
  EXPECT_NEAR(EquirectPixelFromDirection(Vec3(0, 1e-9, 1), kW, kH).y(), -0.5, 1e-6);
  EXPECT_NEAR(EquirectPixelFromDirection(Vec3(1, 0, 1), kW, kH).y(), kH / 4.0 - 0.5, 1e-9);
}

TEST(EquirectPixel, DirectionAndPixelRoundTrip) {
  for (double u : {0.0, 0.3, 511.5, 1024.0, 2047.0}) {
    for (double v : {0.0, 100.25, 511.5, 1023.0}) {
      const Vec2 back = EquirectPixelFromDirection(DirectionFromEquirectPixel({u, v}, kW, kH), kW, kH);
      EXPECT_NEAR(back.x(), u, 1e-6) << u << "," << v;
      EXPECT_NEAR(back.y(), v, 1e-6) << u << "," << v;
    }
  }
}

TEST(PanoView, OpticalAxisFollowsYawAndPitch) {
  PanoView view{.yaw_deg = 30};
  const Vec2 centre(view.camera.cx, view.camera.cy);
  EXPECT_LT((view.RayInWorld(centre).normalized() - YawDirection(30)).norm(), 1e-12);
  // The right edge looks clockwise of the axis (towards smaller yaw); the top row up.
  const Vec3 right = view.RayInWorld({view.camera.width_px - 1.0, view.camera.cy});
  EXPECT_LT(std::atan2(-right.x(), right.y()), DegToRad(30));
  EXPECT_GT(view.RayInWorld({view.camera.cx, 0}).z(), 0);
  view.pitch_deg = 20;
  const Vec3 axis = view.RayInWorld(centre).normalized();
  EXPECT_NEAR(axis.z(), std::sin(DegToRad(20)), 1e-12);
  EXPECT_NEAR(std::atan2(-axis.x(), axis.y()), DegToRad(30), 1e-12);
  // A level view's horizon is its middle row.
  EXPECT_NEAR(PanoView{.yaw_deg = 77}.RayInWorld({12, 239.5}).z(), 0, 1e-12);
}

TEST(TurnInPlaceViews, TurnsCounterClockwiseBySteps) {
  const std::vector<PanoView> views =
      TurnInPlaceViews({.width_px = 320, .height_px = 240, .fx = 200, .views = 4, .yaw_step_deg = 90, .pitch_deg = 10});
  ASSERT_EQ(views.size(), 4u);
  EXPECT_DOUBLE_EQ(views[3].yaw_deg, 270);
  EXPECT_DOUBLE_EQ(views[1].pitch_deg, 10);
  EXPECT_DOUBLE_EQ(views[0].camera.fy, 200);  // fy 0 = fx.
  EXPECT_DOUBLE_EQ(views[0].camera.cx, 159.5);
  EXPECT_DOUBLE_EQ(views[0].camera.cy, 119.5);
  EXPECT_EQ(views[2].ToString(), "PanoView(320x240 fx=200.0 yaw 180.0° pitch 10.0°)");
}

TEST(TurnInPlaceOptions, DefaultsAreValidAndBadFieldsAreNamed) {
  EXPECT_NO_THROW(TurnInPlaceOptions{}.Check());
  try {
    TurnInPlaceOptions{.pitch_deg = 95}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "TurnInPlaceOptions.pitch_deg = 95, must be in (-90, 90)");
  }
  EXPECT_THROW(TurnInPlaceOptions{.views = 0}.Check(), InvalidArgument);
  EXPECT_THROW(TurnInPlaceOptions{.fx = 0}.Check(), InvalidArgument);
}

// A grey panorama with a red vertical stripe at the column that looks along `yaw_deg`.
cv::Mat StripePanorama(double yaw_deg) {
  cv::Mat pano(kH, kW, CV_8UC3, cv::Scalar(90, 90, 90));
  const int u = static_cast<int>(std::lround(EquirectPixelFromDirection(YawDirection(yaw_deg), kW, kH).x()));
  for (int du = -3; du <= 3; ++du) pano.col((u + du + kW) % kW).setTo(cv::Scalar(0, 0, 255));
  return pano;
}

// Mean column of the red pixels in the view's middle row; NaN when none.
double RedColumn(const cv::Mat& view) {
  double sum = 0;
  int n = 0;
  const int v = view.rows / 2;
  for (int u = 0; u < view.cols; ++u) {
    const cv::Vec3b p = view.at<cv::Vec3b>(v, u);
    if (p[2] > 150 && p[1] < 100) {
      sum += u;
      ++n;
    }
  }
  return n ? sum / n : NAN;
}

TEST(RenderPanoView, PutsWhatLiesAtTheViewYawInTheMiddle) {
  const PanoView view{.yaw_deg = 30};
  EXPECT_NEAR(RedColumn(AsMat(RenderPanoView(AsImage(StripePanorama(30)), view))), view.camera.cx, 1.0);
  // A stripe 30° counter-clockwise of the axis (to the left, seen from the
  // camera) appears left of the middle, fx·tan 30° away: no mirror.
  const PanoView level{};
  EXPECT_NEAR(RedColumn(AsMat(RenderPanoView(AsImage(StripePanorama(30)), level))),
              level.camera.cx - level.camera.fx * std::tan(DegToRad(30)), 1.5);
  EXPECT_NEAR(RedColumn(AsMat(RenderPanoView(AsImage(StripePanorama(-30)), level))),
              level.camera.cx + level.camera.fx * std::tan(DegToRad(30)), 1.5);
}

TEST(RenderPanoView, WrapsAcrossTheSeam) {
  // Yaw 0 is the seam (left edge = right edge): the stripe on it is whole.
  const cv::Mat view = AsMat(RenderPanoView(AsImage(StripePanorama(0)), PanoView{}));
  EXPECT_NEAR(RedColumn(view), view.cols / 2.0 - 0.5, 1.0);
  // Just beside the stripe, the seam leaves no black or red seam line.
  for (int u = 0; u < view.cols; ++u) {
    const cv::Vec3b p = view.at<cv::Vec3b>(view.rows / 2, u);
    if (std::abs(u - 319.5) > 12) {
      EXPECT_EQ(p, cv::Vec3b(90, 90, 90)) << u;
    }
  }
}

TEST(RenderPanoView, AveragesALargePanoramaForASmallView) {
  // A one-pixel checkerboard averages to grey in a small view instead of aliasing.
  cv::Mat pano(kH, kW, CV_8UC3);
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u) pano.at<cv::Vec3b>(v, u) = (u + v) % 2 ? cv::Vec3b(255, 255, 255) : cv::Vec3b(0, 0, 0);
  const cv::Mat view = AsMat(RenderPanoView(
      AsImage(pano),
      PanoView{.camera = {.width_px = 64, .height_px = 48, .fx = 40, .fy = 40, .cx = 31.5, .cy = 23.5}}));
  cv::Scalar mean, stddev;
  cv::meanStdDev(view, mean, stddev);
  EXPECT_NEAR(mean[0], 127.5, 3);
  EXPECT_LT(stddev[0], 10);
}

// Label panoramas are sampled at the nearest pixel: every id in the view is
// one of the panorama's, and a region keeps its id up to its edge.
TEST(RenderPanoLabelView, TakesTheNearestIdAndBlendsNone) {
  cv::Mat labels(256, 512, CV_8UC1, cv::Scalar(0));
  labels(cv::Rect(0, 128, 512, 128)).setTo(1);  // Below the horizon: wall.
  labels(cv::Rect(200, 60, 40, 150)).setTo(3);  // A window across it.
  const PanoView view{.camera = {.width_px = 320, .height_px = 240, .fx = 150, .fy = 150, .cx = 159.5, .cy = 119.5},
                      .yaw_deg = -150};  // 150° clockwise from +Y: column 213 of 512, the window.
  const cv::Mat out = AsMat(RenderPanoLabelView(AsImage(labels), view));
  ASSERT_EQ(out.type(), CV_8UC1);
  int counts[256] = {};
  for (int v = 0; v < out.rows; ++v)
    for (int u = 0; u < out.cols; ++u) ++counts[out.at<std::uint8_t>(v, u)];
  EXPECT_GT(counts[0], 0);
  EXPECT_GT(counts[1], 0);
  EXPECT_GT(counts[3], 0);
  EXPECT_EQ(counts[0] + counts[1] + counts[3], out.rows * out.cols);  // No 2: nothing blended between 1 and 3.
  EXPECT_EQ(out.at<std::uint8_t>(119, 159), 3);
  EXPECT_EQ(out.at<std::uint8_t>(230, 5), 1);  // Low and to the left: wall beside the window.
  EXPECT_THROW(RenderPanoLabelView(AsImage(cv::Mat(256, 512, CV_8UC3, cv::Scalar(0))), view), InvalidArgument);
}

TEST(RenderPanoView, RejectsAPanoramaThatIsNotTwoToOne) {
  EXPECT_THROW(RenderPanoView(Image(100, 100, 3, PixelType::kU8), PanoView{}), InvalidArgument);
  EXPECT_THROW(RenderPanoView(Image(), PanoView{}), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
