#ifndef ASBUILT_PLAN_PLAN_DIRECTIONS_H_
#define ASBUILT_PLAN_PLAN_DIRECTIONS_H_

// Plan stage 3, directions (internal to plan/): the dominant directions of
// the wall lines, a Manhattan frame when two of them are square within the
// data's uncertainty, and the lines snapped onto them.
//
// A line's var θ first covers how far its halves disagree with it
// (PlanOptions::bend_sigmas). Directions cluster the lines' angles (within
// snap_max_deg, strongest lines first), each weighted by 1/var θ. Two
// directions form a Manhattan frame when they are 90° apart within
// manhattan_max_deg (or their σ, when wider, up to manhattan_snap_max_deg)
// and within snap_sigmas of their σ (always within manhattan_always_deg).
// A line snaps (is refitted at the direction's angle, taking its σ) when
// its own fit agrees within snap_sigmas of σ (between snap_min_deg and
// snap_max_deg); in a Manhattan frame, within manhattan_snap_max_deg of an
// axis, or up to noisy_snap_max_deg when the axis explains its points within
// their noise. Lines that became collinear are merged. docs/plan.md, step 3, says why and what it was measured on.

#include <vector>

#include "asbuilt/plan/plan_wall_line.h"

namespace asbuilt {

struct Direction {
  double theta = 0;                           // In [0, π).
  double sum_w = 0;                           // Σ 1/var_theta of its lines.
  double Var() const { return 1.0 / sum_w; }  // rad².
};

struct DirectionFrame {
  std::vector<Direction> directions;  // The two axes of a Manhattan frame are exactly 90° apart.
  bool manhattan = false;             // A Manhattan frame was found and used.
  std::vector<int> axes;              // Indices of its two axes in `directions` (empty: no frame).
};

struct SnappedLines {
  std::vector<WallLine> lines;
  DirectionFrame frame;
};

SnappedLines SnapToDominantDirections(const WallPoints& walls, std::vector<WallLine> lines, const PlanOptions& o);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_PLAN_DIRECTIONS_H_
