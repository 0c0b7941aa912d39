// FramePointsOptions' field list (frame_points_options.h); Check() stays in
// frame_points.cc.

#include "asbuilt/stereo/frame_points_options.h"

namespace asbuilt {
namespace {

// The cues and their sampling (first half of the list).
FieldList<FramePointsOptions> FramePointsCueFields() {
  using O = FramePointsOptions;
  return {
      Bind(&O::use_corners, {.name = "use_corners", .description = "Cue: matched contour corners of the labels."}),
      Bind(&O::use_edges, {.name = "use_edges", .description = "Cue: image edges inside class regions."}),
      Bind(&O::use_dense, {.name = "use_dense", .description = "Cue: dense consistent disparity."}),
      Bind(&O::dense_wall, {.name = "dense_wall", .description = "Wall regions give dense points."}),
      Bind(&O::dense_door, {.name = "dense_door", .description = "Door regions give dense points."}),
      Bind(&O::dense_window,
           {.name = "dense_window",
            .description = "Window regions give dense points, in a border band only (the glass shows the outside)."}),
      Bind(&O::window_band_px, {.name = "window_band_px",
                                .description = "Width of that band; door/window edge points use the same band, px.",
                                .exclusive_minimum = 0.0}),
      Bind(&O::dense_stride_px,
           {.name = "dense_stride_px",
            .description = "Keep every n-th dense pixel in x and y (1 = all); fewer points, same fit.",
            .minimum = 1.0}),
      Bind(&O::dense_inset_px,
           {.name = "dense_inset_px",
            .description = "Dense points only this far inside their class region (no foreground edges), px.",
            .minimum = 0.0}),
      Bind(&O::dense_refine_radius_px,
           {.name = "dense_refine_radius_px",
            .description = "Refine each dense disparity by Gauss–Newton on a (2r+1)² patch (SGBM's sub-pixel "
                           "parabola is drawn towards whole pixels); 0 = off, px.",
            .minimum = 0.0,
            .maximum = 20.0}),
      Bind(&O::dense_refine_max_sigma_px,
           {.name = "dense_refine_max_sigma_px",
            .description = "Keep a refined dense disparity only where its own σ (fit residual over the patch's "
                           "gradients) is at most this; else SGBM's, px.",
            .exclusive_minimum = 0.0}),
      Bind(&O::edge_row_step_px,
           {.name = "edge_row_step_px", .description = "Edge points: sample every n-th row.", .minimum = 1.0}),
      Bind(&O::edge_min_gradient,
           {.name = "edge_min_gradient",
            .description = "Edge points: a horizontal gradient that is a row maximum above this, gray levels.",
            .exclusive_minimum = 0.0}),
      Bind(&O::guide_radius_px,
           {.name = "guide_radius_px",
            .description = "Search ± this around the dense disparity at a corner or edge pixel, px.",
            .minimum = 1.0}),
      Bind(&O::corner_region_tolerance_px,
           {.name = "corner_region_tolerance_px",
            .description = "Drop a corner or edge match this far from its region's dense disparity (occlusion), px."}),
      Bind(&O::use_boundaries,
           {.name = "use_boundaries",
            .description = "Cue: opening sides at the label edge, at the depth of the wall beside them."}),
      Bind(&O::boundary_row_step_px,
           {.name = "boundary_row_step_px", .description = "Opening boundaries: every n-th row.", .minimum = 1.0}),
      Bind(&O::boundary_vertical_rows,
           {.name = "boundary_vertical_rows",
            .description = "Only vertical edges: the same transition within ±1 px this many rows up and down."}),
      Bind(&O::boundary_wall_gap_px,
           {.name = "boundary_wall_gap_px",
            .description = "The wall's disparity: median from this far beyond the edge (keeps fattening out), px.",
            .minimum = 0.0}),
      Bind(&O::boundary_wall_span_px,
           {.name = "boundary_wall_span_px",
            .description = "The wall's disparity: median over this many pixels beyond the gap (rows ±2), px.",
            .minimum = 1.0}),
      Bind(&O::boundary_inside_px, {.name = "boundary_inside_px",
                                    .description = "The opening's own disparity: its pixels 1…this inside the edge.",
                                    .minimum = 1.0}),
      Bind(&O::boundary_tolerance_px,
           {.name = "boundary_tolerance_px",
            .description = "Opening and wall disparity must agree within max(this, 8 %), else an occlusion, px.",
            .exclusive_minimum = 0.0}),
      Bind(&O::boundary_sigma_px, {.name = "boundary_sigma_px",
                                   .description = "1σ of the wall disparity at an opening's edge, px.",
                                   .exclusive_minimum = 0.0}),
  };
}

static_assert(FramePointsOptions::kDefaultContactSnapPx == 10, "contact_snap_px's description says 10");
static_assert(FramePointsOptions::kDefaultFloorSnapPx == 1, "floor_snap_px's description says 1");

// Contacts, the stereo check and the point σ (second half of the list).
FieldList<FramePointsOptions> FramePointsContactFields() {
  using O = FramePointsOptions;
  return {
      BindEnum(&O::contacts,
               {.name = "contacts",
                .description = "Walls placed from their floor/ceiling label edges (level rig at the capture's "
                               "height): auto = only where the walls' stereo fails its check, always, off."},
               {{ContactUseName(ContactUse::kWhereStereoFails), ContactUse::kWhereStereoFails},
                {ContactUseName(ContactUse::kAlways), ContactUse::kAlways},
                {ContactUseName(ContactUse::kOff), ContactUse::kOff}}),
      Bind(&O::contact_col_step_px,
           {.name = "contact_col_step_px", .description = "Contacts: every n-th column.", .minimum = 1.0}),
      Bind(&O::contact_min_run_px,
           {.name = "contact_min_run_px",
            .description = "Contacts: the label runs this many pixels on both sides of the transition.",
            .minimum = 1.0}),
      Bind(&O::contact_sigma_px,
           {.name = "contact_sigma_px", .description = "1σ of a label edge's row, px.", .exclusive_minimum = 0.0}),
      Bind(&O::camera_height_sigma_m,
           {.name = "camera_height_sigma_m",
            .description = "1σ of capture.json's rig height (enters contact σ as Z·σ_h/h), m.",
            .minimum = 0.0}),
      Bind(&O::contact_floor_tolerance_px,
           {.name = "contact_floor_tolerance_px",
            .description = "Reject a floor contact when the floor below it is nearer by max(this, 15 %), px.",
            .exclusive_minimum = 0.0}),
      Bind(&O::contact_snap_px,
           {.name = "contact_snap_px",
            .description = "Move each ceiling contact to the image's strongest edge within N rows of the label "
                           "edge (0 = off); unset: 10 for segmented or given labels, 0 for exact ones.",
            .minimum = 0.0,
            .maximum = 64.0}),
      Bind(&O::contact_snap_min_step,
           {.name = "contact_snap_min_step",
            .description = "Ceiling contacts snap only to a colour step at least this strong, gray levels.",
            .minimum = 0.0}),
      Bind(&O::floor_snap_px,
           {.name = "floor_snap_px",
            .description = "Move each floor contact to the image's strongest edge within N rows of the label "
                           "edge (0 = off); unset: 1 for segmented or given labels, 0 for exact ones.",
            .minimum = 0.0,
            .maximum = 64.0}),
      Bind(&O::skirting_depth_m,
           {.name = "skirting_depth_m",
            .description = "Move wall-foot contacts back this far where a skirting board is seen (0 = off), m.",
            .minimum = 0.0,
            .exclusive_maximum = 0.1}),
      Bind(&O::stereo_check_tolerance_px,
           {.name = "stereo_check_tolerance_px",
            .description = "Stereo check: a wall column's disparities agree within max(this, 3 %), px.",
            .exclusive_minimum = 0.0}),
      Bind(&O::stereo_check_min_agree,
           {.name = "stereo_check_min_agree",
            .description = "Stereo check: share of wall pixels that must agree to keep the wall stereo.",
            .minimum = 0.0,
            .maximum = 1.0}),
      Bind(&O::stereo_check_min_pixels,
           {.name = "stereo_check_min_pixels",
            .description = "Stereo check: with fewer comparable pixels the wall stereo is kept (no evidence).",
            .minimum = 0.0}),
      Bind(&O::stereo_check_min_contacts,
           {.name = "stereo_check_min_contacts",
            .description = "Stereo check: contacts needed to replace failed wall stereo.",
            .minimum = 0.0}),
      Bind(&O::ceiling_height_m, {.name = "ceiling_height_m",
                                  .description = "Ceiling above the floor when known; unset: estimated, m.",
                                  .exclusive_minimum = 0.0}),
      Bind(&O::use_vertices, {.name = "use_vertices", .description = "Cue: wall–wall corner columns."}),
      Bind(&O::vertex_sigma_px,
           {.name = "vertex_sigma_px", .description = "1σ disparity of a vertex point, px.", .exclusive_minimum = 0.0}),
      Bind(&O::corner_sigma_px,
           {.name = "corner_sigma_px", .description = "1σ disparity of a corner point, px.", .exclusive_minimum = 0.0}),
      Bind(&O::edge_sigma_px,
           {.name = "edge_sigma_px", .description = "1σ disparity of an edge point, px.", .exclusive_minimum = 0.0}),
      Bind(&O::dense_sigma_px,
           {.name = "dense_sigma_px", .description = "1σ disparity of a dense point, px.", .exclusive_minimum = 0.0}),
      Bind(&O::sigma_from_neighbours,
           {.name = "sigma_from_neighbours",
            .description = "A dense, edge or corner point's σ is taken at the depth of its region's disparity "
                           "around it, not its own: σ ∝ Z², so a point read too near would weigh more and pull "
                           "its wall in."}),
      Bind(&O::min_depth_m,
           {.name = "min_depth_m", .description = "Points nearer than this are dropped, m.", .exclusive_minimum = 0.0}),
      Bind(
          &O::max_depth_m,
          {.name = "max_depth_m", .description = "Points farther than this are dropped, m.", .exclusive_minimum = 0.0}),
      Bind(&O::right_label_radius_px,
           {.name = "right_label_radius_px",
            .description = "With right labels: a match must carry the same class within this radius, px.",
            .minimum = 0.0}),
  };
}

}  // namespace

const FieldList<FramePointsOptions>& FramePointsOptionFields() {
  static const FieldList<FramePointsOptions> kList = [] {
    FieldList<FramePointsOptions> list = FramePointsCueFields();
    const FieldList<FramePointsOptions> contact_fields = FramePointsContactFields();
    for (const auto& f : contact_fields.bound()) list.Add(f);
    list.Nest("disparity", &FramePointsOptions::disparity, DisparityOptionFields());
    list.Nest("corners", &FramePointsOptions::corners, CornerOptionFields());
    list.Nest("match", &FramePointsOptions::match, RowMatchOptionFields());
    list.Nest("vertices", &FramePointsOptions::vertices, WallVertexOptionFields());
    return list;
  }();
  return kList;
}

}  // namespace asbuilt
