#include "asbuilt/home/synthetic_home.h"

#include <algorithm>
#include <numbers>
#include <numeric>

namespace asbuilt {
namespace {

struct Rect {
  double x0, y0, x1, y1;
  double W() const { return x1 - x0; }
  double H() const { return y1 - y0; }
  // Corners counter-clockwise; wall k runs from corner k to k + 1:
  // 0 bottom, 1 right, 2 top, 3 left.
  std::vector<Vec2> Corners() const { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }
};

// An opening on one room's wall: `offset` from the wall's start.
struct Hole {
  int room, wall;
  double offset, width;
  OpeningKind kind;
};

std::vector<Rect> CutFloor(std::mt19937& rng, const SyntheticHomeOptions& o, int rooms) {
  std::uniform_real_distribution<double> width(9, 14), depth(7, 11), u(0, 1);
  std::vector<Rect> rects = {{0, 0, width(rng), depth(rng)}};
  const double t = o.wall_thickness_m, m = o.min_room_m;
  while (static_cast<int>(rects.size()) < rooms) {
    // Cut the largest room that can be cut, across its longer side.
    std::sort(rects.begin(), rects.end(), [](const Rect& a, const Rect& b) { return a.W() * a.H() > b.W() * b.H(); });
    bool cut = false;
    for (std::size_t i = 0; i < rects.size() && !cut; ++i) {
      const Rect r = rects[i];
      const bool across_x = r.W() >= r.H();
      const double side = across_x ? r.W() : r.H();
      if (side < 2 * m + t) continue;
      const double at = m + u(rng) * (side - 2 * m - t);
      Rect a = r, b = r;
      if (across_x) {
        a.x1 = r.x0 + at;
        b.x0 = a.x1 + t;
      } else {
        a.y1 = r.y0 + at;
        b.y0 = a.y1 + t;
      }
      rects[i] = a;
      rects.push_back(b);
      cut = true;
    }
    if (!cut) break;
  }
  return rects;
}

// Where two rooms share a partition: the walls facing each other and the
// stretch both cover (in the coordinate along the partition).
struct Shared {
  int a, b, wall_a, wall_b;
  bool along_y;  // The partition runs along y (a's right wall, b's left).
  double lo, hi;
};

std::vector<Shared> Partitions(const std::vector<Rect>& rects, double t) {
  std::vector<Shared> out;
  for (int a = 0; a < static_cast<int>(rects.size()); ++a) {
    for (int b = 0; b < static_cast<int>(rects.size()); ++b) {
      const Rect &ra = rects[a], &rb = rects[b];
      if (std::abs(ra.x1 + t - rb.x0) < 1e-9) {
        const double lo = std::max(ra.y0, rb.y0), hi = std::min(ra.y1, rb.y1);
        if (hi - lo >= 1.2) out.push_back({a, b, 1, 3, true, lo, hi});
      }
      if (std::abs(ra.y1 + t - rb.y0) < 1e-9) {
        const double lo = std::max(ra.x0, rb.x0), hi = std::min(ra.x1, rb.x1);
        if (hi - lo >= 1.2) out.push_back({a, b, 2, 0, false, lo, hi});
      }
    }
  }
  return out;
}

int Find(std::vector<int>& parent, int i) { return parent[i] == i ? i : parent[i] = Find(parent, parent[i]); }

}  // namespace

SyntheticHome MakeSyntheticHome(unsigned seed, const SyntheticHomeOptions& o) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> count(o.min_rooms, o.max_rooms);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> noise(0, o.jitter_m);
  const std::vector<Rect> rects = CutFloor(rng, o, count(rng));
  const int n = static_cast<int>(rects.size());

  // Doors: a spanning tree of the partitions, in random order, then more.
  std::vector<Shared> shared = Partitions(rects, o.wall_thickness_m);
  std::shuffle(shared.begin(), shared.end(), rng);
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<Hole> holes;
  SyntheticHome home;
  for (const Shared& s : shared) {
    const bool joins = Find(parent, s.a) != Find(parent, s.b);
    if (!joins && u(rng) >= o.extra_door) continue;
    parent[Find(parent, s.a)] = Find(parent, s.b);
    const double w = 0.7 + 0.2 * u(rng);
    const double start = s.lo + 0.1 + u(rng) * (s.hi - s.lo - 0.2 - w);  // Door from start to start + w.
    const Rect &ra = rects[s.a], &rb = rects[s.b];
    // Offsets from each wall's start (walls run counter-clockwise).
    const double off_a = s.along_y ? start - ra.y0 : ra.x1 - (start + w);
    const double off_b = s.along_y ? rb.y1 - (start + w) : start - rb.x0;
    holes.push_back({s.a, s.wall_a, off_a, w, OpeningKind::kDoor});
    holes.push_back({s.b, s.wall_b, off_b, w, OpeningKind::kDoor});
    ++home.doors;
  }
  // Windows on exterior walls.
  const Rect floor = {0, 0, 0, 0};
  double fx1 = 0, fy1 = 0;
  for (const Rect& r : rects) {
    fx1 = std::max(fx1, r.x1);
    fy1 = std::max(fy1, r.y1);
  }
  for (int r = 0; r < n; ++r) {
    const Rect& rc = rects[r];
    const bool exterior[4] = {rc.y0 <= floor.y0 + 1e-9, rc.x1 >= fx1 - 1e-9, rc.y1 >= fy1 - 1e-9,
                              rc.x0 <= floor.x0 + 1e-9};
    const double length[4] = {rc.W(), rc.H(), rc.W(), rc.H()};
    for (int k = 0; k < 4; ++k) {
      if (!exterior[k] || length[k] < 2.0 || u(rng) >= o.window) continue;
      const double w = 1.0 + 0.4 * u(rng);
      holes.push_back({r, k, 0.3 + u(rng) * (length[k] - 0.6 - w), w, OpeningKind::kWindow});
    }
  }

  // Each room as its survey sees it.
  std::uniform_real_distribution<double> yaw(-std::numbers::pi, std::numbers::pi), shift(-4, 4);
  for (int r = 0; r < n; ++r) {
    Eigen::Isometry2d floor_from_room = Eigen::Isometry2d::Identity();
    floor_from_room.linear() = Eigen::Rotation2Dd(yaw(rng)).toRotationMatrix();
    floor_from_room.translation() = Vec2(shift(rng), shift(rng));
    const Eigen::Isometry2d room_from_floor = floor_from_room.inverse();
    std::vector<Vec2> corners = rects[r].Corners();
    home.outlines.push_back(corners);
    for (Vec2& c : corners) c = room_from_floor * c + Vec2(noise(rng), noise(rng));
    Plan plan;
    for (int k = 0; k < 4; ++k) plan.walls.push_back({.start = corners[k], .end = corners[(k + 1) % 4], .height = 2.6});
    for (const Hole& h : holes) {
      if (h.room != r || (h.kind == OpeningKind::kDoor && u(rng) < o.missed_door)) continue;
      const PlanWall& w = plan.walls[h.wall];
      const Vec2 d = (w.end - w.start).normalized();
      const double s0 = h.offset + noise(rng), s1 = h.offset + h.width + noise(rng);
      plan.openings.push_back({.kind = h.kind,
                               .wall = h.wall,
                               .start = w.start + s0 * d,
                               .end = w.start + s1 * d,
                               .width = s1 - s0,
                               .height = h.kind == OpeningKind::kDoor ? 2.0 : 1.2,
                               .sill = h.kind == OpeningKind::kDoor ? 0.0 : 0.9});
    }
    plan.rooms.push_back({.polygon = corners, .area_m2 = std::abs(PolygonArea(corners))});
    home.rooms.push_back({.name = "room " + std::to_string(r + 1), .plan = std::move(plan)});
    home.floor_from_room.push_back(floor_from_room);
  }
  return home;
}

}  // namespace asbuilt
