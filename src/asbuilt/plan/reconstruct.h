#ifndef ASBUILT_PLAN_RECONSTRUCT_H_
#define ASBUILT_PLAN_RECONSTRUCT_H_

// Floor plan from labelled class points (PAPER.md §8, issue 8), in stages
// (each stage's header, in this folder, states its contract; docs/plan.md
// describes them):
//
//  1. Planarize (plan_points.h): wall points → (x, y); each point weighted
//     by 1/σ², with its own inlier band max(ε, k·σ) (capped) and vote.
//  2. Lines (plan_lines.h): sequential RANSAC, hypotheses scored by the
//     inliers' votes (precise points count more), weighted total least
//     squares on the inliers, split at gaps along the line; points in no
//     line are outliers. A final competitive assignment (each point to the
//     line it fits best, within that line's extent) and refit removes
//     corner bias.
//  3. Directions (plan_directions.h): dominant directions from the lines
//     themselves (any angle), paired into a Manhattan frame when two are 90°
//     apart within the data's uncertainty; a line is snapped to its dominant
//     direction only when its own fitted direction agrees within
//     `snap_sigmas` standard errors.
//  4. Closing the room (plan_ring.h): lines ordered by angle around the
//     viewpoint (the capture centre, or the wall points' centroid), collinear
//     neighbours merged, neighbours intersected into corners; parallel or
//     implausible neighbours get an inferred connecting wall. Walls run
//     corner to corner, counter-clockwise (room on the left), so the polygon
//     is the room.
//  5. ± (plan_uncertainty.h): 1σ of every wall length and of the area from
//     the line fits' covariances (scaled by the fit residuals) propagated to
//     the corners.
//  6. Openings (plan_openings.h): door/window points within `opening_band_m`
//     of a wall are projected onto it (along the viewing ray when the
//     viewpoint is known), grouped along the wall, their label extent taken
//     from the binned density (partly occluded stretches count, strays do
//     not) and the casing removed to give the clear opening; height and sill
//     from z; ± from the opening points' spread.

#include <optional>
#include <string>
#include <vector>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/formats/points_file.h"
#include "asbuilt/plan/plan_options.h"

namespace asbuilt {

struct PlanSummary {
  int input_points = 0;
  int wall_points = 0;
  int door_points = 0;
  int window_points = 0;
  int wall_inliers = 0;  // Wall points assigned to a wall line.
  int outliers = -1;     // Wall points in no line (−1: never computed).
  int lines_found = 0;   // Lines before ordering/merging.
  int walls = 0;
  int inferred_walls = 0;           // Connecting walls with no points of their own.
  std::vector<bool> wall_inferred;  // Per wall of the plan: inferred (no points of its own).
  int openings = 0;
  int door_leaves = 0;                          // Door widths taken from an open leaf (hinge side hidden).
  bool closed = false;                          // Walls form a closed room polygon.
  bool manhattan = false;                       // A Manhattan frame was found and used.
  std::vector<double> dominant_directions_deg;  // In [0, 180).
  double rms_residual_m = -1;                   // Of wall inliers about their lines (−1: never computed).
  double area_m2 = -1;
  double seconds = 0;

  // "6 walls (0 inferred), 3 openings, closed, 21.84 m², Manhattan 12.0°, rms 0.012 m, 0.04 s".
  std::string BriefReport() const;
};

struct PlanResult {
  Plan plan;
  PlanSummary summary;
};

// Throws InvalidArgument on bad options, and Error when fewer than two wall
// lines can be found (too few or too scattered wall points); that error
// starts with `points_source` (the point file or capture the points came
// from) when given, so the user learns which input is at fault.
PlanResult ReconstructPlan(const std::vector<ClassPoint>& points, const PlanOptions& options = {},
                           const std::string& points_source = "");

// Pieces of wall `wall` left after cutting out its openings (interval
// trimming), as [t0, t1] distances from the wall's start, in order.
std::vector<std::pair<double, double>> WallPiecesBetweenOpenings(const Plan& plan, int wall);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_RECONSTRUCT_H_
