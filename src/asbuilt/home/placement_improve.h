#ifndef ASBUILT_HOME_PLACEMENT_IMPROVE_H_
#define ASBUILT_HOME_PLACEMENT_IMPROVE_H_

// A complete placement improved by swapping links (internal to home/; see
// home/placement.h). The beam search adds rooms door-to-door first, so a
// door whose other side a survey missed is linked to some other door that
// fits, and the rooms beyond it follow. Here each link of the placement's
// tree is cut in turn; the part of the home beyond it is joined back by
// every other link between the two parts (door to door, or one-sided onto a
// plain wall), moved as one, and the best swap that raises the home's score
// (the search's terms over the pairs of rooms that moved against the rooms
// that did not, the links' own terms, the home's box) is kept, until none
// does.

#include <vector>

#include "asbuilt/home/placement.h"
#include "asbuilt/home/placement_geometry.h"
#include "asbuilt/home/placement_search.h"

namespace asbuilt::placement {

// `s` (grown from `seed`) with links swapped while that raises its score by
// more than `min_gain`; s.score, poses, links and doors used follow. A link
// a person asked for is never cut, a link they refused never made, and a part
// that holds a room they fixed never moves.
void ImproveBySwaps(const std::vector<RoomGeom>& geoms, int seed, const PlacementOptions& o,
                    const PlacementConstraints& c, State& s, double min_gain = 0.5);

}  // namespace asbuilt::placement

#endif  // ASBUILT_HOME_PLACEMENT_IMPROVE_H_
