#ifndef ASBUILT_PLAN_PLAN_LINES_H_
#define ASBUILT_PLAN_PLAN_LINES_H_

// Plan stage 2, lines (internal to plan/): wall points → wall lines.
// Sequential RANSAC with each point's own inlier band, hypotheses scored by
// votes on a random subset (PlanOptions::ransac_subset_points) and drawn by
// vote; weighted total least squares on the inliers, split into dense runs
// along the line. With contact points, RANSAC runs on the contacts alone
// first, then on every point not taken. A competitive assignment (each point
// to the line it fits best within that line's extent) and refit removes the
// bias of corner points; duplicate fits and collinear pieces are merged;
// lines sparser than min_relative_density of the densest, or with less than
// min_wall_fraction of all votes, are dropped unless strongly supported
// (WallPoints::strong_line_votes). Deterministic for a given
// PlanOptions::seed; with PlanOptions::one_viewpoint the draws are tied to
// the points (a hash of the seed and each point's position to 1 cm), so the
// lines do not depend on the points' order, and a point more or less
// changes only the draws it wins. Lines run in their fitted direction (not
// yet oriented).

#include <vector>

#include "asbuilt/plan/plan_wall_line.h"

namespace asbuilt {

struct FittedLines {
  std::vector<WallLine> lines;
  int ransac_lines = 0;  // Lines sequential RANSAC found, before refit and merging.
};

FittedLines FindWallLines(const WallPoints& walls, const PlanOptions& o);

// Merges pairs of lines that are duplicate fits of one wall's points
// (crossing at < 15° through the same stretch, each within
// max_inlier_distance_m of the other's centre) or collinear pieces
// (CollinearLines) at most max_gap_m apart along their direction, refitting
// the union; when the pair's first line has var_theta > 0 and at least the
// other's votes, the union keeps its direction and σ (a snapped line stays
// snapped). Repeats until no pair merges.
void MergeCollinearLines(const std::vector<WallPoint>& pts, std::vector<WallLine>& lines, const PlanOptions& o);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_PLAN_LINES_H_
