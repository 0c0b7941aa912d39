#ifndef ASBUILT_HOME_PLACEMENT_REFINE_H_
#define ASBUILT_HOME_PLACEMENT_REFINE_H_

// From a search state to a HomePlacement (internal to home/; see
// home/placement.h): the loops it closes, its refinement by least squares
// over every link and partition, and what placed each room.

#include <vector>

#include "asbuilt/home/placement.h"
#include "asbuilt/home/placement_geometry.h"
#include "asbuilt/home/placement_search.h"

namespace asbuilt::placement {

// State `s`, grown from room `seed`, as a home: its loops found; refined
// over every link and partition face, the loops and faces that cannot close
// within 5 cm dropped; what placed each room; rooms no link reached placed
// by their hints. The seed and the rooms a person fixed are held.
// `refine`: false for the alternatives (offered to pick from; their poses
// as the search left them, the partition at its prior).
HomePlacement Finish(const std::vector<HomeRoomInput>& rooms, const std::vector<RoomGeom>& geoms, int seed,
                     const PlacementOptions& o, const PlacementConstraints& c, State s, bool refine);

}  // namespace asbuilt::placement

#endif  // ASBUILT_HOME_PLACEMENT_REFINE_H_
