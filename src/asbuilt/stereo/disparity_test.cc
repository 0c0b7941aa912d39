#include "asbuilt/stereo/disparity.h"

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// A textured pair whose right view is the left shifted by `shift_px`.
void ShiftedPair(double shift_px, cv::Mat& left, cv::Mat& right) {
  cv::Mat noise(240, 320, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(noise, left, cv::Size(5, 5), 1.0);
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -shift_px, 0, 1, 0);
  cv::warpAffine(left, right, shift, left.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
}

TEST(DisparityOptions, DefaultsAreValid) { EXPECT_NO_THROW(DisparityOptions{}.Check()); }

TEST(DisparityOptions, RejectsEvenBlockByName) {
  try {
    DisparityOptions{.block_size_px = 4}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("block_size_px = 4"), std::string::npos);
  }
}

TEST(ComputeDisparity, RecoversAConstantShift) {
  cv::Mat left, right;
  ShiftedPair(12.0, left, right);
  for (bool wls : {false, true}) {
    const DisparityResult r = ComputeDisparity(left, right, {.num_disparities_px = 32, .wls_filter = wls});
    EXPECT_GT(r.valid_fraction, 0.7);
    int near = 0, total = 0;
    for (int y = 20; y < 220; ++y) {
      for (int x = 60; x < 300; ++x) {
        const float d = r.disparity_px.at<float>(y, x);
        if (std::isfinite(d)) {
          ++total;
          near += std::abs(d - 12.0) < 0.5;
        }
      }
    }
    EXPECT_GT(near, 0.95 * total) << "wls " << wls;
  }
}

// Mean disparity error over the valid middle of a shifted pair.
double MeanDisparityError(const DisparityOptions& options, double shift_px) {
  cv::Mat left, right;
  ShiftedPair(shift_px, left, right);
  const DisparityResult r = ComputeDisparity(left, right, options);
  double sum = 0;
  int n = 0;
  for (int y = 20; y < 220; ++y) {
    for (int x = 60; x < 300; ++x) {
      const float d = r.disparity_px.at<float>(y, x);
      if (std::isfinite(d)) {
        sum += d - shift_px;
        ++n;
      }
    }
  }
  return n > 0 ? sum / n : NAN;
}

// OpenCV's SGBM rounds its sub-pixel offset toward zero (disparity.cc,
// UnroundSgbm): over a plane's fractional disparities 12.0…12.9 it reads
// 1/32 px high on average; unrounded the mean is within 0.01 px. (What stays
// per fraction is the pixel locking of the parabola, up to ±0.15 px, which
// averages out over a wall seen across many fractions.)
TEST(ComputeDisparity, UnroundedSgbmIsUnbiasedOverFractionalDisparities) {
  for (bool unround : {false, true}) {
    const DisparityOptions options{.num_disparities_px = 32, .unround_subpixel = unround};
    double sum = 0;
    for (int tenth = 0; tenth < 10; ++tenth) sum += MeanDisparityError(options, 12.0 + 0.1 * tenth);
    const double bias = sum / 10;
    if (unround) {
      EXPECT_LT(std::abs(bias), 0.01) << "unrounded";
    } else {
      EXPECT_GT(bias, 0.02) << "OpenCV's rounding";
    }
  }
}

TEST(ComputeDisparity, MultiScaleNarrowsTheRange) {
  cv::Mat left, right;
  ShiftedPair(10.0, left, right);
  const DisparityResult r = ComputeDisparity(left, right, {.num_disparities_px = 128, .multi_scale = true});
  EXPECT_LT(r.num_disparities_px, 128);
  EXPECT_NEAR(r.disparity_px.at<float>(120, 200), 10.0, 0.5);
}

TEST(ComputeDisparity, BackgroundFillLeavesNoHolesAndKeepsValidMask) {
  cv::Mat left, right;
  ShiftedPair(12.0, left, right);
  const DisparityResult r =
      ComputeDisparity(left, right, {.num_disparities_px = 32, .fill_holes = true, .median_px = 5});
  EXPECT_EQ(cv::countNonZero(r.disparity_px == r.disparity_px), static_cast<int>(r.disparity_px.total()));
  // The left band (no match possible) is filled but not marked valid.
  EXPECT_EQ(r.valid.at<unsigned char>(100, 2), 0);
  EXPECT_NEAR(r.disparity_px.at<float>(100, 2), 12.0, 1.0);
}

TEST(ComputeDisparity, MismatchedImagesAreInvalidArguments) {
  EXPECT_THROW(ComputeDisparity(cv::Mat(10, 10, CV_8UC1), cv::Mat(10, 12, CV_8UC1), {}), InvalidArgument);
}

TEST(Pfm, RoundTripsValuesAndHoles) {
  cv::Mat d(3, 4, CV_32F, cv::Scalar(1.5f));
  d.at<float>(1, 2) = NAN;
  d.at<float>(0, 0) = 42.25f;
  const auto path = std::filesystem::temp_directory_path() / "asbuilt_stereo_test.pfm";
  WritePfm(d, path);
  const cv::Mat back = ReadPfm(path);
  ASSERT_EQ(back.size(), d.size());
  EXPECT_FLOAT_EQ(back.at<float>(0, 0), 42.25f);
  EXPECT_TRUE(std::isnan(back.at<float>(1, 2)));
  EXPECT_FLOAT_EQ(back.at<float>(2, 3), 1.5f);
  std::filesystem::remove(path);
}

TEST(ColorizeDisparity, PaintsHolesBlack) {
  cv::Mat d(2, 2, CV_32F, cv::Scalar(5.0f));
  d.at<float>(0, 1) = NAN;
  d.at<float>(1, 1) = 9.0f;
  const cv::Mat c = ColorizeDisparity(d);
  EXPECT_EQ(c.type(), CV_8UC3);
  EXPECT_EQ(c.at<cv::Vec3b>(0, 1), cv::Vec3b(0, 0, 0));
}

}  // namespace
}  // namespace asbuilt
