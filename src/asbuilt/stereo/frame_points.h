#ifndef ASBUILT_STEREO_FRAME_POINTS_H_
#define ASBUILT_STEREO_FRAME_POINTS_H_

// World points by class from stereo frames and their segmentation — the
// stereo stage's entry point for `asbuilt points` and `asbuilt survey`
// (PAPER.md §7). Per frame, three cues, each with evidence from both images:
//   corner  contour corners of each class region, matched along the row by
//           patch correlation (guided by the dense disparity), triangulated;
//   edge    image edges inside wall/door/window regions with horizontal
//           structure (wall–wall corners, frames, casings), matched the same
//           way — what carries textureless painted walls;
//   dense   every labelled pixel with a left–right consistent disparity.
// Points get σ from the disparity error: σ_Z = Z²·σ_d/(f·B). Nothing is
// interpolated where neither image has evidence.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/formats/capture.h"
#include "asbuilt/formats/points_file.h"
#include "asbuilt/geometry/rig.h"
#include "asbuilt/stereo/corners.h"
#include "asbuilt/stereo/disparity.h"
#include "asbuilt/stereo/rectify.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

// One rectified stereo frame with its labels, ready for ComputeFramePoints.
struct StereoFrame {
  cv::Mat left, right;          // Rectified CV_8UC3 (or CV_8UC1).
  cv::Mat labels_left;          // CV_8UC1 label ids, left view (required).
  cv::Mat labels_right;         // Optional; when given, matches must agree with it.
  PinholeCamera camera;         // Rectified intrinsics.
  double baseline_m = 0.12;
  RigPose pose;
  int index = -1;
};

struct FramePointsOptions {
  DisparityOptions disparity = {.num_disparities_px = 80, .block_size_px = 5};
  CornerOptions corners;
  RowMatchOptions match;
  bool use_corners = true;
  bool use_edges = true;
  bool use_dense = true;
  // Classes that give dense points. Window regions give them only in a band
  // along their border (frame, casing): the glass shows the outside.
  bool dense_wall = true;
  bool dense_door = true;
  bool dense_window = true;
  // Width (px) of that band; door/window edge points use the same band.
  double window_band_px = 14.0;
  // Keep every n-th dense pixel in x and y (1 = all); fewer points, same fit.
  int dense_stride_px = 3;
  // Dense points only this far (px) inside their class region, so a
  // foreground edge's disparity never lands on the wall behind it.
  int dense_inset_px = 3;
  // Edge points: sample every n-th row; a pixel is an edge when its
  // horizontal gradient (Sobel, gray levels) is a row maximum above this.
  int edge_row_step_px = 3;
  double edge_min_gradient = 8.0;
  // Search ±guide_radius_px around the dense disparity at a corner or edge
  // pixel; the full range when the dense map has nothing nearby.
  double guide_radius_px = 4.0;
  // A matched corner (or edge point) is dropped when the dense disparity of its own region
  // nearby differs by more than this (occlusion corners: furniture in front
  // of a wall takes the corner's match).
  double corner_region_tolerance_px = 1.5;
  // Opening boundaries: on every n-th row, where a door/window label meets a
  // wall label, one point at the label edge (sub-pixel: halfway between the
  // two pixel centres) with the depth of the wall beside it — so an
  // opening's width is measured on the wall's surface, not from the
  // recessed or protruding depths inside the opening (glass, jambs, an open
  // leaf). Skipped where the opening's own depth just inside the edge is not
  // the wall's: the edge is then an occlusion (an open leaf in front of the
  // wall, a wall corner in front of a window), not the opening's border.
  bool use_boundaries = true;
  int boundary_row_step_px = 2;
  // Only vertical edges (the opening's sides): the same transition within
  // ±1 px on this many rows above and below.
  int boundary_vertical_rows = 3;
  // The wall's disparity: median over wall pixels from boundary_wall_gap_px
  // to boundary_wall_gap_px + boundary_wall_span_px beyond the edge (rows
  // ±2); the gap keeps the matcher's foreground fattening out.
  int boundary_wall_gap_px = 3;
  int boundary_wall_span_px = 10;
  // The opening's own disparity: its pixels 1…boundary_inside_px inside the
  // edge (casing). It must agree with the wall's within max(this, 8 % of
  // the wall's disparity).
  int boundary_inside_px = 5;
  double boundary_tolerance_px = 1.0;
  double boundary_sigma_px = 0.3;  // 1σ of the wall disparity at the edge.
  // 1σ disparity errors used for the point uncertainty.
  double corner_sigma_px = 0.25;
  double edge_sigma_px = 0.3;
  double dense_sigma_px = 0.5;
  // Points outside this depth range are dropped.
  double min_depth_m = 0.3;
  double max_depth_m = 20.0;
  // With right labels: a matched right position must carry the same class
  // within this radius.
  int right_label_radius_px = 2;

  void Check() const;
};

// A corner with its stereo match, for reports and tests.
struct MatchedCorner {
  ClassCorner corner;
  RowMatch match;
  Vec3 point_in_world = Vec3::Zero();
};

// Which cues carried a frame (STYLE.md 6).
struct FrameCues {
  int index = -1;
  int corners_found = 0;
  int corners_matched = 0;
  int edge_candidates = 0;
  int edge_points = 0;
  int dense_points = 0;
  int boundary_points = 0;  // Door/window label edges on the wall.
  double dense_valid_fraction = NAN;  // Of labelled wall/door/window pixels.
  double seconds = 0.0;

  // "corner+edge+dense", or "none" — the cues that produced points.
  std::string CarriedBy() const;
  std::string BriefReport() const;
};

struct FramePointsResult {
  std::vector<ClassPoint> points;  // World frame.
  std::vector<MatchedCorner> corners;
  FrameCues cues;
  DisparityResult disparity;
};

// Points of one frame. Throws InvalidArgument on inconsistent sizes/types.
FramePointsResult ComputeFramePoints(const StereoFrame& frame, const FramePointsOptions& options);

// Labels for a frame's view: empty Mat when there are none (for the right
// view, "none" is normal). Images are as the capture's images (unrectified
// when the capture is); they are rectified with nearest-neighbour lookup.
using LabelProvider = std::function<cv::Mat(const CaptureFrame& frame, StereoEye eye)>;
// Left labels from DIR/NNN.png (frame index, three digits); right labels from
// DIR/right/NNN.png when present. Throws InputError if a left file is missing.
LabelProvider LabelsFromDirectory(const std::filesystem::path& dir);
// Left labels from each frame's `labels` key of capture.json.
LabelProvider LabelsFromCapture(const Capture& capture);

// Reads a frame's images and labels, rectifying them when the capture is not
// rectified (`rectifier` must then be given). Throws InputError for missing
// or unreadable images and labels, naming the file.
StereoFrame LoadStereoFrame(const Capture& capture, const CaptureFrame& frame,
                            const LabelProvider& labels, const StereoRectifier* rectifier);

struct CapturePointsResult {
  std::vector<ClassPoint> points;
  std::vector<FrameCues> frames;
  double seconds = 0.0;

  // "12 frames, 45123 points (wall 40000, door 3000, window 2123; corner 150,
  // edge 3000, dense 41773, boundary 200), 3.2 s".
  std::string BriefReport() const;
};

// Every frame of a capture (rectifying first when `rectified` is false,
// with the maps computed once from capture.calibration).
CapturePointsResult ComputeCapturePoints(const Capture& capture, const LabelProvider& labels,
                                         const FramePointsOptions& options,
                                         const ProgressCallback& progress = {});

// Coloured PLY (ASCII) for viewers: wall grey-blue, door brown, window cyan.
// Written atomically.
void WritePointsPly(const std::vector<ClassPoint>& points, const std::filesystem::path& path);

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_FRAME_POINTS_H_
