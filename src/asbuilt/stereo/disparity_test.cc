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

// A plane at disparity `d_px` seen by two views sampled from one smooth
// texture (a sum of sinusoids up to 0.15 cycles/px along each axis): the right view's pixel x
// sees what the left's x + d sees, with no resampling of either image.
void SinusoidPair(double d_px, cv::Mat& left, cv::Mat& right) {
  cv::RNG rng(5);
  struct Wave {
    double fx, fy, phase, amplitude;
  };
  std::vector<Wave> waves;
  for (int i = 0; i < 24; ++i) {
    waves.push_back({rng.uniform(-0.15, 0.15) * 2 * M_PI, rng.uniform(-0.15, 0.15) * 2 * M_PI,
                     rng.uniform(0.0, 2 * M_PI), rng.uniform(4.0, 10.0)});
  }
  left.create(240, 320, CV_8UC1);
  right.create(240, 320, CV_8UC1);
  for (int y = 0; y < 240; ++y) {
    for (int x = 0; x < 320; ++x) {
      double l = 128, r = 128;
      for (const Wave& w : waves) {
        l += w.amplitude * std::sin(w.fx * x + w.fy * y + w.phase);
        r += w.amplitude * std::sin(w.fx * (x + d_px) + w.fy * y + w.phase);
      }
      left.at<unsigned char>(y, x) = cv::saturate_cast<unsigned char>(l);
      right.at<unsigned char>(y, x) = cv::saturate_cast<unsigned char>(r);
    }
  }
}

// SGBM's sub-pixel parabola is drawn towards whole disparities (pixel
// locking): on a textured plane its mean error swings with the true
// disparity's fraction, by up to 0.155 px here. The patch refinement's
// swings by 0.016 px at most (what is left is the interpolation's).
TEST(RefineDisparityAt, RemovesSgbmPixelLockingOnAFractionalPlane) {
  double worst_sgbm = 0, worst_refined = 0;
  for (int tenth = 0; tenth < 10; ++tenth) {
    const double shift = 12.0 + 0.1 * tenth;
    cv::Mat left, right, left_f, right_f;
    SinusoidPair(shift, left, right);
    left.convertTo(left_f, CV_32F);
    right.convertTo(right_f, CV_32F);
    const DisparityResult r = ComputeDisparity(left, right, {.num_disparities_px = 32});
    double sgbm = 0, refined = 0;
    int n = 0;
    for (int y = 20; y < 220; y += 4) {
      for (int x = 60; x < 300; x += 4) {
        const float d = r.disparity_px.at<float>(y, x);
        if (!std::isfinite(d)) continue;
        const auto s = RefineDisparityAt(left_f, right_f, x, y, d, 7);
        if (!s) continue;
        sgbm += d - shift;
        refined += s->disparity_px - shift;
        ++n;
      }
    }
    ASSERT_GT(n, 1000) << "shift " << shift;
    worst_sgbm = std::max(worst_sgbm, std::abs(sgbm / n));
    worst_refined = std::max(worst_refined, std::abs(refined / n));
  }
  std::printf("worst mean error over fractions: SGBM %.3f px, refined %.3f px\n", worst_sgbm, worst_refined);
  EXPECT_GT(worst_sgbm, 0.05);
  EXPECT_LT(worst_refined, 0.025);
}

TEST(RefineDisparityAt, RefusesAPatchWithoutTexture) {
  const cv::Mat flat(40, 80, CV_32FC1, cv::Scalar(128));
  EXPECT_FALSE(RefineDisparityAt(flat, flat, 40, 20, 5.0, 7));
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
