#include "asbuilt/plan/plan_test_rooms.h"

namespace asbuilt {

Plan PolygonPlan(const std::vector<Vec2>& corners, double height) {
  Plan plan;
  int n = static_cast<int>(corners.size());
  for (int i = 0; i < n; ++i) {
    plan.walls.push_back({.start = corners[i], .end = corners[(i + 1) % n], .thickness = 0.2, .height = height});
  }
  plan.rooms.push_back({.polygon = corners, .area_m2 = PolygonArea(corners)});
  return plan;
}

void AddPlanOpening(Plan& plan, OpeningKind kind, int wall, double offset, double width, double height, double sill) {
  const PlanWall& w = plan.walls[wall];
  Vec2 d = (w.end - w.start).normalized();
  plan.openings.push_back({.kind = kind,
                           .wall = wall,
                           .start = w.start + offset * d,
                           .end = w.start + (offset + width) * d,
                           .width = width,
                           .height = height,
                           .sill = sill});
}

Plan Rotated(const Plan& plan, double angle_deg, const Vec2& shift) {
  Eigen::Rotation2Dd r(DegToRad(angle_deg));
  auto f = [&](const Vec2& p) -> Vec2 { return r * p + shift; };
  Plan out = plan;
  for (PlanWall& w : out.walls) {
    w.start = f(w.start);
    w.end = f(w.end);
  }
  for (PlanOpening& o : out.openings) {
    o.start = f(o.start);
    o.end = f(o.end);
  }
  for (PlanRoom& room : out.rooms) {
    for (Vec2& p : room.polygon) p = f(p);
  }
  return out;
}

Plan RectangleRoom() {
  Plan p = PolygonPlan({{0, 0}, {4.5, 0}, {4.5, 3.6}, {0, 3.6}});
  AddPlanOpening(p, OpeningKind::kDoor, 0, 0.4, 0.9, 2.1, 0.0);
  AddPlanOpening(p, OpeningKind::kWindow, 1, 0.9, 1.2, 1.4, 0.9);
  AddPlanOpening(p, OpeningKind::kWindow, 2, 1.2, 1.6, 1.4, 0.9);
  return p;
}

Plan LShape() {
  Plan p = PolygonPlan({{0, 0}, {6, 0}, {6, 2.6}, {2.6, 2.6}, {2.6, 5}, {0, 5}});
  AddPlanOpening(p, OpeningKind::kDoor, 5, 0.6, 0.9, 2.1, 0.0);
  AddPlanOpening(p, OpeningKind::kWindow, 0, 2.8, 1.5, 1.4, 0.9);
  AddPlanOpening(p, OpeningKind::kWindow, 4, 0.7, 1.2, 1.4, 0.9);
  return p;
}

Plan Trapezoid() {
  Plan p = PolygonPlan({{0, 0}, {5, 0}, {4, 4}, {0, 4}});
  AddPlanOpening(p, OpeningKind::kDoor, 3, 1.0, 0.8, 2.0, 0.0);
  AddPlanOpening(p, OpeningKind::kWindow, 1, 1.0, 1.2, 1.2, 1.0);
  return p;
}

Plan EightWalls() {
  Plan p = PolygonPlan({{0, 0}, {5.5, 0}, {5.5, 1}, {7, 1}, {7, 5}, {1.2, 5}, {1.2, 4}, {0, 4}});
  AddPlanOpening(p, OpeningKind::kDoor, 0, 3.0, 1.0, 2.1, 0.0);
  AddPlanOpening(p, OpeningKind::kWindow, 4, 1.5, 1.5, 1.4, 0.9);
  return p;
}

void AddWallRun(std::vector<ClassPoint>& points, const Vec2& a, const Vec2& b, int n, PointSource source) {
  const double z = source == PointSource::kContact ? 0.0 : 1.0;
  for (int i = 0; i < n; ++i) {
    const Vec2 p = a + (b - a) * (i + 0.5) / n + Vec2(0.002 * (i % 3 - 1), 0.002 * (i % 5 - 2));
    points.push_back({LabelClass::kWall, Vec3(p.x(), p.y(), z), 0.01, source, i % 12});
  }
}

void AddVertex(std::vector<ClassPoint>& points, const Vec2& corner, int frames) {
  for (int f = 0; f < frames; ++f) {
    const Vec2 p = corner + Vec2(0.02 * (f - 0.5), -0.015 * (f - 0.5));
    points.push_back({LabelClass::kWall, Vec3(p.x(), p.y(), 1.5), 0.03, PointSource::kVertex, f});
  }
}

std::vector<ClassPoint> BoundaryPoints(const Plan& plan, const Vec3& view, double depth_error_m) {
  std::vector<ClassPoint> out;
  int k = 0;
  for (const PlanOpening& o : plan.openings) {
    const bool door = o.kind == OpeningKind::kDoor;
    const double casing = door ? 0.07 : 0.05;
    const Vec2 along = (o.end - o.start).normalized(), inward(-along.y(), along.x());
    const double sill = o.sill.value_or(0.0), top = sill + o.height.value_or(2.0);
    // The casing stands kCasingDepth in front of the face. Its outer side
    // faces the viewpoint at one edge, where the label meets the wall on the
    // face; at the other the label ends at its front corner, which hides the
    // face beyond it: the edge is where the ray past that corner meets the face.
    constexpr double kCasingDepth = 0.015;
    const Vec2 v = view.head<2>();
    const double h = inward.dot(v - o.start);
    for (const auto& [edge, outward] : {std::pair<Vec2, Vec2>{o.start - casing * along, -along},
                                        std::pair<Vec2, Vec2>{o.end + casing * along, along}}) {
      const double beyond = outward.dot(edge - v);  // > 0: the outer side faces away.
      const Vec2 seen = beyond > 0 ? Vec2(edge + beyond * kCasingDepth / (h - kCasingDepth) * outward) : edge;
      for (double z = sill + 0.05; z < top; z += 0.05, ++k) {
        const Vec3 on_face(seen.x(), seen.y(), z);
        const double error = depth_error_m * ((k % 7) / 3.0 - 1.0);  // −1 … +1 of the bound.
        const Vec3 p = on_face + error * (on_face - view).normalized();
        out.push_back({door ? LabelClass::kDoor : LabelClass::kWindow, p, 0.03, PointSource::kBoundary, 0});
      }
    }
  }
  return out;
}

}  // namespace asbuilt
