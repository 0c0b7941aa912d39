#ifndef ASBUILT_PANO_PANO_LAYOUT_H_
#define ASBUILT_PANO_PANO_LAYOUT_H_

// A room's layout from one level equirectangular panorama: per column of the
// panorama the horizontal distance to the wall seen there, and the ceiling's
// height — found from the photo's own edges, with a segmenter's labels as a
// weaker guide.
//
// Why: a segmenter trained on renders misreads real rooms (a white ceiling
// taken for wall, shadows for doors), and its wall/floor and wall/ceiling
// edges wander. But a room photographed from a level camera at a known height
// h ties both edges of every column to one number, the wall's distance d: the
// floor edge lies at elevation −atan(h/d), the ceiling edge at
// +atan((H − h)/d), with H the ceiling height shared by the whole room. So
// each column's two edges are sought together (where a cupboard hides the
// foot of a wall, its ceiling edge still places it), and d may change from
// column to column only smoothly (along a wall) or rarely (a jump where one
// wall stands before another). A dynamic programme over the columns finds the
// distances that best explain the image's horizontal-ish edges and the
// labels' wall band; the ceiling height is the one under which that best
// explanation is best. This is the geometric model of layout estimators such
// as HorizonNet (Sun et al., CVPR 2019: one floor and one ceiling boundary per
// column), solved here from image evidence instead of a trained network.
//
// On real photos it finds more walls than the segmenter's own edges but is
// misled by open doors, cabinets and faint ceiling edges; survey uses it only
// when asked (SurveyOptions::pano_layout, docs/survey.md "The layout of a
// panorama", with what was measured).
//
// Pixels follow perspective.h's equirectangular convention (OpenCV centres).
//
//   PanoLayout layout = EstimatePanoLayout(equirect_bgr, 1.435, labels_equirect, {});
//   cv::Mat view_labels = LayoutViewLabels(layout, view, segmenter_labels);

#include <limits>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/pano/perspective.h"
#include "asbuilt/util/fields.h"

namespace asbuilt {

struct PanoLayoutOptions {
  // Width of the working panorama, pixels (height half of it). 1024: 0.35° a
  // column, a row ≈ 2 cm of ceiling height on a wall 3 m away.
  int width_px = 1024;
  // Candidate wall distances, metres: log-spaced bins from min to max.
  double min_distance_m = 0.5;
  double max_distance_m = 12.0;
  int distance_bins = 192;
  // Candidate ceiling heights, metres above the floor, every step; at least
  // 0.2 m above the camera.
  double min_ceiling_m = 1.9;
  double max_ceiling_m = 3.5;
  double ceiling_step_m = 0.02;
  // Weight of the image's edge strength (saturating, 0..1) at a column's
  // floor and at its ceiling edge. The ceiling edge is rarely hidden by
  // furniture, so it weighs more.
  double floor_edge_weight = 1.0;
  double ceiling_edge_weight = 1.5;
  // Weight of the labels' agreement, per row of the column: +1 for each row
  // of the wall band labelled wall/door/window and each row outside it
  // labelled background, −1 the other way round (unknown rows 0). 0 ignores
  // the labels.
  double label_weight_per_row = 0.01;
  // The labels vote only below the horizon: a segmenter trained on renders
  // takes a real white ceiling for wall, but tells floor from wall.
  bool labels_below_horizon_only = true;
  // Edges count only this close to the horizon, degrees: nearer the poles
  // lie the camera's mount and the stitching's smear (nadir) and a ceiling
  // light's rim (zenith). 65° sees a floor edge from 0.67 m at 1.435 m.
  double max_edge_elevation_deg = 65.0;
  // Smoothness between neighbouring columns: cost per distance bin changed
  // (a bin is ln(max/min)/(bins − 1) ≈ 2.2 % of distance), for changes of up
  // to smooth_bins; a larger change (one wall before another) costs jump_cost.
  double smooth_cost_per_bin = 0.05;
  int smooth_bins = 4;
  double jump_cost = 3.0;
  // The walls meet at right angles: each column sees a wall of the room's
  // one direction or its right angle, straight along its length (the
  // Manhattan world). A room corner costs corner_cost. Off: any distance per
  // column, changing smoothly.
  bool manhattan = true;
  double corner_cost = 1.5;
  // A column shows its wall when the median, over ±support_half_width
  // columns, of its edge strength at the floor row plus at the ceiling row
  // (each 0..1, unweighted) is at least this; 0 keeps every column.
  double min_column_support = 0.5;
  int support_half_width = 8;
  // Manhattan: close the path's walls into the room's polygon (walls held
  // by at least min_wall_columns columns, mostly supported; a gap, such as
  // an open door leaf before the camera, bridged by the walls beside it) and
  // take every column's distance from it. Off by default: cleaner plans where
  // it is right, a room lost where a wall is dropped (ZInD room IoU median
  // 0.651 with it, 0.76 without; docs/survey.md).
  bool close_polygon = false;
  int min_wall_columns = 28;  // 10° of the panorama.
  // With close_polygon: only the columns the photo does not show take the
  // polygon's distance (a gap bridged); the others keep their own.
  bool polygon_gaps_only = false;
  // Survey (pipeline/pano_layout_labels.h): keep the labels' doors and
  // windows inside the layout's wall band; off: wall only.
  bool openings_from_labels = true;

  void Check() const;  // Throws InvalidArgument naming a bad field.
};

// Every PanoLayoutOptions field, for flags (`--layout.NAME`) and docs.
const FieldList<PanoLayoutOptions>& PanoLayoutOptionFields();

struct PanoLayout {
  double camera_height_m = 0.0;   // Given: camera above the floor.
  double ceiling_height_m = 0.0;  // Found: ceiling above the floor.
  // Per working column (width_px of PanoLayoutOptions; column u looks along
  // the yaw perspective.h gives pixel u): horizontal distance to the wall.
  std::vector<double> distance_m;
  // Per working column: whether the image shows the wall there (an edge at
  // its floor or its ceiling row, over the columns around it; see
  // PanoLayoutOptions::min_column_support). An unsupported column's distance
  // is the programme's guess across a gap (an open door leaf before the
  // camera, a wall base below the view): no wall is drawn there.
  std::vector<bool> supported;
  // Manhattan with close_polygon: the room polygon, pano frame metres, the
  // camera at the origin, vertices in column order (empty: none closed).
  std::vector<Vec2> polygon_m;
  // Manhattan layouts: the walls' direction in the pano frame, degrees in
  // [0, 90) from +X (NaN: not Manhattan).
  double wall_direction_deg = std::numeric_limits<double>::quiet_NaN();
  double score = 0.0;  // The best explanation's total (higher: edges and labels agree better).

  int Columns() const { return static_cast<int>(distance_m.size()); }
  // The working column that looks along a direction's yaw (nearest;
  // the direction need not be normalised). Throws InvalidArgument when empty.
  int ColumnAlong(const Vec3& direction) const;
  // The wall distance along a direction's yaw (the nearest column's; a
  // direction need not be normalised).
  double DistanceAlong(const Vec3& direction) const;
  // The floor edge's and ceiling edge's elevation, radians, along a yaw
  // (floor negative, ceiling positive).
  // Whether the wall along a yaw shows in the image (true when `supported`
  // is empty).
  bool Supported(const Vec3& direction) const;
  double FloorElevation(const Vec3& direction) const;
  double CeilingElevation(const Vec3& direction) const;
  std::string BriefReport() const;  // "layout: ceiling 2.36 m, walls 1.2–4.8 m away (median 2.9 m)".
};

// Builds the layout of `equirect_bgr` (8-bit BGR, 2:1) seen from
// camera_height_m above the floor. `labels_equirect` (CV_8UC1 label ids of
// the same panorama at any 2:1 size, 255 unknown; or empty) guides it.
// Throws InvalidArgument for a bad image, height or options.
PanoLayout EstimatePanoLayout(const cv::Mat& equirect_bgr, double camera_height_m, const cv::Mat& labels_equirect,
                              const PanoLayoutOptions& options);

// Label ids of views gathered into one equirectangular map (width_px ×
// width_px/2, CV_8UC1): each pixel takes the label of the view that looks
// most nearly its way and sees it, 255 where none does.
cv::Mat EquirectFromViewLabels(const std::vector<PanoView>& views, const std::vector<cv::Mat>& labels, int width_px);

// A view's labels redrawn on the layout: wall between each column's ceiling
// and floor edge, background elsewhere; inside the wall band, door and window
// where `view_labels` (the segmenter's, same size as the view; may be empty)
// has them.
cv::Mat LayoutViewLabels(const PanoLayout& layout, const PanoView& view, const cv::Mat& view_labels);

// The panorama with the layout's floor (red) and ceiling (green) edges drawn
// on it, for reports.
cv::Mat DrawPanoLayout(const cv::Mat& equirect_bgr, const PanoLayout& layout);

}  // namespace asbuilt

#endif  // ASBUILT_PANO_PANO_LAYOUT_H_
