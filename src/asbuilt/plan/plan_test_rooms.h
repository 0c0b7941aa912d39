#ifndef ASBUILT_PLAN_PLAN_TEST_ROOMS_H_
#define ASBUILT_PLAN_PLAN_TEST_ROOMS_H_

// Truth rooms and synthetic points for the plan tests (test-only; linked
// into plan_test). Plans are in metres, walls counter-clockwise.

#include <vector>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/formats/points_file.h"

namespace asbuilt {

// The room with these corners (counter-clockwise), walls 0.2 m thick and
// `height` high, no openings.
Plan PolygonPlan(const std::vector<Vec2>& corners, double height = 2.7);

// Adds an opening on `wall`, `offset` m from its start, `width` m wide.
void AddPlanOpening(Plan& plan, OpeningKind kind, int wall, double offset, double width, double height, double sill);

// `plan` rotated by `angle_deg` about the origin, then shifted.
Plan Rotated(const Plan& plan, double angle_deg, const Vec2& shift);

// 4.5 × 3.6 m with a door and two windows.
Plan RectangleRoom();
// An L of 6 × 5 m with a door and two windows.
Plan LShape();
// Non-Manhattan: a trapezoid with one slanted wall.
Plan Trapezoid();
// Eight walls, two corners cut out; every wall visible from the centre.
Plan EightWalls();

// `n` wall points (σ 1 cm) along a → b, scattered by ±2 mm; contacts lie on
// the floor, other points 1 m up.
void AddWallRun(std::vector<ClassPoint>& points, const Vec2& a, const Vec2& b, int n, PointSource source);

// Vertex points (wall–wall corner columns) of `frames` frames at `corner`,
// a few centimetres apart, as the stereo stage gives them.
void AddVertex(std::vector<ClassPoint>& points, const Vec2& corner, int frames = 2);

// Label-edge (boundary) points of every opening of `plan`: on the wall face
// at the label's edges (the casing's outer edges; where a 1.5 cm deep
// casing's outer side faces away from `view`, where the ray past its front
// corner meets the face), every 5 cm in height, each
// moved along its viewing ray by up to ±`depth_error_m` (what stereo depth
// error does), as ComputeFramePoints makes them.
std::vector<ClassPoint> BoundaryPoints(const Plan& plan, const Vec3& view, double depth_error_m);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_PLAN_TEST_ROOMS_H_
