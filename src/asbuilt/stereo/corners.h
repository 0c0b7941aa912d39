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
#include "asbuilt/util/fields.h"

namespace asbuilt {

struct CornerOptions {
  int min_region_area_px = 150;            // Smaller label regions are ignored (specks, slivers), px².
  double approx_epsilon_px = 2.0;          // approxPolyDP tolerance max(this, fraction · perimeter)…
  double approx_epsilon_fraction = 0.004;  // …larger keeps fewer corners, smaller keeps noise vertices.
  int border_margin_px = 6;                // Vertices this near the image border are frame cut-offs, dropped.
  int refine_radius_px = 3;                // cornerSubPix window (2r+1)² on the gray image (0: no refinement).
  double max_refine_shift_px = 1.5;        // A refinement moving farther is discarded (the label vertex is kept).

  void Check() const;
};

// Its field list (corner_options.cc), under `corners.` in `asbuilt points`.
const FieldList<CornerOptions>& CornerOptionFields();

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
std::vector<ClassCorner> FindClassCorners(const cv::Mat& labels, const cv::Mat& gray, const CornerOptions& options);

struct RowMatchOptions {
  int patch_radius_px = 5;                 // Patch (2r+1)² compared by zero-mean normalised cross-correlation.
  int row_tolerance_px = 0;                // Also search rows v ± this (imperfect rectification).
  double min_score = 0.6;                  // Best correlation must reach this…
  double ambiguity_margin = 0.15;          // …and beat every other peak 2 px away or more by this.
  double min_patch_stddev = 3.0;           // Patches with a smaller gray-level σ have no texture: rejected.
  double min_horizontal_structure = 0.25;  // Mean |∂I/∂x| over mean |∇I| at least this (row-locatable).
  int gauss_newton_iterations = 5;         // Sub-pixel refinement steps after the parabola (0: parabola, biased).

  void Check() const;
};

// Its field list (corner_options.cc), under `match.` in `asbuilt points`.
const FieldList<RowMatchOptions>& RowMatchOptionFields();

struct RowMatch {
  double disparity_px = 0.0;   // u_left − u_right, sub-pixel.
  double row_offset_px = 0.0;  // v_right − v_left (0 unless row_tolerance_px > 0).
  double score = 0.0;          // Best ZNCC in [-1, 1].
  double second_score = -1.0;  // Best other peak.

  std::string ToString() const;
};

// Finds `left_px` of the left image in the right image along the same row,
// for disparities in [min_disparity_px, max_disparity_px]. Images are CV_32F
// gray. nullopt when the patch is textureless, the match weak or ambiguous,
// or the search leaves the image.
std::optional<RowMatch> MatchAlongRow(const cv::Mat& left_gray, const cv::Mat& right_gray, const Vec2& left_px,
                                      double min_disparity_px, double max_disparity_px, const RowMatchOptions& options);

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_CORNERS_H_
