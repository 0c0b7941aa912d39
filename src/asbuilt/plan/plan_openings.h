#ifndef ASBUILT_PLAN_PLAN_OPENINGS_H_
#define ASBUILT_PLAN_PLAN_OPENINGS_H_

// Plan stage 6, openings (internal to plan/): door and window points → the
// openings on the plan's walls, with ±.
//
// A point belongs to the wall whose face it is nearest, within
// PlanOptions::opening_band_m behind it or opening_front_m in front, and
// within 0.3 m of its ends. Noisy points (σ > 1 cm), label-edge points
// (PointSource::kBoundary) and points behind the face are projected onto the
// wall along their viewing ray when the viewpoint is known (which cancels
// depth error); the others perpendicularly. Per wall and kind, points are
// grouped along the wall (split at gaps > opening_gap_m and at piers: a gap
// with wall label edges at both its ends); a group of min_opening_points or
// more gives an opening when at least min_opening_points of them are its own
// (not label edges). Its extent comes from 2 cm bins holding edge_level of a
// well-filled bin; an edge with min_boundary_points label-edge points is
// their median instead, moved back by casing_depth_m's parallax where the
// casing hides its own outer side from the viewpoint. Label-edge points may
// stand up to inlier_sigmas σ (at most max_inlier_distance_m) in front of the
// face. A door seen with a label edge on one side only takes its width from
// its open leaf when one is found (door points up to leaf_max_distance_m in
// front of the wall along one line). The clear
// opening is the extent minus the casing (door_casing_m, window_casing_m) on
// each side (not where the points stop behind the face: glass seen through
// the opening ends at the clear opening's edge), clamped to the wall;
// narrower than min_opening_width_m: none.
// Height and sill come from the z extent minus the casing; a door no taller
// than min_door_height_m is none (door labels on the floor), and so is a
// door with wall seen low across its span (door_wall_below_share).

#include <vector>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/formats/points_file.h"
#include "asbuilt/plan/plan_options.h"
#include "asbuilt/plan/plan_wall_line.h"

namespace asbuilt {

struct FoundOpenings {
  std::vector<PlanOpening> openings;  // Ordered by wall, then along it.
  int door_leaves = 0;                // Door widths taken from an open leaf.
};

// `points`: door and window points; `walls`: the plan's walls (room on their
// left); `viewpoint`: in plan, m, where the walls were seen from (the ring's
// viewpoint); it places points along their rays only when
// PlanOptions::viewpoint_m is set, and always scales the ± of label edges
// (label_edge_sigma_mrad). `wall_points`, when given, drop a door whose
// clear span shows wall low on the face (door_wall_below_share: a door label
// painted down a plain wall). Deterministic for a given PlanOptions::seed.
FoundOpenings FindOpenings(const std::vector<const ClassPoint*>& points, const std::vector<PlanWall>& walls,
                           const Vec2& viewpoint, const PlanOptions& o, const WallPoints* wall_points = nullptr);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_PLAN_OPENINGS_H_
