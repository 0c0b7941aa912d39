#ifndef ASBUILT_PLAN_PLAN_OPTIONS_H_
#define ASBUILT_PLAN_PLAN_OPTIONS_H_

// Options of ReconstructPlan (plan/reconstruct.h).

#include <cstdint>
#include <optional>

#include "asbuilt/geometry/rig.h"

namespace asbuilt {

struct PlanOptions {
  double epsilon_m = 0.05;            // Collinearity tolerance ε: base half-width of a wall's inlier band.
  double inlier_sigmas = 3.0;         // A point is also an inlier within this many of its own σ…
  double max_inlier_distance_m = 0.3; // …but never farther than this from the line.
  double nominal_sigma_m = 0.01;      // σ for points whose file gives 0 (paper-style files).
  // A point's vote (its support for a line) is min(1, (vote_sigma_m/σ)²): a
  // wall–floor contact 4 m away (σ ≈ 2 cm) counts fully, a dense stereo point
  // there (σ ≈ 17 cm) about 1/70 — so thousands of noisy disparities on a
  // textureless wall cannot outvote a few hundred exact contacts. Counts
  // below (min_wall_points, densities, fractions) are in votes. Without any
  // contact point every vote is 1 (plain counts).
  double vote_sigma_m = 0.02;
  int min_wall_points = 30;           // Fewer votes: not a wall (outliers, clutter)…
  double min_wall_fraction = 0.005;   // …nor fewer than this fraction of all wall votes.
  double min_wall_length_m = 0.3;     // Shorter point runs are not walls.
  double max_gap_m = 1.0;             // A line's points split into separate walls at longer gaps.
  double min_relative_density = 0.05; // Walls need this fraction of the densest wall's points per metre.
  int ransac_iterations = 250;        // Hypotheses per line; more = surer on clutter, slower.
  int ransac_subset_points = 3000;    // Hypotheses are scored on a random subset of this size.
  double snap_sigmas = 3.0;           // Snap to a dominant direction within this many σ of the fit…
  double snap_max_deg = 5.0;          // …and never more than this many degrees.
  double manhattan_snap_max_deg = 8.0;  // In a Manhattan frame, every line this close to an axis.
  double snap_min_deg = 0.05;         // Always snap within this (depth quantisation, exact labels).
  double manhattan_max_deg = 3.0;     // Two dominant directions this close to 90° may form a frame…
  // …and this close always do: rooms are built square to well within a
  // degree, while fits of thousands of stereo points give their angles σ of
  // hundredths of a degree and land 0.1–0.5° off square (bench_rooms seeds
  // 5, 9, 10, 15, 19 formed no frame at 3σ).
  double manhattan_always_deg = 1.0;
  // In a Manhattan frame, a line up to this far off an axis is snapped too
  // when the axis explains its points within their own noise (χ² up by
  // less than one per point): noisy far walls, cut into pieces by RANSAC;
  // or when snap_sigmas of its angle σ, widened for a bend (bend_sigmas),
  // take in the axis.
  double noisy_snap_max_deg = 25.0;
  // A line is bent when a half of its points (split at the median along it)
  // fits a direction more than this many of that half's σ off the whole
  // line's; its angle σ is then at least that difference (0: off). Point
  // noise alone gives a fit's angle σ of hundredths of a degree, but a
  // segmenter that takes a skirting board for floor over part of a wall
  // pushes that part's contacts 10–20 cm out: bench_rooms seed 10's 4.8 m
  // south wall came out as a "V" of two pieces 4.8° apart, fitted as one
  // line 2.7° off at ±0.06°. It outweighed two square walls measured to
  // millimetres and kept the room from its Manhattan frame (max wall error
  // 14.1 %; 2.5 % with this rule).
  double bend_sigmas = 3.0;
  double parallel_max_deg = 20.0;     // Neighbours closer than this in angle are not intersected.
  double max_corner_extension_m = 2.5;  // A corner may lie at most this far beyond a wall's points.
  double door_casing_m = 0.07;        // Door labels extend this far beyond the clear opening (casing).
  double window_casing_m = 0.05;      // Window labels extend this far beyond the clear opening.
  double casing_sigma_m = 0.01;       // Uncertainty of the casing widths (enters the ± of openings).
  double opening_band_m = 0.3;        // Door/window points within this behind a wall's line belong to it…
  double opening_front_m = 0.03;      // …and within this in front: casings (not sill boards, not open leaves).
  double opening_gap_m = 0.25;        // Openings on one wall are split at gaps longer than this.
  int min_opening_points = 12;        // Fewer points: not an opening.
  double min_opening_width_m = 0.25;  // Narrower clear openings are dropped.
  double edge_level = 0.01;           // Opening extent: 2 cm bins with at least this fraction of a full bin.
  int min_boundary_points = 4;        // Label-edge points needed per side to measure a width from them.
  // An open door's leaf hides its hinge-side edge from a rig in the room;
  // its width then comes from the leaf (door points standing up to
  // leaf_max_distance_m in front of the wall, along one line: a leaf is as
  // wide as its clear opening), measured from the edge that is seen.
  double leaf_max_distance_m = 1.5;
  int leaf_min_points = 20;
  int max_independent_points = 400;   // Dense points are correlated: cap the points a ± assumes.
  // Errors a wall's points share do not average out over them: a wall's
  // offset keeps this share of its points' median σ — for contacts (the
  // rig's height, a label edge a fraction of a pixel off along the whole
  // wall, a skirting's depth) and for stereo points (the matcher's
  // sub-pixel bias). docs/plan.md, "±", says how they were measured.
  double shared_sigma_fraction = 0.5;
  double shared_stereo_sigma_fraction = 0.25;
  std::optional<Vec3> viewpoint_m;    // Capture centre (rig position), if known; improves openings.
  std::uint64_t seed = 1;             // RANSAC sampling.

  void Check() const;
};

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_PLAN_OPTIONS_H_
