#include "asbuilt/scene/procedural_home.h"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

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

std::vector<Rect> CutFloor(SceneRng& rng, const HomeLayoutOptions& o, int rooms) {
  std::vector<Rect> rects = {
      {0, 0, rng.Uniform(o.min_width_m, o.max_width_m), rng.Uniform(o.min_depth_m, o.max_depth_m)}};
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
      const double at = m + rng.Uniform(0, 1) * (side - 2 * m - t);
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

void HomeLayoutOptions::Check() const {
  auto fail = [](const std::string& what) { throw InvalidArgument("HomeLayoutOptions: " + what); };
  if (min_rooms < 1 || max_rooms < min_rooms || max_rooms > 100) fail("need 1 ≤ min_rooms ≤ max_rooms ≤ 100");
  if (!(min_width_m > 0 && max_width_m >= min_width_m && min_depth_m > 0 && max_depth_m >= min_depth_m)) {
    fail("the floor's sides must be positive ranges");
  }
  if (!(min_room_m >= 1.0)) fail("min_room_m must be at least 1 m");
  if (!(wall_thickness_m > 0 && wall_thickness_m <= 0.5)) fail("wall_thickness_m must be in (0, 0.5]");
  if (!(extra_door >= 0 && extra_door <= 1 && window >= 0 && window <= 1 && exterior_door >= 0 && exterior_door <= 1))
    fail("chances must be in [0, 1]");
}

HomeLayout MakeHomeLayout(SceneRng& rng, const HomeLayoutOptions& o) {
  o.Check();
  const std::vector<Rect> rects = CutFloor(rng, o, rng.UniformInt(o.min_rooms, o.max_rooms));
  const int n = static_cast<int>(rects.size());
  HomeLayout layout;
  layout.wall_thickness_m = o.wall_thickness_m;
  for (const Rect& r : rects) layout.rooms.push_back(r.Corners());

  // Doors: a spanning tree of the partitions, in random order, then more.
  std::vector<Shared> shared = Partitions(rects, o.wall_thickness_m);
  for (std::size_t i = shared.size(); i > 1; --i) std::swap(shared[i - 1], shared[rng.UniformInt(0, int(i) - 1)]);
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const Shared& s : shared) {
    const bool joins = Find(parent, s.a) != Find(parent, s.b);
    if (!joins && !rng.Chance(o.extra_door)) continue;
    parent[Find(parent, s.a)] = Find(parent, s.b);
    const double w = rng.Uniform(0.7, 0.9);
    const double start = s.lo + 0.1 + rng.Uniform(0, 1) * (s.hi - s.lo - 0.2 - w);  // Door from start to start + w.
    const Rect &ra = rects[s.a], &rb = rects[s.b];
    // Offsets from each wall's start (walls run counter-clockwise).
    const double off_a = s.along_y ? start - ra.y0 : ra.x1 - (start + w);
    const double off_b = s.along_y ? rb.y1 - (start + w) : start - rb.x0;
    layout.openings.push_back({s.a, s.wall_a, OpeningKind::kDoor, off_a, w});
    layout.openings.push_back({s.b, s.wall_b, OpeningKind::kDoor, off_b, w});
    ++layout.doors;
  }
  // Windows on exterior walls.
  double fx1 = 0, fy1 = 0;
  for (const Rect& r : rects) {
    fx1 = std::max(fx1, r.x1);
    fy1 = std::max(fy1, r.y1);
  }
  for (int r = 0; r < n; ++r) {
    const Rect& rc = rects[r];
    const bool exterior[4] = {rc.y0 <= 1e-9, rc.x1 >= fx1 - 1e-9, rc.y1 >= fy1 - 1e-9, rc.x0 <= 1e-9};
    const double length[4] = {rc.W(), rc.H(), rc.W(), rc.H()};
    for (int k = 0; k < 4; ++k) {
      if (!exterior[k]) continue;
      // A door to the outside (front, patio or garage door; a door to a
      // space nobody surveyed looks the same): a door of one room only.
      if (o.exterior_door > 0 && length[k] >= 1.5 && rng.Chance(o.exterior_door)) {
        const double w = rng.Chance(0.25) ? rng.Uniform(1.5, std::min(2.4, length[k] - 0.2)) : rng.Uniform(0.8, 1.0);
        layout.openings.push_back({r, k, OpeningKind::kDoor, 0.1 + rng.Uniform(0, 1) * (length[k] - 0.2 - w), w});
        continue;
      }
      if (length[k] < 2.0 || !rng.Chance(o.window)) continue;
      const double w = rng.Uniform(1.0, 1.4);
      layout.openings.push_back({r, k, OpeningKind::kWindow, 0.3 + rng.Uniform(0, 1) * (length[k] - 0.6 - w), w});
    }
  }
  return layout;
}

Scene HomeScene(const HomeLayout& layout, std::uint64_t seed, double height_m) {
  Scene scene;
  scene.name = "home";
  scene.seed = seed;
  for (std::size_t r = 0; r < layout.rooms.size(); ++r) {
    Room room;
    room.name = fmt::format("room {}", r + 1);
    room.polygon = layout.rooms[r];
    room.height_m = height_m;
    room.wall_thickness_m = layout.wall_thickness_m;
    for (const HomeLayoutOpening& o : layout.openings) {
      if (o.room != static_cast<int>(r)) continue;
      Opening op;
      op.kind = o.kind;
      op.wall = o.wall;
      op.offset_m = o.offset_m;
      op.width_m = o.width_m;
      op.height_m = o.kind == OpeningKind::kDoor ? 2.0 : 1.2;
      op.sill_m = o.kind == OpeningKind::kDoor ? 0.0 : 0.9;
      room.openings.push_back(op);
    }
    Vec2 centre = Vec2::Zero();
    for (const Vec2& p : room.polygon) centre += p / static_cast<double>(room.polygon.size());
    scene.lights.push_back({.kind = LightKind::kArea, .position_m = Vec3(centre.x(), centre.y(), height_m - 0.05)});
    scene.rooms.push_back(std::move(room));
  }
  return scene;
}

}  // namespace asbuilt
