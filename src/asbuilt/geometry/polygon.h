#ifndef ASBUILT_GEOMETRY_POLYGON_H_
#define ASBUILT_GEOMETRY_POLYGON_H_

// Plan polygons (floor outlines, x/y metres), the verbs every layer shares:
// inside, area, self-crossings, triangulation, offset.

#include <vector>

#include <Eigen/Core>

#include "asbuilt/geometry/rig.h"

namespace asbuilt {

// Whether `point` lies inside `polygon` (even-odd rule; either winding; a
// polygon of fewer than 3 points contains nothing). On an edge: either.
bool PointInPolygon(const std::vector<Vec2>& polygon, const Vec2& point);

// Signed area of a polygon (positive when counter-clockwise), m².
double PolygonArea(const std::vector<Vec2>& polygon);

// Pairs of non-neighbouring edges of the closed polygon that cross each
// other (0 for a simple polygon).
int PolygonCrossings(const std::vector<Vec2>& polygon);

// Triangulates a simple counter-clockwise polygon (ear clipping); returns
// index triples. Empty for fewer than 3 points.
std::vector<Eigen::Vector3i> TriangulatePolygon(const std::vector<Vec2>& polygon);

// The polygon offset outwards by `distance_m` (mitred corners) — the outer
// faces of walls of that thickness around a counter-clockwise polygon.
std::vector<Vec2> OffsetPolygonOutwards(const std::vector<Vec2>& polygon, double distance_m);

}  // namespace asbuilt

#endif  // ASBUILT_GEOMETRY_POLYGON_H_
