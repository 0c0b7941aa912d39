#ifndef ASBUILT_STEREO_CORNERS_H_
#define ASBUILT_STEREO_CORNERS_H_

// Component corners from a segmentation (PAPER.md §7): per class, binarize →
// outer contours → polygon approximation → corners refined to sub-pixel on
// the image; and matching along the epipolar line of a rectified pair (same
// row ± tolerance) by normalised cross-correlation of a local patch, with
// sub-pixel refinement and rejection of weak or ambiguous matches.

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/formats/points_file.h"
#include "asbuilt/geometry/rig.h"

namespace asbuilt {

struct CornerOptions {
  // Regions smaller than this (pixels) are ignored (specks, slivers).
  int min_region_area_px = 150;
  // approxPolyDP tolerance: max(approx_epsilon_px, fraction · perimeter).
  // Larger keeps fewer corners; smaller keeps noise-induced vertices.
  double approx_epsilon_px = 2.0;
  double approx_epsilon_fraction = 0.004;
  // Vertices within this many pixels of the image border are cut-offs by the
  // frame, not corners of the component, and are dropped.
  int border_margin_px = 6;
  // Sub-pixel refinement on the gray image (cornerSubPix) with a window of
  // (2r+1)²; a refinement that moves farther than max_refine_shift_px is
  // discarded (the label vertex is kept).
  int refine_radius_px = 3;
  double max_refine_shift_px = 1.5;

  void Check() const;
};

struct ClassCorner {
  LabelClass label = LabelClass::kWall;
  Vec2 pixel = Vec2::Zero();  // Left view, OpenCV pixel centres.
  int region = 0;             // Index of the contour it came from.
  bool refined = false;       // cornerSubPix moved it.

  std::string ToString() const;
};

// Corners of every wall/door/window region in a label image (CV_8U label
// ids). `gray` (CV_8U, same size) is used for the sub-pixel refinement; pass
// an empty Mat to keep the label vertices. Throws InvalidArgument on
// mismatched sizes or types.
std::vector<ClassCorner> FindClassCorners(const cv::Mat& labels, const cv::Mat& gray,
                                          const CornerOptions& options);

struct RowMatchOptions {
  // Patch (2r+1)² compared by zero-mean normalised cross-correlation.
  int patch_radius_px = 5;
  // Also search rows v ± tolerance (for imperfect rectification).
  int row_tolerance_px = 0;
  // Best correlation must reach min_score, and beat every other peak farther
  // than 2 px by ambiguity_margin (rejects repeated texture).
  double min_score = 0.6;
  double ambiguity_margin = 0.15;
  // A left patch with a gray-level standard deviation below this has no
  // texture to match (textureless plaster) and is rejected outright.
  double min_patch_stddev = 3.0;
  // Patch must have horizontal structure: the mean |∂I/∂x| over the mean
  // |∇I| at least this (horizontal edges cannot be located along a row).
  double min_horizontal_structure = 0.25;
  // Gauss–Newton steps refining the parabola's sub-pixel disparity on the
  // normalised patch difference (0 keeps the parabola; it is biased towards
  // whole pixels by up to ~0.1 px).
  int gauss_newton_iterations = 5;

  void Check() const;
};

struct RowMatch {
  double disparity_px = 0.0;  // u_left − u_right, sub-pixel.
  double row_offset_px = 0.0; // v_right − v_left (0 unless row_tolerance_px > 0).
  double score = 0.0;         // Best ZNCC in [-1, 1].
  double second_score = -1.0; // Best other peak.

  std::string ToString() const;
};

// Finds `left_px` of the left image in the right image along the same row,
// for disparities in [min_disparity_px, max_disparity_px]. Images are CV_32F
// gray. nullopt when the patch is textureless, the match weak or ambiguous,
// or the search leaves the image.
std::optional<RowMatch> MatchAlongRow(const cv::Mat& left_gray, const cv::Mat& right_gray,
                                      const Vec2& left_px, double min_disparity_px,
                                      double max_disparity_px, const RowMatchOptions& options);

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_CORNERS_H_
