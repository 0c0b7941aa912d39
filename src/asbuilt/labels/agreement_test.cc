#include "asbuilt/labels/agreement.h"

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

TEST(CompareLabels, CountsBandAroundAVerticalEdge) {
  // 10x10: left half wall (1), right half door (2). The band (1 px) is
  // columns 4 and 5: 20 pixels.
  cv::Mat exact(10, 10, CV_8UC1, cv::Scalar(1));
  exact.colRange(5, 10).setTo(2);
  cv::Mat predicted = exact.clone();
  predicted.at<std::uint8_t>(0, 5) = 1;  // A band error.
  predicted.at<std::uint8_t>(9, 9) = 0;  // An interior error.
  exact.at<std::uint8_t>(5, 0) = 255;    // Ignored.
  LabelAgreement a = CompareLabels(predicted, exact);
  EXPECT_EQ(a.pixels, 99);
  EXPECT_EQ(a.agree, 97);
  // The ignore pixel makes its neighbours band pixels too (a label change).
  EXPECT_EQ(a.band_pixels, 20 + 5);
  EXPECT_EQ(a.band_agree, 24);
  EXPECT_EQ(a.confusion[2][1], 1);
  EXPECT_EQ(a.confusion[2][0], 1);
  EXPECT_NEAR(a.Interior(), 73.0 / 74.0, 1e-12);
  EXPECT_EQ(a.ToString(), "agreement 97.98 % (band 96.00 %, interior 98.65 %) over 99 px");
}

TEST(CompareLabels, WiderBandCoversMore) {
  cv::Mat exact(10, 10, CV_8UC1, cv::Scalar(0));
  exact.colRange(5, 10).setTo(3);
  LabelAgreement a = CompareLabels(exact, exact, {.boundary_band_px = 2});
  EXPECT_EQ(a.band_pixels, 40);
  EXPECT_DOUBLE_EQ(a.Overall(), 1.0);
}

TEST(CompareLabels, RejectsMismatchedSizes) {
  EXPECT_THROW(CompareLabels(cv::Mat(3, 3, CV_8UC1), cv::Mat(3, 4, CV_8UC1)), InvalidArgument);
  EXPECT_THROW(CompareLabels(cv::Mat(3, 3, CV_8UC1), cv::Mat(3, 3, CV_8UC1), {.boundary_band_px = 0}), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
