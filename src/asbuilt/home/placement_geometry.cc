#include "asbuilt/home/placement_geometry.h"

#include <algorithm>

#include "asbuilt/geometry/polygon.h"
#include "asbuilt/plan/room_iou.h"

namespace asbuilt::placement {

RoomGeom GeomOf(const Plan& plan) {
  RoomGeom g;
  const std::vector<Vec2>* polygon = nullptr;
  for (const PlanRoom& r : plan.rooms) {
    if (r.polygon.size() >= 3) {
      polygon = &r.polygon;
      g.outline.rooms.push_back(PlanRoom{.polygon = r.polygon, .area_m2 = std::abs(PolygonArea(r.polygon))});
      g.area = g.outline.rooms.back().area_m2;
      break;
    }
  }
  Vec2 mean = Vec2::Zero();
  for (const PlanWall& w : plan.walls) mean += 0.5 * (w.start + w.end);
  if (!plan.walls.empty()) mean /= static_cast<double>(plan.walls.size());
  for (const PlanWall& w : plan.walls) {
    Face f{w.start, w.end, Vec2::Zero()};
    const Vec2 d = w.end - w.start;
    Vec2 n = d.norm() > 1e-9 ? Perp(d.normalized()) : Vec2(1, 0);
    const Vec2 mid = 0.5 * (w.start + w.end);
    const bool inward = polygon ? PointInPolygon(*polygon, mid + 0.05 * n) : n.dot(mean - mid) > 0;
    f.n = inward ? -n : n;
    g.walls.push_back(f);
    for (const Vec2& p : {w.start, w.end}) {
      g.lo = g.lo.cwiseMin(p);
      g.hi = g.hi.cwiseMax(p);
    }
  }
  if (polygon) {
    for (const Vec2& p : *polygon) {
      g.lo = g.lo.cwiseMin(p);
      g.hi = g.hi.cwiseMax(p);
    }
  }
  for (std::size_t i = 0; i < plan.openings.size(); ++i) {
    const PlanOpening& o = plan.openings[i];
    if (o.wall < 0 || o.wall >= static_cast<int>(g.walls.size())) continue;
    Hole h{static_cast<int>(i), o.wall, o.Centre(), g.walls[o.wall].n, o.width};
    (o.kind == OpeningKind::kDoor ? g.doors : g.windows).push_back(h);
  }
  g.wall_has_opening.assign(g.walls.size(), 0);
  for (const auto* holes : {&g.doors, &g.windows}) {
    for (const Hole& h : *holes) g.wall_has_opening[h.wall] = 1;
  }
  for (int k = 0; k < static_cast<int>(g.walls.size()); ++k) {
    if (!g.wall_has_opening[k]) g.plain_walls.push_back(k);
  }
  std::stable_sort(g.plain_walls.begin(), g.plain_walls.end(),
                   [&](int x, int y) { return g.walls[x].Length() > g.walls[y].Length(); });
  if (static_cast<int>(g.plain_walls.size()) > kPlainWalls) g.plain_walls.resize(kPlainWalls);
  return g;
}

RoomGeom Transformed(const RoomGeom& g, const Pose& t) {
  RoomGeom out;
  out.area = g.area;
  const Eigen::Matrix2d r = t.linear();
  for (const PlanRoom& room : g.outline.rooms) {
    PlanRoom moved = room;
    for (Vec2& p : moved.polygon) p = t * p;
    out.outline.rooms.push_back(std::move(moved));
  }
  for (const Face& f : g.walls) {
    out.walls.push_back({t * f.a, t * f.b, r * f.n});
    for (const Vec2& p : {out.walls.back().a, out.walls.back().b}) {
      out.lo = out.lo.cwiseMin(p);
      out.hi = out.hi.cwiseMax(p);
    }
  }
  for (const PlanRoom& room : out.outline.rooms) {
    for (const Vec2& p : room.polygon) {
      out.lo = out.lo.cwiseMin(p);
      out.hi = out.hi.cwiseMax(p);
    }
  }
  out.wall_has_opening = g.wall_has_opening;
  out.plain_walls = g.plain_walls;
  auto move = [&](const std::vector<Hole>& in, std::vector<Hole>& to) {
    for (Hole h : in) {
      h.c = t * h.c;
      h.n = r * h.n;
      to.push_back(h);
    }
  };
  move(g.doors, out.doors);
  move(g.windows, out.windows);
  return out;
}

Pose LinkTransform(const Hole& a, const Hole& b, double thickness) {
  const double yaw = std::atan2(-a.n.y(), -a.n.x()) - std::atan2(b.n.y(), b.n.x());
  Pose t = Pose::Identity();
  t.linear() = Eigen::Rotation2Dd(yaw).toRotationMatrix();
  t.translation() = a.c + thickness * a.n - t.linear() * b.c;
  return t;
}

Pose FaceTransform(const Face& f, double u, const Face& g, double s, double thickness) {
  const double yaw = std::atan2(-f.n.y(), -f.n.x()) - std::atan2(g.n.y(), g.n.x());
  Pose t = Pose::Identity();
  t.linear() = Eigen::Rotation2Dd(yaw).toRotationMatrix();
  t.translation() = f.a + u * f.Dir() + thickness * f.n - t.linear() * (g.a + s * g.Dir());
  return t;
}

std::vector<double> Slides(double u, double lf, double lg, double width) {
  std::vector<double> out;
  for (double s : {0.5 * lg, lf - u, lg - u}) {
    if (s < 0.5 * width + 0.05 || s > lg - 0.5 * width - 0.05) continue;
    if (std::none_of(out.begin(), out.end(), [&](double t) { return std::abs(t - s) < 0.02; })) out.push_back(s);
  }
  return out;
}

std::vector<OneSidedLink> OneSidedLinks(const RoomGeom& placed_a, const RoomGeom& b, const std::vector<char>& used_a,
                                        const std::vector<char>& used_b, double thickness) {
  std::vector<OneSidedLink> out;
  for (int i = 0; i < static_cast<int>(placed_a.doors.size()); ++i) {
    if (used_a[i]) continue;
    const Hole& da = placed_a.doors[i];
    const Face& f = placed_a.walls[da.wall];
    const double u = ProjectOnFace(f, da.c, 0).along;
    for (int k : b.plain_walls) {
      const Face& g = b.walls[k];
      if (g.Length() < da.width + 0.1) continue;
      for (double sl : Slides(u, f.Length(), g.Length(), da.width)) {
        out.push_back({.a_door = i, .b_wall = k, .pose = FaceTransform(f, u, g, sl, thickness)});
      }
    }
  }
  for (int j = 0; j < static_cast<int>(b.doors.size()); ++j) {
    if (used_b[j]) continue;
    const Hole& db = b.doors[j];
    const Face& g = b.walls[db.wall];
    const double sc = ProjectOnFace(g, db.c, 0).along;
    for (int k : placed_a.plain_walls) {
      const Face& f = placed_a.walls[k];
      if (f.Length() < db.width + 0.1) continue;
      for (double uu : Slides(sc, g.Length(), f.Length(), db.width)) {
        out.push_back({.b_door = j, .a_wall = k, .pose = FaceTransform(f, uu, g, sc, thickness)});
      }
    }
  }
  return out;
}

bool WidthsMatch(double a, double b, const PlacementOptions& o) {
  return std::abs(a - b) <= std::max(o.max_width_difference_m, o.width_tolerance * std::max(a, b));
}

bool DoorsMeet(const Hole& da, const Hole& db, const PlacementOptions& o) {
  if (da.n.dot(db.n) > -kAntiParallel || !WidthsMatch(da.width, db.width, o)) return false;
  const double across = (db.c - da.c).dot(da.n);
  const double along = std::abs((db.c - da.c).dot(Perp(da.n)));
  return across >= -0.05 && across <= o.max_wall_thickness_m && along <= 0.35;
}

FaceHit ProjectOnFace(const Face& f, const Vec2& p, double inset) {
  const double s = (p - f.a).dot(f.Dir());
  return {s, s >= inset && s <= f.Length() - inset};
}

const Face* FaceInFront(const Hole& h, const RoomGeom& y, const PlacementOptions& o) {
  for (const Face& f : y.walls) {
    if (h.n.dot(f.n) > -kAntiParallel) continue;
    const double dist = (f.a - h.c).dot(h.n);
    if (dist < -0.05 || dist > o.max_wall_thickness_m) continue;
    if (ProjectOnFace(f, h.c, 0.1).within) return &f;
  }
  return nullptr;
}

double OpeningsAgainstWalls(const RoomGeom& x, const RoomGeom& y, const PlacementOptions& o) {
  double score = 0.0;
  auto face_in_front = [&](const Hole& h) { return FaceInFront(h, y, o); };
  for (const Hole& d : x.doors) {
    const Face* f = face_in_front(d);
    if (f == nullptr) continue;
    const int wall = static_cast<int>(f - y.walls.data());
    const double s = ProjectOnFace(*f, d.c, 0).along;
    bool meets = false;
    for (const Hole& e : y.doors) {
      meets |=
          e.wall == wall && std::abs(ProjectOnFace(*f, e.c, 0).along - s) < 0.35 && WidthsMatch(d.width, e.width, o);
    }
    score += meets ? kDoorsMeet : -kDoorIntoWall;
  }
  for (const Hole& w : x.windows) {
    if (face_in_front(w) != nullptr) score -= kWindowIntoWall;
  }
  return score;
}

double SharedFaces(const RoomGeom& x, const RoomGeom& y, const PlacementOptions& o) {
  double metres = 0.0;
  for (const Face& f : x.walls) {
    for (const Face& g : y.walls) {
      if (f.n.dot(g.n) > -kFacesAntiParallel) continue;
      const double da = (g.a - f.a).dot(f.n), db = (g.b - f.a).dot(f.n);
      if (std::min(da, db) < -0.03 || std::max(da, db) > o.max_wall_thickness_m) continue;
      const double s0 = ProjectOnFace(f, g.a, 0).along, s1 = ProjectOnFace(f, g.b, 0).along;
      const double lo = std::max(0.0, std::min(s0, s1)), hi = std::min(f.Length(), std::max(s0, s1));
      if (hi - lo > 0.1) metres += hi - lo;
    }
  }
  return metres;
}

namespace {

// Walls of the two rooms that lie on one line, facing the same way, their
// ends a partition apart: one wall of the home running past a partition.
int ContinuingWalls(const RoomGeom& x, const RoomGeom& y, const PlacementOptions& o) {
  int count = 0;
  for (const Face& f : x.walls) {
    for (const Face& g : y.walls) {
      if (f.n.dot(g.n) < kFacesAntiParallel) continue;
      if (std::abs((g.a - f.a).dot(f.n)) > 0.05 || std::abs((g.b - f.a).dot(f.n)) > 0.05) continue;
      const double s0 = ProjectOnFace(f, g.a, 0).along, s1 = ProjectOnFace(f, g.b, 0).along;
      const double gap = std::max(std::min(s0, s1) - f.Length(), -std::max(s0, s1));
      if (gap >= -0.05 && gap <= o.max_wall_thickness_m) ++count;
    }
  }
  return count;
}

}  // namespace

void GrowBox(const RoomGeom& g, const Eigen::Matrix2d& axes, Vec2& lo, Vec2& hi) {
  for (const Face& f : g.walls) {
    for (const Vec2& p : {f.a, f.b}) {
      const Vec2 q = axes.transpose() * p;
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
  }
}

double BoxArea(const Vec2& lo, const Vec2& hi) { return lo.x() > hi.x() ? 0.0 : (hi - lo).prod(); }

bool BoxesNear(const RoomGeom& x, const RoomGeom& y, double margin) {
  return x.lo.x() <= y.hi.x() + margin && y.lo.x() <= x.hi.x() + margin && x.lo.y() <= y.hi.y() + margin &&
         y.lo.y() <= x.hi.y() + margin;
}

std::optional<double> PairScore(const RoomGeom& x, const RoomGeom& y, const PlacementOptions& o) {
  if (!BoxesNear(x, y, o.max_wall_thickness_m + 0.05)) return 0.0;
  double score = 0.0;
  if (!x.outline.rooms.empty() && !y.outline.rooms.empty()) {
    const auto overlap = RoomIntersectionArea(x.outline, y.outline, RoomIouOptions{.row_step_m = 0.02});
    if (overlap) {
      const double shared = *overlap;
      if (shared > o.max_overlap * std::min(x.area, y.area)) return std::nullopt;
      score -= kOverlapPerM2 * shared;
    }
  }
  score += kContactPerM * SharedFaces(x, y, o) + kContinues * ContinuingWalls(x, y, o);
  score += OpeningsAgainstWalls(x, y, o) + OpeningsAgainstWalls(y, x, o);
  return score;
}

}  // namespace asbuilt::placement
