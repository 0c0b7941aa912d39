#ifndef ASBUILT_SCENE_SCENE_TEXT_LAYOUT_H_
#define ASBUILT_SCENE_SCENE_TEXT_LAYOUT_H_

// Where the text → scene parser's request puts things (internal to scene/):
// the room's outline, its openings along the walls, the rig's spot. Each
// default chosen is added to `assumptions`; what cannot fit throws InputError
// (file "text") naming the clause.

#include <string>
#include <vector>

#include "asbuilt/scene/scene.h"
#include "asbuilt/scene/scene_text_request.h"

namespace asbuilt::scene_text {

// A w × d rectangle with its south-west corner at the origin; for an L, with
// the cut-out (by default half of each side, to 0.1 m) at the requested
// corner. Throws when the cut-out leaves a side under 0.5 m.
std::vector<Vec2> RoomPolygon(const Request& r, double w, double d, std::vector<std::string>& assumptions);

// The requested openings on `room`'s walls: a compass name means the longest
// wall facing that way; offsets along each wall are explicit placements
// first, the rest spread evenly (or, when that collides, into the largest
// free gaps).
std::vector<Opening> BuildOpenings(const Request& r, const Room& room, std::vector<std::string>& assumptions);

// The turn's spot: where a surveyor would stand (SurveySpot: a rectangle's
// centre, the meeting square of an L's wings); for a room no one spot sees
// whole, the centroid or the interior point nearest it.
Vec2 TurnSpot(const std::vector<Vec2>& polygon);

}  // namespace asbuilt::scene_text

#endif  // ASBUILT_SCENE_SCENE_TEXT_LAYOUT_H_
