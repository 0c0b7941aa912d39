#ifndef ASBUILT_PLAN_PLAN_RING_H_
#define ASBUILT_PLAN_PLAN_RING_H_

// Plan stage 4, the ring (internal to plan/): snapped wall lines → the walls
// of one closed room, in order around the viewpoint.
//
//  - Order: lines are oriented counter-clockwise around the viewpoint
//    (PlanOptions::viewpoint_m, or the length-weighted centre of the lines)
//    and ordered by the bearing of their middle; a line mostly hidden behind
//    or in front of a much better supported one in the same bearings is
//    clutter, and so is one between two pieces of one wall and wholly behind
//    that wall's line (seen through its openings).
//  - Room vertices (wall–wall corner columns, PointSource::kVertex) are
//    clustered across frames; they join two walls across the lines seen
//    through them, and decide corners that the wall points leave open.
//  - Neighbours that continue each other are merged.
//  - Corners: neighbours are intersected; where they are parallel or would
//    meet more than max_corner_extension_m beyond their points, a connecting
//    wall is inferred (two, turning at a corner, when both ends of the gap
//    are vertices and the gap runs across the dominant directions) — unless
//    the connector runs along a neighbour's own line, which is then that wall
//    extended to its corner.
// With PlanOptions::one_viewpoint (a capture from one spot) the lines are
// first reduced to one wall per bearing (plan_ring_visible.h).
// docs/plan.md, step 4, gives each rule's reason and the cases it was
// measured on.

#include <vector>

#include "asbuilt/plan/plan_directions.h"
#include "asbuilt/plan/plan_points.h"

namespace asbuilt {

struct Ring {
  // The room's walls, counter-clockwise with the room on their left; wall i
  // runs from corner i to corner i + 1 (RingCorners). Inferred walls have no
  // members.
  std::vector<WallLine> walls;
  Vec2 viewpoint = Vec2::Zero();  // What the ring was ordered around, in plan, m.
  int inferred_walls = 0;         // Connecting walls with no points of their own.
};

// Throws nothing; `lines` should hold at least two lines (the ring of fewer
// than three walls is not closed).
Ring CloseRoom(const WallPoints& walls, std::vector<WallLine> lines, const std::vector<VertexPoint>& vertex_points,
               const DirectionFrame& frame, const PlanOptions& o);

// Corner i joins ring[i − 1] and ring[i]: where their lines cross; for
// neighbours within 1° of parallel, the midpoint of their ends.
std::vector<Vec2> RingCorners(const std::vector<WallLine>& ring);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_PLAN_RING_H_
