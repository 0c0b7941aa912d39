#ifndef ASBUILT_STEREO_FRAME_POINTS_OPTIONS_H_
#define ASBUILT_STEREO_FRAME_POINTS_OPTIONS_H_

// Options of the stereo stage's world points (stereo/frame_points.h).

#include <optional>
#include <string>

#include "asbuilt/stereo/corners.h"
#include "asbuilt/stereo/disparity.h"
#include "asbuilt/stereo/wall_vertices.h"

namespace asbuilt {

// When walls are placed from their floor/ceiling label edges (FramePointsOptions::contacts).
enum class ContactUse { kOff, kWhereStereoFails, kAlways };
// "off", "auto", "always"; parse throws InvalidArgument on anything else.
const char* ContactUseName(ContactUse use);
ContactUse ParseContactUse(const std::string& name);

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
  // Contacts: every n-th column; the label must run this many pixels on both
  // sides of the transition; σ of the label edge's row (px).
  //   kOff               no contact points;
  //   kWhereStereoFails  (default) the capture's wall stereo is checked
  //                      first (stereo_check_* below): where it holds
  //                      (textured walls) the points are exactly kOff's;
  //                      where it fails (plain paint: SGBM matches noise),
  //                      wall stereo points are dropped and the contacts
  //                      place the walls (CapturePoints decides);
  //   kAlways            contacts in every frame, beside the stereo points.
  ContactUse contacts = ContactUse::kWhereStereoFails;
  int contact_col_step_px = 2;
  int contact_min_run_px = 4;
  double contact_sigma_px = 0.5;
  // 1σ of the rig height above the floor given in capture.json (enters the
  // contact points' σ as Z·σ_h/h).
  double camera_height_sigma_m = 0.005;
  // A floor contact is rejected when the floor's disparity just below it
  // exceeds the floor plane's by more than max(this, 15 %): something stands
  // in front of the wall base there.
  double contact_floor_tolerance_px = 1.0;
  // A segmenter's label edges wander by pixels (its logits are at a quarter
  // of its input scale); the image's own step between wall and ceiling is
  // sharp. With contact_snap_px > 0, each ceiling contact row moves to the
  // strongest vertical colour step (channels summed, 5-column mean,
  // sub-pixel) within that many rows of the label edge, when it is at least
  // contact_snap_min_step levels. survey and points set it for labels that
  // are not a capture's exact ones. Measured with the shipped model on the
  // plain rooms of bench_rooms (seeds 6, 8, 9, 10): median ceiling row error
  // 1.0–4.0 → 0.2–0.9 px, and seed 9's ceiling height 3.518 → 3.449 m
  // (truth 3.451). Floor contacts are not snapped: a skirting board's top
  // (8 cm up, labelled wall, but often labelled floor by the model) and
  // tiles' grout lines give steps as strong as the wall's foot, so snapping
  // the floor helped rooms without skirting (seed 9: floor > 3 px off 28 →
  // 8 % of columns) and hurt those with it (seed 10: 36 → 41 %; its plan
  // 5/6 → 4/6 walls). Exact labels need no snapping: it moves their edges
  // by 0.3 px median.
  int contact_snap_px = 0;
  double contact_snap_min_step = 1.0;
  // Skirting boards (labelled wall) stand this far in front of the wall's
  // face, so a floor contact at their foot places the wall too near. A frame
  // whose wall foot contacts show a colour step at one height 3–25 cm above
  // the floor in most columns has them; its wall floor contacts then move
  // this far back, normal to the wall. 0 turns the correction off.
  double skirting_depth_m = 0.012;
  // What survey and points use for labels that are not a capture's exact ones.
  static constexpr int kDefaultContactSnapPx = 10;
  // `asked` when given, else kDefaultContactSnapPx, or 0 for exact labels.
  static int ContactSnapPxFor(std::optional<int> asked, bool exact_labels) {
    return asked.value_or(exact_labels ? 0 : kDefaultContactSnapPx);
  }
  // The stereo check (kWhereStereoFails): a level camera sees a vertical
  // wall at one depth down each image column, so a wall's valid disparities
  // down a column should lie within max(this, 3 %) of their median. The
  // capture's wall stereo is kept when at least stereo_check_min_agree of
  // its wall pixels do, or when fewer than stereo_check_min_pixels could be
  // compared (no evidence against it). Measured (bench/results/survey.md):
  // textured walls 0.87–0.99 of pixels per capture, plain paint 0.30–0.42.
  double stereo_check_tolerance_px = 0.5;
  double stereo_check_min_agree = 0.7;
  int stereo_check_min_pixels = 2000;
  // …and the contacts replace it only when the capture has this many (a
  // tilted hand-held camera, or wall bases out of view, give none).
  int stereo_check_min_contacts = 100;
  // The ceiling's height above the floor when known; otherwise it is
  // estimated (see CeilingHeightFromSamples) and ceiling contacts wait for it.
  std::optional<double> ceiling_height_m;
  // Vertices: wall–wall corner columns (wall_vertices.h), one point per
  // corner and frame at the middle of the rows that show it, with this σ.
  bool use_vertices = true;
  WallVertexOptions vertices;
  double vertex_sigma_px = 0.2;
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

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_FRAME_POINTS_OPTIONS_H_
