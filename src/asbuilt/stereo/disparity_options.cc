// DisparityOptions' field list (disparity.h); Check() stays in disparity.cc.

#include "asbuilt/stereo/disparity.h"

namespace asbuilt {

const FieldList<DisparityOptions>& DisparityOptionFields() {
  using O = DisparityOptions;
  static const FieldList<O> kList = {
      BindEnum(&O::matcher, {.name = "matcher", .description = "sgbm (semi-global) or bm (block matching, faster)."},
               {{"sgbm", DisparityMatcher::kSgbm}, {"bm", DisparityMatcher::kBm}}),
      Bind(&O::min_disparity_px, {.name = "min_disparity_px", .description = "Search range start, px."}),
      Bind(&O::num_disparities_px,
           {.name = "num_disparities_px",
            .description = "Search range width, a multiple of 16; larger sees nearer points, slower.",
            .minimum = 16.0}),
      Bind(&O::block_size_px,
           {.name = "block_size_px",
            .description = "Matching window side (odd); larger: smoother, fewer holes, blurrier edges.",
            .minimum = 1.0,
            .maximum = 255.0}),
      Bind(&O::p1_per_block_px, {.name = "p1_per_block_px",
                                 .description = "SGBM smoothness penalty P1 = p1 · channels · block².",
                                 .minimum = 1.0}),
      Bind(&O::p2_per_block_px, {.name = "p2_per_block_px",
                                 .description = "SGBM smoothness penalty P2 = p2 · channels · block²; > p1.",
                                 .minimum = 1.0}),
      Bind(&O::full_dp,
           {.name = "full_dp", .description = "SGBM: eight paths (MODE_HH; slow, memory-hungry) instead of three."}),
      Bind(&O::uniqueness_percent,
           {.name = "uniqueness_percent",
            .description = "Reject a match unless its cost beats the second best by this percentage.",
            .minimum = 0.0,
            .maximum = 100.0}),
      Bind(&O::speckle_window_px,
           {.name = "speckle_window_px",
            .description = "Speckle filter: invalidate blobs smaller than this whose disparity varies by more "
                           "than speckle_range_px (0: off).",
            .minimum = 0.0}),
      Bind(&O::speckle_range_px, {.name = "speckle_range_px",
                                  .description = "Speckle filter: disparity variation within a blob, px.",
                                  .minimum = 0.0}),
      Bind(&O::left_right_check, {.name = "left_right_check",
                                  .description = "Keep a left pixel only when the right view's disparity agrees."}),
      Bind(&O::max_left_right_diff_px,
           {.name = "max_left_right_diff_px", .description = "Left–right agreement needed, px.", .minimum = 0.0}),
      Bind(&O::wls_filter,
           {.name = "wls_filter", .description = "Edge-aware WLS filter (ximgproc): smooths and fills most holes."}),
      Bind(&O::wls_lambda, {.name = "wls_lambda", .description = "WLS smoothness strength.", .exclusive_minimum = 0.0}),
      Bind(&O::wls_sigma,
           {.name = "wls_sigma", .description = "WLS edge sensitivity (colour distance).", .exclusive_minimum = 0.0}),
      Bind(&O::fill_holes,
           {.name = "fill_holes",
            .description = "Fill holes along rows with the farther bounding disparity (occlusions are background)."}),
      Bind(&O::median_px, {.name = "median_px",
                           .description = "Median filter after filling: 3 or 5 px, 0 = off (only with fill_holes).",
                           .minimum = 0.0,
                           .maximum = 5.0}),
      Bind(&O::multi_scale,
           {.name = "multi_scale",
            .description = "A half-size pass narrows the full-size range to its 1st–99th percentile."}),
      Bind(&O::unround_subpixel,
           {.name = "unround_subpixel",
            .description = "SGBM: undo OpenCV's rounding of the sub-pixel offset toward zero, which reads half "
                           "the pixels 1/16 px too high (a mean +0.03 px: walls ~0.2 % too near)."}),
  };
  return kList;
}

}  // namespace asbuilt
