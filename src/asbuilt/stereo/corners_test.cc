#include "asbuilt/stereo/corners.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

TEST(CornerOptions, DefaultsAreValid) { EXPECT_NO_THROW(CornerOptions{}.Check()); }

TEST(FindClassCorners, FindsTheFourCornersOfAWindow) {
  cv::Mat labels(200, 300, CV_8UC1, cv::Scalar(1));
  cv::rectangle(labels, cv::Rect(100, 50, 80, 60), cv::Scalar(3), cv::FILLED);
  const auto corners = FindClassCorners(labels, cv::Mat(), {});
  std::vector<Vec2> window;
  for (const auto& c : corners) {
    if (c.label == LabelClass::kWindow) window.push_back(c.pixel);
  }
  ASSERT_EQ(window.size(), 4u);
  for (const Vec2& expected : {Vec2(100, 50), Vec2(179, 50), Vec2(179, 109), Vec2(100, 109)}) {
    double best = 1e9;
    for (const Vec2& p : window) best = std::min(best, (p - expected).norm());
    EXPECT_LT(best, 0.5) << expected.transpose();
  }
  // The wall region's own vertices are image-border cut-offs, dropped.
  for (const auto& c : corners) EXPECT_NE(c.label, LabelClass::kWall) << c.ToString();
}

TEST(MatchAlongRow, RecoversASubPixelShift) {
  cv::Mat noise(120, 200, CV_32F), left, right;
  cv::RNG rng(3);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(noise, left, cv::Size(7, 7), 1.5);
  for (double shift : {7.3, 12.75, 20.5}) {
    const cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, -shift, 0, 1, 0);
    cv::warpAffine(left, right, m, left.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
    const auto match = MatchAlongRow(left, right, Vec2(120, 60), 0, 40, {});
    ASSERT_TRUE(match.has_value()) << shift;
    EXPECT_NEAR(match->disparity_px, shift, 0.05) << match->ToString();
  }
}

TEST(MatchAlongRow, RejectsATexturelessPatch) {
  cv::Mat flat(100, 100, CV_32F, cv::Scalar(128));
  EXPECT_FALSE(MatchAlongRow(flat, flat, Vec2(60, 50), 0, 30, {}).has_value());
}

TEST(MatchAlongRow, RejectsRepeatedTexture) {
  // Vertical stripes every 8 px: every 8 px of disparity matches as well.
  cv::Mat stripes(100, 200, CV_32F);
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 200; ++x) stripes.at<float>(y, x) = 128 + 60 * std::sin(2 * 3.14159265 * x / 8.0);
  EXPECT_FALSE(MatchAlongRow(stripes, stripes, Vec2(120, 50), 0, 40, {}).has_value());
}

}  // namespace
}  // namespace asbuilt
