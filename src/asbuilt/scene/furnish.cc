#include "asbuilt/scene/furnish.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

struct Catalogue {
  std::vector<std::string> names;  // Singular and plural words.
  std::map<std::string, FurnitureSpec> by_word;
};

const Catalogue& TheCatalogue() {
  static const Catalogue kCatalogue = [] {
    struct Row {
      std::vector<std::string> words;
      FurnitureSpec spec;
    };
    const std::vector<Row> rows = {
        {{"desk", "desks"}, {"desk", Vec3(1.2, 0.6, 0.75), true}},
        {{"table", "tables"}, {"table", Vec3(1.6, 0.9, 0.75), false}},
        {{"chair", "chairs"}, {"chair", Vec3(0.45, 0.45, 0.9), false}},
        {{"bed", "beds"}, {"bed", Vec3(1.6, 2.1, 0.55), true}},
        {{"sofa", "sofas", "couch", "couches", "settee"}, {"sofa", Vec3(2.0, 0.9, 0.85), true}},
        {{"armchair", "armchairs"}, {"armchair", Vec3(0.9, 0.9, 0.9), false}},
        {{"wardrobe", "wardrobes", "closet"}, {"wardrobe", Vec3(1.2, 0.6, 2.0), true}},
        {{"bookshelf", "bookshelves", "bookcase", "bookcases", "shelf", "shelves", "shelving"},
         {"bookshelf", Vec3(0.9, 0.35, 1.9), true}},
        {{"cabinet", "cabinets", "cupboard", "cupboards", "locker", "lockers"}, {"cabinet", Vec3(1.0, 0.5, 1.8), true}},
        {{"counter", "counters", "worktop", "worktops", "kitchen counter"}, {"counter", Vec3(2.4, 0.6, 0.9), true}},
        {{"fridge", "fridges", "refrigerator"}, {"fridge", Vec3(0.6, 0.65, 1.8), true}},
        {{"stove", "oven", "cooker"}, {"stove", Vec3(0.6, 0.6, 0.9), true}},
        {{"sink", "sinks", "washbasin", "basin"}, {"sink", Vec3(0.6, 0.45, 0.85), true}},
        {{"bathtub", "bath", "tub"}, {"bathtub", Vec3(1.7, 0.75, 0.55), true}},
        {{"toilet", "toilets", "wc"}, {"toilet", Vec3(0.4, 0.65, 0.75), true}},
        {{"shower", "showers"}, {"shower", Vec3(0.9, 0.9, 2.0), true}},
        {{"tv", "television", "tvs"}, {"tv unit", Vec3(1.4, 0.4, 0.5), true}},
        {{"nightstand", "nightstands", "bedside"}, {"nightstand", Vec3(0.45, 0.4, 0.55), true}},
        {{"dresser", "dressers", "chest"}, {"dresser", Vec3(1.0, 0.5, 0.9), true}},
        {{"workbench", "workbenches", "bench", "benches"}, {"workbench", Vec3(2.0, 0.7, 0.9), true}},
        {{"piano", "pianos"}, {"piano", Vec3(1.5, 0.6, 1.2), true}},
        {{"plant", "plants"}, {"plant", Vec3(0.5, 0.5, 1.2), false}},
        {{"box", "boxes", "crate", "crates"}, {"box", Vec3(0.6, 0.4, 0.4), false}},
    };
    Catalogue c;
    for (const Row& r : rows) {
      for (const std::string& w : r.words) {
        c.names.push_back(w);
        c.by_word[w] = r.spec;
      }
    }
    return c;
  }();
  return kCatalogue;
}

// An oriented rectangle on the floor.
struct Box2 {
  Vec2 centre;
  Vec2 half;     // Half extents along the local axes.
  double angle;  // Radians, local x from +X.

  Vec2 AxisX() const { return Vec2(std::cos(angle), std::sin(angle)); }
  Vec2 AxisY() const { return Vec2(-std::sin(angle), std::cos(angle)); }
  std::array<Vec2, 4> Corners() const {
    Vec2 ax = half.x() * AxisX(), ay = half.y() * AxisY();
    return {centre - ax - ay, centre + ax - ay, centre + ax + ay, centre - ax + ay};
  }
  bool Contains(const Vec2& p) const {
    Vec2 d = p - centre;
    return std::abs(d.dot(AxisX())) < half.x() && std::abs(d.dot(AxisY())) < half.y();
  }
  double DistanceTo(const Vec2& p) const {
    Vec2 d = p - centre;
    double dx = std::max(0.0, std::abs(d.dot(AxisX())) - half.x());
    double dy = std::max(0.0, std::abs(d.dot(AxisY())) - half.y());
    return std::hypot(dx, dy);
  }
};

// Separating-axis test, with a gap: true when the boxes come closer than gap.
bool Overlap(const Box2& a, const Box2& b, double gap) {
  for (const Vec2& axis : {a.AxisX(), a.AxisY(), b.AxisX(), b.AxisY()}) {
    auto project = [&](const Box2& box) {
      double c = box.centre.dot(axis);
      double r = box.half.x() * std::abs(box.AxisX().dot(axis)) + box.half.y() * std::abs(box.AxisY().dot(axis));
      return std::pair(c - r, c + r);
    };
    auto [a0, a1] = project(a);
    auto [b0, b1] = project(b);
    if (a1 + gap <= b0 || b1 + gap <= a0) return false;
  }
  return true;
}

Box2 FootprintOf(const Furniture& f) { return {f.centre_m, 0.5 * f.size_m.head<2>(), DegToRad(f.yaw_deg)}; }

bool InsideRoom(const Room& room, const Box2& box) {
  for (const Vec2& c : box.Corners()) {
    if (!PointInPolygon(room.polygon, c)) return false;
  }
  for (const Vec2& v : room.polygon) {
    if (box.Contains(v)) return false;
  }
  return true;
}

// Zones kept clear for a piece of this height: door swings, and windows
// whose sill is below the piece's top.
std::vector<Box2> KeepClearZones(const Room& room, double piece_height_m, double door_clearance_m) {
  std::vector<Box2> zones;
  for (const Opening& o : room.openings) {
    if (o.wall < 0 || o.wall >= WallCount(room)) continue;
    bool door = o.kind == OpeningKind::kDoor || o.sill_m < 0.3;
    if (!door && o.sill_m > piece_height_m + 0.02) continue;
    double depth = door ? door_clearance_m : 0.4;
    Vec2 s = WallStart(room, o.wall);
    Vec2 d = (WallEnd(room, o.wall) - s).normalized();
    Vec2 inward(-d.y(), d.x());
    zones.push_back({s + d * (o.offset_m + 0.5 * o.width_m) + inward * (0.5 * depth),
                     Vec2(0.5 * o.width_m + 0.1, 0.5 * depth), std::atan2(d.y(), d.x())});
  }
  return zones;
}

std::vector<Vec2> RigPositions(const Scene& scene) {
  std::vector<Vec2> out;
  for (const Viewpoint& v : scene.viewpoints) out.push_back(v.position_m.head<2>());
  if (scene.turn) out.push_back(scene.turn->position_m.head<2>());
  return out;
}

// A free spot: inside the room, clear of keep-clear zones, rigs and other pieces.
bool SpotIsClear(const Scene& scene, const Room& room, const Box2& box, const std::vector<Box2>& zones,
                 const std::vector<Vec2>& rigs, const PlaceFurnitureOptions& options) {
  if (!InsideRoom(room, box)) return false;
  for (const Box2& z : zones) {
    if (Overlap(box, z, 0.0)) return false;
  }
  for (const Vec2& r : rigs) {
    if (box.DistanceTo(r) <= options.rig_clearance_m) return false;
  }
  for (const Furniture& f : scene.furniture) {
    if (Overlap(box, FootprintOf(f), options.piece_gap_m)) return false;
  }
  return true;
}

}  // namespace

std::uint64_t SceneRng::Next() {
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double SceneRng::Uniform(double lo, double hi) {
  return lo + (hi - lo) * (static_cast<double>(Next() >> 11) * 0x1.0p-53);
}

int SceneRng::UniformInt(int lo, int hi) {
  if (hi <= lo) return lo;
  return lo + static_cast<int>(Next() % static_cast<std::uint64_t>(hi - lo + 1));
}

bool SceneRng::Chance(double p) { return Uniform(0, 1) < p; }

std::optional<FurnitureSpec> FurnitureByName(const std::string& word) {
  const auto& m = TheCatalogue().by_word;
  auto it = m.find(word);
  if (it == m.end()) return std::nullopt;
  return it->second;
}

const std::vector<std::string>& FurnitureNames() { return TheCatalogue().names; }

void PlaceFurnitureOptions::Check() const {
  CheckArgument(wall_gap_m >= 0, fmt::format("PlaceFurnitureOptions.wall_gap_m = {}, must be >= 0", wall_gap_m));
  CheckArgument(door_clearance_m >= 0,
                fmt::format("PlaceFurnitureOptions.door_clearance_m = {}, must be >= 0", door_clearance_m));
  CheckArgument(rig_clearance_m >= 0,
                fmt::format("PlaceFurnitureOptions.rig_clearance_m = {}, must be >= 0", rig_clearance_m));
  CheckArgument(piece_gap_m >= 0, fmt::format("PlaceFurnitureOptions.piece_gap_m = {}, must be >= 0", piece_gap_m));
  CheckArgument(attempts_per_piece > 0,
                fmt::format("PlaceFurnitureOptions.attempts_per_piece = {}, must be > 0", attempts_per_piece));
}

std::vector<std::string> PlaceFurniture(Scene& scene, int room_index, const std::vector<FurnitureSpec>& pieces,
                                        std::uint64_t seed, const PlaceFurnitureOptions& options) {
  options.Check();
  CheckArgument(room_index >= 0 && room_index < static_cast<int>(scene.rooms.size()),
                fmt::format("PlaceFurniture: room {} out of range", room_index));
  const Room& room = scene.rooms[room_index];
  SceneRng rng(seed);
  std::vector<std::string> not_placed;
  const int n_walls = WallCount(room);
  double perimeter = 0;
  for (int w = 0; w < n_walls; ++w) perimeter += WallLength(room, w);
  Vec2 lo = room.polygon[0], hi = room.polygon[0];
  for (const Vec2& p : room.polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec2 d0 = (WallEnd(room, 0) - WallStart(room, 0)).normalized();
  const double base_angle = std::atan2(d0.y(), d0.x());
  const std::vector<Vec2> rigs = RigPositions(scene);

  for (const FurnitureSpec& piece : pieces) {
    const std::vector<Box2> zones = KeepClearZones(room, piece.size_m.z(), options.door_clearance_m);
    bool placed = false;
    for (int attempt = 0; attempt < options.attempts_per_piece && !placed; ++attempt) {
      Box2 box;
      box.half = 0.5 * piece.size_m.head<2>();
      if (piece.against_wall) {
        // Pick a wall in proportion to its length, then a spot along it.
        double pick = rng.Uniform(0, perimeter);
        int w = 0;
        while (w + 1 < n_walls && pick > WallLength(room, w)) pick -= WallLength(room, w++);
        double length = WallLength(room, w);
        if (length < piece.size_m.x() + 0.1) continue;
        double t = rng.Uniform(0.05 + box.half.x(), length - 0.05 - box.half.x());
        Vec2 s = WallStart(room, w);
        Vec2 d = (WallEnd(room, w) - s).normalized();
        Vec2 inward(-d.y(), d.x());
        box.centre = s + d * t + inward * (box.half.y() + options.wall_gap_m);
        box.angle = std::atan2(d.y(), d.x());
      } else {
        box.centre = Vec2(rng.Uniform(lo.x(), hi.x()), rng.Uniform(lo.y(), hi.y()));
        box.angle = base_angle + 0.5 * kPi * rng.UniformInt(0, 3);
      }
      if (!SpotIsClear(scene, room, box, zones, rigs, options)) continue;
      double yaw_deg = RadToDeg(box.angle);
      yaw_deg = std::remainder(yaw_deg, 360.0);
      scene.furniture.push_back({.name = piece.name,
                                 .centre_m = box.centre,
                                 .yaw_deg = yaw_deg,
                                 .size_m = piece.size_m,
                                 .elevation_m = 0.0,
                                 .material = piece.material});
      placed = true;
    }
    if (!placed) not_placed.push_back(piece.name);
  }
  return not_placed;
}

int PlaceInRows(Scene& scene, int room_index, const FurnitureSpec& piece, int count, double aisle_m,
                const PlaceFurnitureOptions& options) {
  options.Check();
  CheckArgument(room_index >= 0 && room_index < static_cast<int>(scene.rooms.size()),
                fmt::format("PlaceInRows: room {} out of range", room_index));
  CheckArgument(aisle_m >= 0, fmt::format("PlaceInRows: aisle_m = {}, must be >= 0", aisle_m));
  const Room& room = scene.rooms[room_index];
  // Grid in wall 0's frame: u along wall 0, v into the room.
  const Vec2 origin = WallStart(room, 0);
  const Vec2 u = (WallEnd(room, 0) - origin).normalized();
  const Vec2 v(-u.y(), u.x());
  double u_lo = 1e18, u_hi = -1e18, v_lo = 1e18, v_hi = -1e18;
  for (const Vec2& p : room.polygon) {
    u_lo = std::min(u_lo, (p - origin).dot(u));
    u_hi = std::max(u_hi, (p - origin).dot(u));
    v_lo = std::min(v_lo, (p - origin).dot(v));
    v_hi = std::max(v_hi, (p - origin).dot(v));
  }
  const std::vector<Box2> zones = KeepClearZones(room, piece.size_m.z(), options.door_clearance_m);
  const std::vector<Vec2> rigs = RigPositions(scene);
  // Try the grid at a few offsets (the rig may sit in a row or an aisle)
  // and keep the one that seats the most.
  std::vector<Box2> best;
  for (double shift_u : {0.0, 0.5}) {
    for (double shift_v : {0.0, 0.5}) {
      const double pitch_u = piece.size_m.x() + aisle_m, pitch_v = piece.size_m.y() + aisle_m + 0.3;
      const int cols = std::max(0, static_cast<int>((u_hi - u_lo - 1.0) / pitch_u));
      const int rows = std::max(0, static_cast<int>((v_hi - v_lo - 1.0) / pitch_v));
      const double u0 = 0.5 * (u_lo + u_hi) - 0.5 * (cols - 1) * pitch_u + shift_u * pitch_u;
      const double v0 = 0.5 * (v_lo + v_hi) - 0.5 * (rows - 1) * pitch_v + shift_v * pitch_v;
      std::vector<Box2> boxes;
      for (int r = -1; r <= rows && static_cast<int>(boxes.size()) < count; ++r) {
        for (int c = -1; c <= cols && static_cast<int>(boxes.size()) < count; ++c) {
          Box2 box{origin + u * (u0 + c * pitch_u) + v * (v0 + r * pitch_v), 0.5 * piece.size_m.head<2>(),
                   std::atan2(u.y(), u.x())};
          if (SpotIsClear(scene, room, box, zones, rigs, options)) boxes.push_back(box);
        }
      }
      if (boxes.size() > best.size()) best = boxes;
    }
  }
  int placed = 0;
  for (const Box2& box : best) {
    scene.furniture.push_back({.name = piece.name,
                               .centre_m = box.centre,
                               .yaw_deg = std::remainder(RadToDeg(box.angle), 360.0),
                               .size_m = piece.size_m,
                               .elevation_m = 0.0,
                               .material = piece.material});
    ++placed;
  }
  return count - placed;
}

void AddCeilingLights(Scene& scene, int room_index, int count, double intensity) {
  CheckArgument(room_index >= 0 && room_index < static_cast<int>(scene.rooms.size()),
                fmt::format("AddCeilingLights: room {} out of range", room_index));
  CheckArgument(count >= 0, fmt::format("AddCeilingLights: count = {}, must be >= 0", count));
  const Room& room = scene.rooms[room_index];
  double area = PolygonArea(room.polygon);
  if (count == 0) count = std::max(1, static_cast<int>(std::lround(area / 8.0)));
  Vec2 lo = room.polygon[0], hi = room.polygon[0];
  for (const Vec2& p : room.polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  Vec2 extent = hi - lo;
  int cols = std::max(1, static_cast<int>(std::lround(std::sqrt(count * extent.x() / extent.y()))));
  cols = std::min(cols, count);
  int rows = (count + cols - 1) / cols;
  Vec2 size(std::min(1.2, 0.4 * extent.x() / cols), std::min(0.3, 0.4 * extent.y() / rows));
  int added = 0;
  for (int r = 0; r < rows && added < count; ++r) {
    for (int c = 0; c < cols && added < count; ++c) {
      Vec2 p(lo.x() + (c + 0.5) * extent.x() / cols, lo.y() + (r + 0.5) * extent.y() / rows);
      if (!PointInPolygon(room.polygon, p)) continue;
      scene.lights.push_back({.kind = LightKind::kArea,
                              .position_m = Vec3(p.x(), p.y(), room.height_m - 0.02),
                              .size_m = size,
                              .intensity = intensity});
      ++added;
    }
  }
  if (added == 0) {
    Vec2 c = PolygonCentroid(room.polygon);
    scene.lights.push_back(
        {.kind = LightKind::kPoint, .position_m = Vec3(c.x(), c.y(), room.height_m - 0.3), .intensity = intensity});
  }
}

}  // namespace asbuilt
