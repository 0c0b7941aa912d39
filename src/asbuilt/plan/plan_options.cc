// PlanOptions' field list (plan_options.h) and Check(), which reads its bounds from it.

#include "asbuilt/plan/plan_options.h"

#include <utility>
#include <vector>

namespace asbuilt {

static_assert(PlanOptions::kSegmentedContactScaleSigma == 0.005, "contact_scale_sigma's description says 0.005");
static_assert(PlanOptions::kSegmentedLabelEdgeSigmaMrad == 3.5, "label_edge_sigma_mrad's description says 3.5");

namespace {

// The opening stage's fields (plan_openings.h), in the order the tables list them.
std::vector<BoundField<PlanOptions>> OpeningFields() {
  using O = PlanOptions;
  return {
      Bind(&O::door_casing_m,
           {.name = "door_casing_m",
            .description = "Door labels extend this far beyond the clear opening (0 if labels mark the clear "
                           "opening), m.",
            .minimum = 0.0}),
      Bind(&O::window_casing_m, {.name = "window_casing_m",
                                 .description = "Window labels extend this far beyond the clear opening, m.",
                                 .minimum = 0.0}),
      Bind(&O::casing_depth_m,
           {.name = "casing_depth_m",
            .description = "Casings stand this far in front of the wall face: a label edge seen past a casing's "
                           "front corner is moved back by it (0: labels end at the face), m.",
            .minimum = 0.0,
            .maximum = 0.1}),
      Bind(&O::casing_sigma_m,
           {.name = "casing_sigma_m",
            .description = "Uncertainty of the casing widths and depth (enters the ± of openings), m.",
            .minimum = 0.0}),
      Bind(&O::opening_band_m, {.name = "opening_band_m",
                                .description = "Door/window points within this behind a wall's line belong to it, m.",
                                .exclusive_minimum = 0.0}),
      Bind(&O::opening_front_m,
           {.name = "opening_front_m",
            .description = "Door/window points within this in front of a wall's line belong to it too "
                           "(casings; not sill boards or open leaves), m.",
            .exclusive_minimum = 0.0}),
      Bind(&O::opening_gap_m, {.name = "opening_gap_m",
                               .description = "Openings on one wall are split at gaps longer than this, m.",
                               .exclusive_minimum = 0.0}),
      Bind(&O::min_opening_points,
           {.name = "min_opening_points", .description = "Fewer points are not an opening.", .minimum = 2.0}),
      Bind(&O::min_opening_width_m, {.name = "min_opening_width_m",
                                     .description = "Narrower clear openings are dropped, m.",
                                     .exclusive_minimum = 0.0}),
      Bind(&O::min_door_height_m,
           {.name = "min_door_height_m",
            .description = "Door labels reaching no higher than this above the floor are no door (a blob on the "
                           "floor), m.",
            .minimum = 0.0}),
      Bind(&O::door_wall_below_share,
           {.name = "door_wall_below_share",
            .description = "A door whose clear span shows wall points low on the face (0.1-1 m up, where a doorway "
                           "shows its leaf or the room beyond) in more than this share of it is no door (a door label "
                           "painted down a plain wall); 1: never.",
            .minimum = 0.0,
            .maximum = 1.0}),
      Bind(&O::edge_level, {.name = "edge_level",
                            .description = "Opening extent: 2 cm bins with at least this fraction of a full bin (< 1).",
                            .exclusive_minimum = 0.0,
                            .exclusive_maximum = 1.0}),
      Bind(&O::min_boundary_points,
           {.name = "min_boundary_points",
            .description = "Label-edge points needed per side to measure an opening's width from them.",
            .minimum = 1.0}),
      Bind(&O::max_own_beyond_label_edge,
           {.name = "max_own_beyond_label_edge",
            .description = "A side's label edges are not the opening's edge where more than this share of its own "
                           "points lie beyond them (past the casing and 3 cm): an open leaf's outline, a stray edge.",
            .minimum = 0.0,
            .maximum = 1.0}),
      Bind(&O::leaf_max_distance_m,
           {.name = "leaf_max_distance_m",
            .description = "An open door's leaf: door points up to this far in front of the wall, m."}),
      Bind(&O::leaf_min_points, {.name = "leaf_min_points",
                                 .description = "Door points along one line that make a leaf (its width gives "
                                                "the door's)."}),
      Bind(&O::leaf_edge_sigma_m, {.name = "leaf_edge_sigma_m",
                                   .description = "1σ of a door edge placed one leaf width from the seen one "
                                                  "(enters the ± of widths), m.",
                                   .minimum = 0.0}),
  };
}
}  // namespace

const FieldList<PlanOptions>& PlanOptionFields() {
  using O = PlanOptions;
  static const FieldList<O> kList = [] {
    FieldList<O> list = {
        Bind(&O::epsilon_m, {.name = "epsilon_m",
                             .description = "Collinearity tolerance ε: base half-width of a wall's inlier band, m.",
                             .exclusive_minimum = 0.0}),
        Bind(&O::inlier_sigmas, {.name = "inlier_sigmas",
                                 .description = "A point is also an inlier within this many of its own σ.",
                                 .minimum = 0.0}),
        Bind(&O::max_inlier_distance_m, {.name = "max_inlier_distance_m",
                                         .description = "Cap on a wall's inlier band for noisy points, m.",
                                         .exclusive_minimum = 0.0}),
        Bind(&O::nominal_sigma_m, {.name = "nominal_sigma_m",
                                   .description = "σ for points whose file gives 0 (paper-style files), m.",
                                   .exclusive_minimum = 0.0}),
        Bind(&O::vote_sigma_m, {.name = "vote_sigma_m",
                                .description = "A point's vote is min(1, (vote_sigma_m/σ)²): exact contacts "
                                               "outvote noisy stereo points, m.",
                                .exclusive_minimum = 0.0}),
        Bind(&O::min_wall_points, {.name = "min_wall_points",
                                   .description = "Fewer votes are not a wall (outliers, clutter).",
                                   .minimum = 3.0}),
        Bind(&O::min_wall_fraction, {.name = "min_wall_fraction",
                                     .description = "Nor fewer than this fraction of all wall votes (< 0.2).",
                                     .minimum = 0.0,
                                     .exclusive_maximum = 0.2}),
        Bind(&O::min_wall_length_m, {.name = "min_wall_length_m",
                                     .description = "Shorter point runs are not walls, m.",
                                     .exclusive_minimum = 0.0}),
        Bind(&O::max_gap_m, {.name = "max_gap_m",
                             .description = "A line's points split into separate walls at longer gaps, m.",
                             .exclusive_minimum = 0.0}),
        Bind(&O::min_relative_density,
             {.name = "min_relative_density",
              .description = "Walls need this fraction of the densest wall's votes per metre (< 1).",
              .minimum = 0.0,
              .exclusive_maximum = 1.0}),
        Bind(&O::ransac_iterations, {.name = "ransac_iterations",
                                     .description = "Hypotheses per line; more = surer on clutter, slower.",
                                     .minimum = 1.0}),
        Bind(&O::ransac_subset_points, {.name = "ransac_subset_points",
                                        .description = "Hypotheses are scored on a random subset of this size.",
                                        .minimum = 10.0}),
        Bind(&O::snap_sigmas, {.name = "snap_sigmas",
                               .description = "Snap a line to a dominant direction within this many σ of its fit.",
                               .minimum = 0.0}),
        Bind(&O::snap_max_deg,
             {.name = "snap_max_deg", .description = "Never snap a line by more than this, deg.", .minimum = 0.0}),
        Bind(&O::manhattan_snap_max_deg,
             {.name = "manhattan_snap_max_deg",
              .description = "In a Manhattan frame, every line this close to an axis snaps, deg.",
              .minimum = 0.0}),
        Bind(&O::snap_min_deg, {.name = "snap_min_deg",
                                .description = "Always snap within this (depth quantisation, exact labels), deg.",
                                .minimum = 0.0}),
        Bind(&O::manhattan_max_deg,
             {.name = "manhattan_max_deg",
              .description = "Two dominant directions this close to 90° may form a Manhattan frame (or up to their σ "
                             "when wider, at most manhattan_snap_max_deg), deg.",
              .minimum = 0.0}),
        Bind(&O::manhattan_always_deg,
             {.name = "manhattan_always_deg",
              .description = "Two dominant directions this close to 90° always form a Manhattan frame, deg.",
              .minimum = 0.0}),
        Bind(&O::noisy_snap_max_deg,
             {.name = "noisy_snap_max_deg",
              .description = "In a frame, a line this far off an axis snaps when the axis fits its points within "
                             "their noise, deg.",
              .minimum = 0.0}),
        Bind(&O::bend_sigmas, {.name = "bend_sigmas",
                               .description = "A line whose halves differ in direction by this many σ is bent; "
                                              "its angle σ widens to the difference (0: off).",
                               .minimum = 0.0}),
        Bind(&O::parallel_max_deg,
             {.name = "parallel_max_deg",
              .description = "Neighbours closer than this in angle are not intersected, deg (< 90).",
              .exclusive_minimum = 0.0,
              .exclusive_maximum = 90.0}),
        Bind(&O::max_corner_extension_m, {.name = "max_corner_extension_m",
                                          .description = "A corner may lie at most this far beyond a wall's points, m.",
                                          .exclusive_minimum = 0.0}),
    };
    for (BoundField<O>& f : OpeningFields()) list.Add(std::move(f));
    for (BoundField<O>&f : std::vector<BoundField<O>>{
             Bind(&O::extent_edge_sigma_m,
                  {.name = "extent_edge_sigma_m",
                  .description = "1σ of an opening edge taken where its points stop, without a label edge there "
                                 "(occluders, recessed frames; enters the ± of widths), m.",
                  .minimum = 0.0}),
             Bind(&O::label_edge_sigma_mrad,
                  {.name = "label_edge_sigma_mrad",
                  .description =
                       "1σ of an opening's label edge beyond its points' spread, as an angle seen from the "
                       "viewpoint (enters the ± of widths); unset: 0 for exact labels, 3.5 for segmented ones, "
                       "mrad.",
                  .minimum = 0.0}),
             Bind(&O::max_independent_points,
                  {.name = "max_independent_points",
                  .description = "Dense points are correlated: cap on the points a ± assumes.",
                  .minimum = 2.0}),
             Bind(&O::shared_sigma_fraction,
                  {.name = "shared_sigma_fraction",
                  .description = "Share of a wall's contact points' median σ that does not average out over them.",
                  .minimum = 0.0}),
             Bind(&O::shared_stereo_sigma_fraction,
                  {.name = "shared_stereo_sigma_fraction",
                  .description = "Share of a wall's stereo points' median σ that does not average out over them.",
                  .minimum = 0.0}),
             Bind(
                 &O::contact_scale_sigma,
                 {.name = "contact_scale_sigma",
                 .description = "Relative 1σ of a room-wide scale error of contact-placed walls about the rig (ceiling "
                                "height, label edges off alike all round); unset: 0 for exact labels, 0.005 for "
                                "segmented ones.",
                 .minimum = 0.0,
                 .maximum = 0.5}),
             Bind(&O::ceiling_scale_sigma,
                  {.name = "ceiling_scale_sigma",
                  .description =
                       "Relative 1σ of the ceiling's height above the rig, σ_H / (H − h): moves ceiling-contact "
                       "walls together; unset: survey sets it from its ceiling estimate, else 0.",
                  .minimum = 0.0,
                  .maximum = 0.5}),
             BindWith<O>(
                 {.name = "viewpoint_m",
     .kind = FieldKind::kPoint3,
     .description = "Capture centre X,Y,Z (world m), if known; improves openings."},
                 [](const O&o) -> nlohmann::json {
                   if (!o.viewpoint_m) return nullptr;
                   return {o.viewpoint_m->x(), o.viewpoint_m->y(), o.viewpoint_m->z()};
                 },
                 [](O&o, const nlohmann::json&v) {
                   o.viewpoint_m = Vec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
                 }),
             Bind(&O::one_viewpoint,
                  {.name = "one_viewpoint",
                  .description =
                       "Every point was seen from viewpoint_m (panorama or mono capture): the walls are "
                       "chosen one per bearing around it. `survey` turns it on for a panorama or mono capture taken "
                       "from one spot (docs/survey.md, \"Survey from a 360° photo\")."}),
             Bind(&O::seed,
                  {.name = "seed", .description = "RANSAC sampling seed.", .minimum = 0.0, .maximum = 4294967295.0}),
         }) {
      list.Add(std::move(f));
    }
    return list;
  }();
  return kList;
}

// Every bound of one option is stated once, in the list above; no rule
// involves several options.
void PlanOptions::Check() const { PlanOptionFields().CheckValues(*this, "PlanOptions"); }

}  // namespace asbuilt
