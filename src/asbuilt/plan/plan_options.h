#ifndef ASBUILT_PLAN_PLAN_OPTIONS_H_
#define ASBUILT_PLAN_PLAN_OPTIONS_H_

// Options of ReconstructPlan (plan/reconstruct.h). One line per field; the
// measurements behind the defaults are in docs/plan.md, "Option notes".

#include <cstdint>
#include <optional>

#include "asbuilt/geometry/rig.h"
#include "asbuilt/util/fields.h"

namespace asbuilt {

struct PlanOptions {
  double epsilon_m = 0.05;              // Collinearity tolerance ε: base half-width of a wall's inlier band, m.
  double inlier_sigmas = 3.0;           // A point is also an inlier within this many of its own σ…
  double max_inlier_distance_m = 0.3;   // …but never farther than this from the line, m.
  double nominal_sigma_m = 0.01;        // σ for points whose file gives 0 (paper-style files), m.
  double vote_sigma_m = 0.02;           // Vote = min(1, (vote_sigma_m/σ)²): exact contacts outvote noisy stereo, m.
  int min_wall_points = 30;             // Fewer votes: not a wall (outliers, clutter)…
  double min_wall_fraction = 0.005;     // …nor fewer than this fraction of all wall votes.
  double min_wall_length_m = 0.3;       // Shorter point runs are not walls, m.
  double max_gap_m = 1.0;               // A line's points split into separate walls at longer gaps, m.
  double min_relative_density = 0.05;   // Walls need this fraction of the densest wall's votes per metre.
  int ransac_iterations = 250;          // Hypotheses per line; more = surer on clutter, slower.
  int ransac_subset_points = 3000;      // Hypotheses are scored on a random subset of this size.
  double snap_sigmas = 3.0;             // Snap to a dominant direction within this many σ of the fit…
  double snap_max_deg = 5.0;            // …and never more than this many degrees.
  double manhattan_snap_max_deg = 8.0;  // In a Manhattan frame, every line this close to an axis snaps, deg.
  double snap_min_deg = 0.05;           // Always snap within this (depth quantisation, exact labels), deg.
  double manhattan_max_deg = 3.0;  // Two dominant directions this close to 90° (or their σ) may form a frame, deg…
  double manhattan_always_deg = 1.0;    // …and this close always do (docs/plan.md, "Option notes").
  double noisy_snap_max_deg = 25.0;     // In a frame, a line this far off an axis snaps when the axis fits its noise.
  double bend_sigmas = 3.0;             // A line whose halves differ by this many σ is bent; its σ widens (0: off).
  double parallel_max_deg = 20.0;       // Neighbours closer than this in angle are not intersected, deg.
  double max_corner_extension_m = 2.5;  // A corner may lie at most this far beyond a wall's points, m.
  double door_casing_m = 0.07;          // Door labels extend this far beyond the clear opening (casing), m.
  double window_casing_m = 0.05;        // Window labels extend this far beyond the clear opening, m.
  double casing_depth_m = 0.015;  // Casings stand this far in front of the wall face (label edges seen past them), m.
  double casing_sigma_m = 0.01;   // Uncertainty of the casing widths and depth (enters the ± of openings), m.
  double opening_band_m = 0.3;    // Door/window points within this behind a wall's line belong to it…
  double opening_front_m = 0.03;  // …and within this in front: casings (not sill boards, not open leaves).
  double opening_gap_m = 0.25;    // Openings on one wall are split at gaps longer than this, m.
  int min_opening_points = 12;    // Fewer points: not an opening.
  double min_opening_width_m = 0.25;   // Narrower clear openings are dropped, m.
  double min_door_height_m = 0.5;      // Door labels reaching no higher than this are no door (a blob on the floor), m.
  double door_wall_below_share = 0.5;  // A door whose clear span shows wall low on the face over this share: none.
  double edge_level = 0.01;            // Opening extent: 2 cm bins with at least this fraction of a full bin.
  int min_boundary_points = 4;         // Label-edge points needed per side to measure a width from them.
  double max_own_beyond_label_edge = 0.1;  // More of an opening's own points beyond a label edge: not its edge.
  double leaf_max_distance_m = 1.5;        // An open door's leaf: door points up to this far in front of the wall, m…
  int leaf_min_points = 20;                // …at least this many, along one line (its width gives the door's).
  double leaf_edge_sigma_m = 0.08;         // 1σ of a door edge placed one leaf width from the seen one, m.
  double extent_edge_sigma_m = 0.06;       // 1σ of an opening edge where its points stop (no label edge there), m.
  // 1σ of an opening's label edge beyond its points' spread, as an angle
  // seen from the viewpoint (a segmenter's edge off alike all along it by a
  // fraction of a pixel or more); along the wall it is range²/h times that,
  // h the viewpoint's distance from the wall, mrad. Unset: auto, ForLabels().
  std::optional<double> label_edge_sigma_mrad;
  int max_independent_points = 400;            // Dense points are correlated: cap the points a ± assumes.
  double shared_sigma_fraction = 0.5;          // Share of a wall's contacts' median σ that does not average out.
  double shared_stereo_sigma_fraction = 0.15;  // The same for stereo points (the matcher's sub-pixel bias).
  // Relative 1σ of a room-wide scale error of the contact-placed walls about
  // the viewpoint: a ceiling height or label edges off the same way all
  // round move every such wall by this share of its distance from the rig.
  // Unset: auto, ForLabels().
  std::optional<double> contact_scale_sigma;
  // Relative 1σ of the ceiling's height above the rig, (H − h): a ceiling
  // contact's distance is proportional to it, so an error in H moves every
  // ceiling-contact-placed wall by its ceiling contacts' share of the weight
  // times this times its distance from the rig, all together. Unset: survey
  // sets it from its ceiling estimate (σ_H / (H − h)); elsewhere 0.
  std::optional<double> ceiling_scale_sigma;
  std::optional<Vec3> viewpoint_m;  // Capture centre (rig position, world m), if known; improves openings.
  bool one_viewpoint = false;       // Every point seen from viewpoint_m (panorama/mono): one wall per bearing.
  std::uint64_t seed = 1;           // RANSAC sampling.

  // These options with the auto ones (unset) resolved for labels of this
  // origin: 0 for a capture's exact labels, the kSegmented… values for
  // segmented or given ones (fitted on calibration rooms, docs/plan.md
  // "±"). survey resolves them; ReconstructPlan, which does not know the
  // labels' origin, reads unset ones as segmented.
  static constexpr double kSegmentedContactScaleSigma = 0.005;
  static constexpr double kSegmentedLabelEdgeSigmaMrad = 3.5;
  PlanOptions ForLabels(bool exact_labels) const {
    PlanOptions o = *this;
    o.contact_scale_sigma = contact_scale_sigma.value_or(exact_labels ? 0.0 : kSegmentedContactScaleSigma);
    o.label_edge_sigma_mrad = label_edge_sigma_mrad.value_or(exact_labels ? 0.0 : kSegmentedLabelEdgeSigmaMrad);
    return o;
  }

  void Check() const;
};

// Its field list (plan_options.cc): every option of `asbuilt plan`, and of
// `asbuilt survey` under `plan.`.
const FieldList<PlanOptions>& PlanOptionFields();

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_PLAN_OPTIONS_H_
