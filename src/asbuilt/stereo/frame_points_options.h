#ifndef ASBUILT_STEREO_FRAME_POINTS_OPTIONS_H_
#define ASBUILT_STEREO_FRAME_POINTS_OPTIONS_H_

// Options of the stereo stage's world points (stereo/frame_points.h). One
// line per field; the measurements behind the defaults are in docs/stereo.md,
// "Option notes".

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
  DisparityOptions disparity = {.num_disparities_px = 80, .block_size_px = 5};  // The dense guide.
  CornerOptions corners;                                                        // Contour corners of the label regions.
  RowMatchOptions match;           // Matching corners and edge points along rows.
  bool use_corners = true;         // Cue: matched contour corners.
  bool use_edges = true;           // Cue: image edges inside class regions.
  bool use_dense = true;           // Cue: dense consistent disparity.
  bool dense_wall = true;          // Wall regions give dense points…
  bool dense_door = true;          // …door regions…
  bool dense_window = true;        // …window regions (only in a border band: the glass shows the outside).
  double window_band_px = 14.0;    // Width of that band; door/window edge points use the same band, px.
  int dense_stride_px = 3;         // Keep every n-th dense pixel in x and y (1 = all); fewer points, same fit.
  int dense_inset_px = 3;          // Dense points only this far inside their region (no foreground edges), px.
  int dense_refine_radius_px = 0;  // Refine dense disparities on a (2r+1)² patch (RefineDisparityAt; 0: off)…
  double dense_refine_max_sigma_px = 0.1;  // …keeping the refinement where its own σ is at most this, px.
  int edge_row_step_px = 3;                // Edge points: sample every n-th row…
  double edge_min_gradient = 8.0;          // …where the horizontal gradient is a row maximum above this, gray levels.
  double guide_radius_px = 4.0;            // Search ± this around the dense disparity at a corner or edge pixel.
  double corner_region_tolerance_px = 1.5;  // Drop a match this far from its region's dense disparity (occlusion).
  bool use_boundaries = true;               // Cue: opening sides at the label edge, at the wall's depth beside it.
  int boundary_row_step_px = 2;             // Opening boundaries: every n-th row.
  int boundary_vertical_rows = 3;      // Only vertical edges: the same transition ±1 px this many rows up and down.
  int boundary_wall_gap_px = 3;        // The wall's disparity: median from this far beyond the edge…
  int boundary_wall_span_px = 10;      // …over this many pixels (rows ±2).
  int boundary_inside_px = 5;          // The opening's own disparity: its pixels 1…this inside the edge…
  double boundary_tolerance_px = 1.0;  // …must agree with the wall's within max(this, 8 %), else an occlusion.
  double boundary_sigma_px = 0.3;      // 1σ of the wall disparity at the edge, px.
  ContactUse contacts = ContactUse::kWhereStereoFails;  // Walls from floor/ceiling label edges: off, auto, always.
  int contact_col_step_px = 2;                          // Contacts: every n-th column…
  int contact_min_run_px = 4;               // …where the label runs this many pixels on both sides of the transition.
  double contact_sigma_px = 0.5;            // 1σ of the label edge's row, px.
  double camera_height_sigma_m = 0.005;     // 1σ of capture.json's rig height (enters contact σ as Z·σ_h/h), m.
  double contact_floor_tolerance_px = 1.0;  // Reject a floor contact when the floor below is nearer by max(this, 15 %).
  std::optional<int> contact_snap_px;  // Snap ceiling contacts to the image edge within this many rows; unset: auto.
  double contact_snap_min_step = 1.0;  // …when that colour step is at least this, gray levels.
  std::optional<int> floor_snap_px;    // Snap floor contacts to the image edge within this many rows; unset: auto.
  double skirting_depth_m = 0.012;     // Move wall-foot contacts back this far where a skirting is seen (0: off), m.
  double stereo_check_tolerance_px = 0.5;  // Stereo check: a wall column's disparities agree within max(this, 3 %)…
  double stereo_check_min_agree = 0.7;     // …for this share of wall pixels, or the wall stereo is dropped…
  int stereo_check_min_pixels = 2000;      // …unless fewer pixels could be compared (no evidence)…
  int stereo_check_min_contacts = 100;     // …or the capture has fewer contacts to replace it.
  std::optional<double> ceiling_height_m;  // Ceiling above the floor when known; unset: estimated, m.
  bool use_vertices = true;                // Cue: wall–wall corner columns (wall_vertices.h).
  WallVertexOptions vertices;              // Finding those columns.
  double vertex_sigma_px = 0.2;            // 1σ disparity of a vertex point, px.
  double corner_sigma_px = 0.25;           // 1σ disparity of a corner point, px.
  double edge_sigma_px = 0.3;              // 1σ disparity of an edge point, px.
  double dense_sigma_px = 0.5;             // 1σ disparity of a dense point, px.
  bool sigma_from_neighbours =
      true;                       // A stereo point's σ at its neighbours' depth, not its own (unbiased fit weights).
  double min_depth_m = 0.3;       // Points nearer than this are dropped, m.
  double max_depth_m = 20.0;      // Points farther than this are dropped, m.
  int right_label_radius_px = 2;  // With right labels: a match must carry the same class within this, px.

  // The snap radius for labels of this origin: contact_snap_px when set,
  // else 0 for a capture's exact labels and kDefaultContactSnapPx for
  // segmented or given ones (docs/stereo.md, "Option notes"). survey and
  // points resolve auto with it before the frame loop; the frame functions,
  // which do not know the labels' origin, read an unset value as 0.
  static constexpr int kDefaultContactSnapPx = 10;
  int ContactSnapPx(bool exact_labels) const {
    return contact_snap_px.value_or(exact_labels ? 0 : kDefaultContactSnapPx);
  }
  // The same for floor contacts, with a window too narrow to reach a
  // skirting board's top or a tile's grout line (they gave steps as strong
  // as the wall's foot to the wide ceiling window): at 1 the snap only
  // refines a segmented label edge to the image's own sub-pixel edge within
  // its row (2, which can move it a row, did better on rendered rooms and
  // worse on real panoramas: docs/stereo.md).
  static constexpr int kDefaultFloorSnapPx = 1;
  int FloorSnapPx(bool exact_labels) const { return floor_snap_px.value_or(exact_labels ? 0 : kDefaultFloorSnapPx); }
  // Both snap radii resolved for labels of this origin.
  void ResolveSnaps(bool exact_labels) {
    contact_snap_px = ContactSnapPx(exact_labels);
    floor_snap_px = FloorSnapPx(exact_labels);
  }

  void Check() const;
};

// Its field list (frame_points_options.cc), nested lists under `disparity.`,
// `corners.`, `match.`, `vertices.`: every option of `asbuilt points`, and
// of `asbuilt survey` under `points.`.
const FieldList<FramePointsOptions>& FramePointsOptionFields();

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_FRAME_POINTS_OPTIONS_H_
