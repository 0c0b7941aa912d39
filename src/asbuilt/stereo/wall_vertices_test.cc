#include "asbuilt/stereo/wall_vertices.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// A gray image of two walls meeting at column `corner` (continuous: pixel u
// covers [u − 0.5, u + 0.5]), the left one brighter, each with its own
// shading slope, plus render noise; rows [edge_from, edge_to) show the
// corner, the others one continuous wall.
cv::Mat TwoWalls(double corner, std::uint64_t seed, int edge_from = 0, int edge_to = 160) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> noise(0.0f, 2.0f);
  cv::Mat img(160, 240, CV_32F);
  for (int v = 0; v < img.rows; ++v) {
    for (int u = 0; u < img.cols; ++u) {
      const double a = 150 + 0.05 * u, b = 118 - 0.03 * u;  // Shading on each wall.
      const double cover_left = std::clamp(corner - (u - 0.5), 0.0, 1.0);
      const bool edge = v >= edge_from && v < edge_to;
      img.at<float>(v, u) = static_cast<float>((edge ? cover_left * a + (1 - cover_left) * b : a) + noise(rng));
    }
  }
  return img;
}

TEST(FindWallVertices, FindsTheCornerColumnAndItsDisparityToSubPixel) {
  const cv::Mat labels(160, 240, CV_8UC1, cv::Scalar(1));
  for (const double corner : {120.3, 131.5, 97.8}) {
    const double disparity = 23.35;
    const cv::Mat left = TwoWalls(corner, 1), right = TwoWalls(corner - disparity, 2);
    const std::vector<WallVertex> found = FindWallVertices(left, right, labels, 0, 60, {});
    ASSERT_EQ(found.size(), 1u) << "corner " << corner;
    EXPECT_NEAR(found[0].u_left_px, corner, 0.2) << "corner " << corner;
    EXPECT_NEAR(found[0].disparity_px, disparity, 0.2) << "corner " << corner;
    EXPECT_LT(found[0].contrast, 0);  // Bright to dark.
    EXPECT_EQ(found[0].rows, 160);
  }
}

// An edge on a third of the rows (a painting's side, a shadow) is no corner;
// nor is one with something other than wall beside it (a door's jamb).
TEST(FindWallVertices, IgnoresEdgesThatAreNotWallWallCorners) {
  const cv::Mat labels(160, 240, CV_8UC1, cv::Scalar(1));
  const cv::Mat left = TwoWalls(120.3, 1, 40, 90), right = TwoWalls(100.3, 2, 40, 90);
  EXPECT_TRUE(FindWallVertices(left, right, labels, 0, 60, {}).empty());

  cv::Mat door_beside = labels.clone();
  door_beside.colRange(121, 240).setTo(2);
  const cv::Mat l2 = TwoWalls(120.5, 3), r2 = TwoWalls(100.5, 4);
  EXPECT_TRUE(FindWallVertices(l2, r2, door_beside, 0, 60, {}).empty());
  EXPECT_EQ(FindWallVertices(l2, r2, labels, 0, 60, {}).size(), 1u);
}

TEST(FindWallVertices, RejectsBadInputAndOptions) {
  const cv::Mat gray(20, 40, CV_32F, cv::Scalar(0)), labels(20, 40, CV_8UC1, cv::Scalar(1));
  EXPECT_THROW(FindWallVertices(gray, gray, cv::Mat(20, 41, CV_8UC1), 0, 10, {}), InvalidArgument);
  EXPECT_THROW(FindWallVertices(gray, gray, labels, 0, 10, {.min_sign_agreement = 0.3}), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
