#ifndef ASBUILT_PLAN_PLAN_POINTS_H_
#define ASBUILT_PLAN_PLAN_POINTS_H_

// Plan stage 1, planarize (internal to plan/): labelled class points → wall
// points in plan (each with its weight 1/σ², inlier band and vote), the
// door/window points, and the room-vertex points. Points with a non-finite
// position are skipped; a σ of 0 means PlanOptions::nominal_sigma_m.

#include <vector>

#include "asbuilt/formats/points_file.h"
#include "asbuilt/plan/plan_wall_line.h"

namespace asbuilt {

// A wall–wall corner column seen in one frame (PointSource::kVertex).
struct VertexPoint {
  Vec2 p;        // In plan, m.
  double sigma;  // m.
};

struct PlanPoints {
  WallPoints walls;  // Label kWall, source other than kVertex.
  // Door and window points, pointing into the caller's points (which must
  // outlive this).
  std::vector<const ClassPoint*> openings;
  std::vector<VertexPoint> vertices;
  int door_points = 0;
  int window_points = 0;
};

// Sorts `points` by label and source and planarizes the wall points. Votes
// weigh precision (PlanOptions::vote_sigma_m) only when some wall point is a
// floor/ceiling contact; otherwise every vote is 1.
PlanPoints PlanarizePoints(const std::vector<ClassPoint>& points, const PlanOptions& o);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_PLAN_POINTS_H_
