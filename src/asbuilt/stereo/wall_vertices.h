#ifndef ASBUILT_STEREO_WALL_VERTICES_H_
#define ASBUILT_STEREO_WALL_VERTICES_H_

// Wall–wall vertical corners (the room's vertices) in a rectified, level
// stereo pair. A level camera sees a vertical corner as one image column
// where two wall planes meet; their shading differs (they face the light at
// different angles), so the horizontal intensity gradient, averaged down the
// column over the rows that show wall on both sides, peaks there with one
// sign on nearly every row. This holds on plain paint, where stereo on the
// wall surfaces matches noise and the floor/ceiling edges of a near wall are
// out of view — the walls that had no other cue. A painting's edge or a
// shadow covers only some rows and fails the sign test.
//
// The corner's disparity: the mean intensity profile across the column (the
// two walls' shading levels) is matched along the same rows of the right
// view by normalised cross-correlation; the sub-pixel positions of the
// gradient peaks in both views give the disparity.

#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/util/fields.h"

namespace asbuilt {

struct WallVertexOptions {
  int side_px = 3;                   // Wall labels on both sides for this many columns.
  int min_rows = 40;                 // Rows with wall on both sides a column needs.
  double min_contrast = 0.8;         // |mean gradient| (gray levels per pixel) at the peak.
  int block_rows = 16;               // Rows are averaged in blocks for the sign test…
  double min_sign_agreement = 0.75;  // …and this fraction of blocks must share the peak's sign.
  int profile_half_width_px = 10;    // Intensity profiles compared over ±this.
  double min_ncc = 0.9;              // Weakest accepted profile match…
  double ambiguity_margin = 0.05;    // …and a rival 2 px away or more must score this much less.

  void Check() const;
};

// Its field list (wall_vertex_options.cc), under `vertices.` in `asbuilt points`.
const FieldList<WallVertexOptions>& WallVertexOptionFields();

struct WallVertex {
  double u_left_px = 0;   // Sub-pixel column in the left view (pixel centres).
  double u_right_px = 0;  // The same corner in the right view.
  double disparity_px = 0;
  double v_mid_px = 0;  // Middle of the rows used.
  int rows = 0;         // Rows with wall on both sides.
  double contrast = 0;  // Mean gradient at the peak (signed).
  double ncc = 0;       // Profile match score.
};

// Corners in the left view with their right-view matches, searching
// disparities in [min_disparity_px, max_disparity_px]. `gray_left` and
// `gray_right` are CV_32F gray levels, `labels_left` CV_8U label ids, all of
// one size. Throws InvalidArgument on mismatched inputs or bad options.
std::vector<WallVertex> FindWallVertices(const cv::Mat& gray_left, const cv::Mat& gray_right,
                                         const cv::Mat& labels_left, double min_disparity_px, double max_disparity_px,
                                         const WallVertexOptions& options);

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_WALL_VERTICES_H_
