#ifndef ASBUILT_STEREO_DISPARITY_H_
#define ASBUILT_STEREO_DISPARITY_H_

// Dense disparity for a rectified pair (PAPER.md §7, §5.3): OpenCV block
// matching (SGBM or BM) behind one call, with a left–right consistency check,
// optional WLS filtering (ximgproc) and an optional multi-scale pass (a coarse
// pass on half-size images narrows the full-resolution disparity range).
// Disparity d = u_left − u_right in pixels, positive for points in front.

#include <filesystem>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "asbuilt/util/fields.h"

namespace asbuilt {

enum class DisparityMatcher { kSgbm, kBm };

struct DisparityOptions {
  DisparityMatcher matcher = DisparityMatcher::kSgbm;  // SGBM (semi-global) or BM (block matching, faster).
  int min_disparity_px = 0;                            // Search range start, px.
  int num_disparities_px = 64;          // Search range width (multiple of 16); larger sees nearer points, slower.
  int block_size_px = 5;                // Matching window side (odd); larger: smoother, fewer holes, blurrier edges.
  int p1_per_block_px = 8;              // SGBM smoothness penalty P1 = p1 · channels · block²…
  int p2_per_block_px = 32;             // …and P2 likewise; P2 > P1.
  bool full_dp = false;                 // SGBM: eight paths (MODE_HH; slow, memory-hungry) instead of three.
  int uniqueness_percent = 10;          // Reject a match unless its cost beats the second best by this %.
  int speckle_window_px = 100;          // Speckle filter: invalidate blobs smaller than this (0: off)…
  int speckle_range_px = 2;             // …whose disparity varies by more than this, px.
  bool left_right_check = true;         // Keep a left pixel only when the right view's disparity agrees…
  double max_left_right_diff_px = 1.0;  // …within this, px.
  bool wls_filter = false;              // Edge-aware WLS filter (ximgproc): smooths, fills most holes.
  double wls_lambda = 8000.0;           // WLS smoothness strength.
  double wls_sigma = 1.5;               // WLS edge sensitivity (colour distance).
  bool fill_holes = false;              // Fill holes along rows with the farther bounding disparity (background).
  int median_px = 0;                    // Median filter after filling (3 or 5; 0: off; only with fill_holes).
  bool multi_scale = false;             // A half-size pass narrows the full-size range (coarse 1st–99th percentile).
  bool unround_subpixel =
      true;  // SGBM: undo OpenCV's sub-pixel rounding (+1/16 px on half the pixels, ~+0.03 px mean).

  // Throws InvalidArgument naming the field ("DisparityOptions.block_size_px = 4, must be odd").
  void Check() const;
  std::string ToString() const;
};

// Its field list (disparity_options.cc); `asbuilt points` takes it under
// `disparity.`, `asbuilt survey` under `points.disparity.`. `valid` of the
// result marks only raw consistent pixels whatever the filters; docs/stereo.md,
// "Option notes", says which filters measured best.
const FieldList<DisparityOptions>& DisparityOptionFields();

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
DisparityResult ComputeDisparity(const cv::Mat& left, const cv::Mat& right, const DisparityOptions& options);

// A sub-pixel disparity refined from the images themselves.
struct SubpixelDisparity {
  double disparity_px = 0.0;
  double left_u_px = 0.0;  // The left column it belongs to (within half a pixel of the one asked).
  double sigma_px = 0.0;   // 1σ from the residual of the fit and the patches' gradients.
};

// Refines the disparity d0 of left pixel (u, v) by Gauss–Newton on the
// zero-mean, unit-variance difference of (2r+1)² patches, a 1-D
// Lucas–Kanade along the row: unlike SGBM's cost parabola it is not drawn
// towards whole pixels. Symmetric: for d = whole + e both views are sampled
// (bilinear) half of e apart from their pixels, the left at u + e/2, so the
// disparity is that of column u + e/2 (`left_u_px`). `left_gray`,
// `right_gray` CV_32FC1 of one size. nullopt when a patch leaves the image or
// has no texture (σ below half a gray level), or the estimate moves more
// than 1 px from d0; it stops after `iterations` steps or a step under
// 0.001 px.
std::optional<SubpixelDisparity> RefineDisparityAt(const cv::Mat& left_gray, const cv::Mat& right_gray, int u, int v,
                                                   double d0, int radius_px, int iterations = 10);

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
