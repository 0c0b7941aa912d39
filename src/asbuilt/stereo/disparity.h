#ifndef ASBUILT_STEREO_DISPARITY_H_
#define ASBUILT_STEREO_DISPARITY_H_

// Dense disparity for a rectified pair (PAPER.md §7, §5.3): OpenCV block
// matching (SGBM or BM) behind one call, with a left–right consistency check,
// optional WLS filtering (ximgproc) and an optional multi-scale pass (a coarse
// pass on half-size images narrows the full-resolution disparity range).
// Disparity d = u_left − u_right in pixels, positive for points in front.

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

namespace asbuilt {

enum class DisparityMatcher { kSgbm, kBm };

struct DisparityOptions {
  DisparityMatcher matcher = DisparityMatcher::kSgbm;
  // Search range [min_disparity_px, min_disparity_px + num_disparities_px);
  // num must be a multiple of 16. Larger ranges see nearer points, cost time.
  int min_disparity_px = 0;
  int num_disparities_px = 64;
  // Matching window side (odd). Larger: smoother, fewer holes, blurrier edges.
  int block_size_px = 5;
  // SGBM smoothness penalties per channel·pixel² of the block (P1 = p1 ·
  // channels · block², P2 likewise); P2 > P1.
  int p1_per_block_px = 8;
  int p2_per_block_px = 32;
  // SGBM: eight paths (MODE_HH, slow, memory-hungry) instead of the fast
  // three-way mode.
  bool full_dp = false;
  // Reject a match unless its cost beats the second best by this percentage.
  int uniqueness_percent = 10;
  // Speckle filter: blobs smaller than the window (px) whose disparity varies
  // by more than the range are invalidated (0 disables).
  int speckle_window_px = 100;
  int speckle_range_px = 2;
  // Left–right consistency: compute the right view's disparity too and keep a
  // left pixel only when both agree within max_left_right_diff_px.
  bool left_right_check = true;
  double max_left_right_diff_px = 1.0;
  // Edge-aware, confidence-weighted WLS filter (ximgproc) guided by the left
  // image: smooths and fills most holes (not the left band where the right
  // view has no match); `valid` still marks only the raw consistent pixels.
  bool wls_filter = false;
  double wls_lambda = 8000.0;  // Smoothness strength.
  double wls_sigma = 1.5;      // Edge sensitivity (colour distance).
  // Fill every hole along its row with the smaller (farther) of the valid
  // disparities bounding it — occlusions belong to the background. No holes
  // remain; `valid` still marks only the raw consistent pixels. Best measured
  // accuracy on Middlebury/ETH3D (bench/results/stereo.md) at no extra time.
  bool fill_holes = false;
  // Median filter (3 or 5 px; 0 = off) after filling: removes isolated
  // outliers; applied only when fill_holes is on (holes would spread).
  int median_px = 0;
  // Coarse pass at half size; the full-size range becomes the coarse 1st–99th
  // percentile (× 2, padded by 16 px) when that is narrower.
  bool multi_scale = false;

  // Throws InvalidArgument naming the field ("DisparityOptions.block_size_px = 4, must be odd").
  void Check() const;
  std::string ToString() const;
};

struct DisparityResult {
  // CV_32F, left view, pixels. NaN where no disparity (holes, occlusions);
  // with WLS or fill_holes, filled values too.
  cv::Mat disparity_px;
  // CV_8U, 255 where the raw matcher found a disparity that passed the
  // uniqueness, speckle and left–right checks.
  cv::Mat valid;
  int min_disparity_px = 0;  // The range actually searched.
  int num_disparities_px = 0;
  double valid_fraction = 0.0;  // Of all pixels.
  double seconds = 0.0;

  std::string ToString() const;
};

// Computes the left view's disparity. `left` and `right` are the rectified
// images, same size and type (CV_8UC1 or CV_8UC3). Throws InvalidArgument on
// mismatched or empty images or bad options.
DisparityResult ComputeDisparity(const cv::Mat& left, const cv::Mat& right,
                                 const DisparityOptions& options);

// A colour picture of a disparity map (turbo colour map over [lo, hi], NaN
// black); lo/hi default to the map's 1st/99th percentile.
cv::Mat ColorizeDisparity(const cv::Mat& disparity_px, double lo = NAN, double hi = NAN);

// Float maps as PFM (Middlebury/ETH3D: little-endian, bottom-to-top rows,
// NaN written as +inf = unknown). Written atomically.
void WritePfm(const cv::Mat& image_32f, const std::filesystem::path& path);
// Reads a one-channel PFM; +inf/NaN come back as NaN. Throws InputError.
cv::Mat ReadPfm(const std::filesystem::path& path);

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_DISPARITY_H_
