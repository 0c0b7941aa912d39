#ifndef ASBUILT_GEOMETRY_POLYGON_H_
#define ASBUILT_GEOMETRY_POLYGON_H_

// Plan polygons (floor outlines, x/y metres), the verbs every layer shares.

#include <vector>

#include "asbuilt/geometry/rig.h"

namespace asbuilt {

// Whether `point` lies inside `polygon` (even-odd rule; either winding; a
// polygon of fewer than 3 points contains nothing). On an edge: either.
bool PointInPolygon(const std::vector<Vec2>& polygon, const Vec2& point);

}  // namespace asbuilt

#endif  // ASBUILT_GEOMETRY_POLYGON_H_
