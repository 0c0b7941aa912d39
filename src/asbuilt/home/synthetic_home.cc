#include "asbuilt/home/synthetic_home.h"

#include <cmath>
#include <numbers>

namespace asbuilt {
namespace {

// A normal draw (Box–Muller) from the scene's deterministic generator.
double Normal(SceneRng& rng, double sigma) {
  const double u = std::max(1e-12, rng.Uniform(0, 1)), v = rng.Uniform(0, 1);
  return sigma * std::sqrt(-2 * std::log(u)) * std::cos(2 * std::numbers::pi * v);
}

}  // namespace

SyntheticHome MakeSyntheticHome(unsigned seed, const SyntheticHomeOptions& o) {
  SceneRng rng(seed);
  const HomeLayout layout = MakeHomeLayout(rng, o.layout);
  SyntheticHome home;
  home.doors = layout.doors;
  for (std::size_t r = 0; r < layout.rooms.size(); ++r) {
    Eigen::Isometry2d floor_from_room = Eigen::Isometry2d::Identity();
    floor_from_room.linear() = Eigen::Rotation2Dd(rng.Uniform(-std::numbers::pi, std::numbers::pi)).toRotationMatrix();
    floor_from_room.translation() = Vec2(rng.Uniform(-4, 4), rng.Uniform(-4, 4));
    const Eigen::Isometry2d room_from_floor = floor_from_room.inverse();
    std::vector<Vec2> corners = layout.rooms[r];
    home.outlines.push_back(corners);
    for (Vec2& c : corners) c = room_from_floor * c + Vec2(Normal(rng, o.jitter_m), Normal(rng, o.jitter_m));
    Plan plan;
    const std::size_t n = corners.size();
    for (std::size_t k = 0; k < n; ++k)
      plan.walls.push_back({.start = corners[k], .end = corners[(k + 1) % n], .height = 2.6});
    for (const HomeLayoutOpening& h : layout.openings) {
      if (h.room != static_cast<int>(r) || (h.kind == OpeningKind::kDoor && rng.Chance(o.missed_door))) continue;
      const PlanWall& w = plan.walls[h.wall];
      const Vec2 d = (w.end - w.start).normalized();
      const double s0 = h.offset_m + Normal(rng, o.jitter_m), s1 = h.offset_m + h.width_m + Normal(rng, o.jitter_m);
      const bool door = h.kind == OpeningKind::kDoor;
      plan.openings.push_back({.kind = h.kind,
                               .wall = h.wall,
                               .start = w.start + s0 * d,
                               .end = w.start + s1 * d,
                               .width = s1 - s0,
                               .height = door ? 2.0 : 1.2,
                               .sill = door ? 0.0 : 0.9});
    }
    plan.rooms.push_back({.polygon = corners, .area_m2 = std::abs(PolygonArea(corners))});
    home.rooms.push_back({.name = "room " + std::to_string(r + 1), .plan = std::move(plan)});
    home.floor_from_room.push_back(floor_from_room);
  }
  return home;
}

}  // namespace asbuilt
