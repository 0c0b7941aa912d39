#ifndef ASBUILT_PLAN_PLAN_RING_VISIBLE_H_
#define ASBUILT_PLAN_PLAN_RING_VISIBLE_H_

// Plan stage 4a, for a capture taken from one spot (PlanOptions::
// one_viewpoint: panorama and mono captures; internal to plan/): the walls
// the camera saw, one per bearing, before the ring is closed (plan_ring.h).
//
// Every wall point was seen from the viewpoint, so along each bearing the
// room shows one wall: the visible boundary is a star-shaped polygon about
// the viewpoint, the way panorama layout methods decode one wall boundary
// per image column (HorizonNet, Sun et al. 2019; LED2-Net, Wang et al.
// 2021). Points that fit no such boundary — floor contacts of furniture
// inside the room, tops of things projected beyond a wall, a neighbouring
// room seen through a door — then cannot cut the room polygon.
//
//  - Candidates: the snapped wall lines, and along each dominant direction
//    the peaks of the wall points' offsets (votes within ±epsilon_m of an
//    offset, at least min_wall_points; a wall the line fit split, or missed
//    among clutter).
//  - Bearings are cut in 1° bins around the viewpoint. A candidate's score
//    in a bin is the votes of the bin's points within their inlier band of
//    it, less the votes of those seen beyond it along their ray (an opaque
//    wall hides what lies behind it; nearer points may be furniture before
//    it); invalid where the bin's ray does not meet it within 0.3–30 m. A
//    bin whose ray meets no candidate (a camera outside the room, looking
//    out of its doorway) lets any candidate carry through it at no score.
//  - Dynamic programming around the circle picks one candidate per bin,
//    maximising the score less a cost per change: a corner (the two lines
//    meet at that bearing) costs the votes of a typical bin (the median over
//    bins with points), a jump (an occluding edge, e.g. the far wing of an L
//    behind a corner) three times that. In a Manhattan frame every change to
//    or from a line along neither axis costs a jump: such walls stay
//    possible, but need that much more support. A line thus wins a stretch
//    of bearings only by holding more of its points than the changes cost.
//  - Each run of bins with one candidate becomes a line refitted (at the
//    candidate's angle) on its inliers in those bearings; runs with fewer
//    than min_wall_points votes are left to the ring's connectors.
// Returns the lines in bearing order; `lines` unchanged when the viewpoint
// is unknown or the points give fewer than two runs.

#include <vector>

#include "asbuilt/plan/plan_directions.h"
#include "asbuilt/plan/plan_wall_line.h"

namespace asbuilt {

std::vector<WallLine> SelectVisibleLines(const WallPoints& walls, std::vector<WallLine> lines,
                                         const DirectionFrame& frame, const PlanOptions& o);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_PLAN_RING_VISIBLE_H_
