#include "asbuilt/scene/procedural.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "asbuilt/scene/furnish.h"
#include "asbuilt/scene/scene_json.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

double DistanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  Vec2 ab = b - a;
  double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

Vec3 Jitter(SceneRng& rng, const Vec3& c, double amount) {
  Vec3 out;
  for (int i = 0; i < 3; ++i) out[i] = std::clamp(c[i] + rng.Uniform(-amount, amount), 0.0, 1.0);
  return out;
}

template <typename T>
const T& Pick(SceneRng& rng, const std::vector<T>& items) {
  return items[rng.UniformInt(0, static_cast<int>(items.size()) - 1)];
}

std::vector<Vec2> RandomPolygon(SceneRng& rng, const RandomSceneOptions& o, bool l_shape) {
  double w = rng.Uniform(o.min_side_m, o.max_side_m);
  double d = rng.Uniform(o.min_side_m, o.max_side_m);
  if (!l_shape || w < 3.0 || d < 3.0) return {{0, 0}, {w, 0}, {w, d}, {0, d}};
  // Cut a corner out, leaving at least 1.5 m on each arm.
  double cw = std::clamp(rng.Uniform(0.3, 0.6) * w, 1.0, w - 1.5);
  double cd = std::clamp(rng.Uniform(0.3, 0.6) * d, 1.0, d - 1.5);
  switch (rng.UniformInt(0, 3)) {
    case 0:
      return {{0, 0}, {w, 0}, {w, d - cd}, {w - cw, d - cd}, {w - cw, d}, {0, d}};
    case 1:
      return {{0, 0}, {w, 0}, {w, d}, {cw, d}, {cw, d - cd}, {0, d - cd}};
    case 2:
      return {{0, 0}, {w - cw, 0}, {w - cw, cd}, {w, cd}, {w, d}, {0, d}};
    default:
      return {{cw, 0}, {w, 0}, {w, d}, {0, d}, {0, cd}, {cw, cd}};
  }
}

// Tries to add one opening of `kind` to the room; false when nothing fits.
bool AddOpening(SceneRng& rng, const RandomSceneOptions& o, Room& room, OpeningKind kind,
                std::vector<int>& used_walls) {
  const int n = WallCount(room);
  for (int attempt = 0; attempt < 60; ++attempt) {
    int wall;
    if (!used_walls.empty() && rng.Chance(o.same_wall_probability)) {
      wall = Pick(rng, used_walls);
    } else {
      wall = rng.UniformInt(0, n - 1);
    }
    const double length = WallLength(room, wall);
    Opening op;
    op.kind = kind;
    op.wall = wall;
    if (kind == OpeningKind::kDoor) {
      op.width_m = rng.Uniform(0.7, 1.2);
      op.height_m = std::min(rng.Uniform(1.95, 2.3), room.height_m - 0.1);
      op.sill_m = 0.0;
      op.open_deg = rng.Chance(0.6) ? 0.0 : rng.Uniform(10.0, 100.0);
      op.hinge = rng.Chance(0.5) ? HingeSide::kLeft : HingeSide::kRight;
    } else {
      op.width_m = rng.Uniform(0.6, 2.0);
      op.sill_m = rng.Uniform(0.5, 1.2);
      op.height_m = std::min(rng.Uniform(0.8, 1.6), room.height_m - 0.15 - op.sill_m);
      op.glass = rng.Chance(0.9);
      op.frame_width_m = rng.Uniform(0.03, 0.08);
    }
    if (op.height_m < 0.4 || op.width_m > length - 0.2) continue;
    if (kind == OpeningKind::kDoor && rng.Chance(o.corner_door_probability)) {
      double gap = rng.Uniform(0.05, 0.15);
      op.offset_m = rng.Chance(0.5) ? gap : length - op.width_m - gap;
    } else {
      op.offset_m = rng.Uniform(0.1, length - op.width_m - 0.1);
    }
    bool clear = true;
    for (const Opening& other : room.openings) {
      if (other.wall == wall && op.offset_m < other.offset_m + other.width_m + 0.1 &&
          op.offset_m + op.width_m + 0.1 > other.offset_m) {
        clear = false;
      }
    }
    if (!clear) continue;
    room.openings.push_back(op);
    if (std::find(used_walls.begin(), used_walls.end(), wall) == used_walls.end()) used_walls.push_back(wall);
    return true;
  }
  return false;
}

void RandomMaterials(SceneRng& rng, Scene& scene) {
  const std::vector<Vec3> wall_colours = {Vec3(0.9, 0.9, 0.88),  Vec3(0.86, 0.82, 0.72), Vec3(0.75, 0.8, 0.85),
                                          Vec3(0.7, 0.78, 0.68), Vec3(0.92, 0.85, 0.7),  Vec3(0.6, 0.6, 0.62),
                                          Vec3(0.85, 0.7, 0.65)};
  const std::vector<TextureKind> wall_textures = {TextureKind::kPlaster, TextureKind::kPaint, TextureKind::kWallpaper,
                                                  TextureKind::kConcrete, TextureKind::kNone};
  const std::vector<std::pair<TextureKind, Vec3>> floors = {{TextureKind::kWood, Vec3(0.5, 0.35, 0.2)},
                                                            {TextureKind::kWood, Vec3(0.7, 0.55, 0.35)},
                                                            {TextureKind::kTiles, Vec3(0.75, 0.75, 0.72)},
                                                            {TextureKind::kCarpet, Vec3(0.35, 0.38, 0.45)},
                                                            {TextureKind::kConcrete, Vec3(0.55, 0.55, 0.55)}};
  Material wall = *FindMaterial(scene, "wall");
  wall.base_color = Jitter(rng, Pick(rng, wall_colours), 0.05);
  wall.secondary_color = Jitter(rng, 0.9 * wall.base_color, 0.03);
  wall.texture = Pick(rng, wall_textures);
  wall.texture_scale_m = rng.Uniform(0.1, 0.6);
  wall.roughness = rng.Uniform(0.6, 1.0);
  Material floor = *FindMaterial(scene, "floor");
  const auto& [floor_texture, floor_colour] = Pick(rng, floors);
  floor.texture = floor_texture;
  floor.base_color = Jitter(rng, floor_colour, 0.06);
  floor.secondary_color = Jitter(rng, 0.75 * floor.base_color, 0.03);
  floor.texture_scale_m = rng.Uniform(0.1, 0.6);
  floor.roughness = rng.Uniform(0.3, 0.9);
  Material ceiling = *FindMaterial(scene, "ceiling");
  ceiling.base_color = Jitter(rng, Vec3(0.92, 0.92, 0.9), 0.04);
  Material furniture = *FindMaterial(scene, "furniture");
  furniture.base_color = Jitter(rng,
                                Pick(rng, std::vector<Vec3>{Vec3(0.6, 0.5, 0.4), Vec3(0.3, 0.3, 0.32),
                                                            Vec3(0.85, 0.85, 0.82), Vec3(0.45, 0.3, 0.2)}),
                                0.05);
  furniture.texture = rng.Chance(0.5) ? TextureKind::kWood : TextureKind::kNone;
  scene.materials = {wall, floor, ceiling, furniture};
}

// A point inside the polygon at least `margin_m` from every wall.
std::optional<Vec2> InteriorPoint(SceneRng& rng, const std::vector<Vec2>& polygon, double margin_m) {
  Vec2 lo = polygon[0], hi = polygon[0];
  for (const Vec2& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  for (int attempt = 0; attempt < 500; ++attempt) {
    Vec2 p(rng.Uniform(lo.x(), hi.x()), rng.Uniform(lo.y(), hi.y()));
    if (!PointInPolygon(polygon, p)) continue;
    bool far = true;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      far = far && DistanceToSegment(p, polygon[i], polygon[(i + 1) % polygon.size()]) >= margin_m;
    }
    if (far) return p;
  }
  return std::nullopt;
}

bool IsRotated(const Room& room) {
  Vec2 d = WallEnd(room, 0) - WallStart(room, 0);
  return std::abs(d.x()) > 1e-9 && std::abs(d.y()) > 1e-9;
}

// --- Realism levers (RandomSceneOptions, issue 21) ---------------------------

// A box against wall `wall` of the room: `s` along the wall to its centre,
// `gap_m` between its back and the wall's inner face (negative: inside the
// wall), size width (along), depth, height, bottom at `elevation_m`.
Furniture WallBox(const Room& room, int wall, double s, double gap_m, const Vec3& size, double elevation_m,
                  const std::string& name, const std::string& material) {
  Vec2 a = WallStart(room, wall);
  Vec2 d = (WallEnd(room, wall) - a).normalized();
  Vec2 inward(-d.y(), d.x());
  return {.name = name,
          .centre_m = a + s * d + (gap_m + 0.5 * size.y()) * inward,
          .yaw_deg = RadToDeg(std::atan2(d.y(), d.x())),
          .size_m = size,
          .elevation_m = elevation_m,
          .material = material};
}

// True when [s0, s1] on `wall` keeps `margin_m` from every opening's casing.
bool ClearOfOpenings(const Room& room, int wall, double s0, double s1, double margin_m) {
  for (const Opening& o : room.openings) {
    if (o.wall == wall && s0 < o.offset_m + o.width_m + 0.1 + margin_m && s1 > o.offset_m - 0.1 - margin_m) {
      return false;
    }
  }
  return true;
}

void AddMaterialOnce(Scene& scene, const Material& m) {
  for (const Material& existing : scene.materials) {
    if (existing.name == m.name) return;
  }
  scene.materials.push_back(m);
}

void StyleDoors(SceneRng& rng, const RandomSceneOptions& o, Scene& scene) {
  const std::vector<Vec3> woods = {Vec3(0.55, 0.3, 0.13), Vec3(0.62, 0.4, 0.2), Vec3(0.42, 0.24, 0.12),
                                   Vec3(0.3, 0.17, 0.09), Vec3(0.7, 0.5, 0.3)};
  Material white{.name = "door_white",
                 .base_color = Jitter(rng, Vec3(0.88, 0.87, 0.84), 0.03),
                 .roughness = 0.35,
                 .texture = TextureKind::kPaint,
                 .texture_scale_m = 0.3};
  white.secondary_color = 0.95 * white.base_color;
  Material wood{.name = "door_wood",
                .base_color = Jitter(rng, Pick(rng, woods), 0.04),
                .roughness = rng.Uniform(0.35, 0.7),
                .texture = TextureKind::kWood,
                .texture_scale_m = rng.Uniform(0.6, 1.0)};
  wood.secondary_color = 0.75 * wood.base_color;
  bool used_white = false, used_wood = false;
  for (Opening& op : scene.rooms[0].openings) {
    if (op.kind != OpeningKind::kDoor) continue;
    if (rng.Chance(o.styled_door_probability)) {
      bool is_wood = rng.Chance(0.55);
      op.material = is_wood ? "door_wood" : "door_white";
      (is_wood ? used_wood : used_white) = true;
    }
    if (op.open_deg == 0.0 && rng.Chance(o.open_door_probability)) op.open_deg = rng.Uniform(60.0, 110.0);
  }
  if (used_white) AddMaterialOnce(scene, white);
  if (used_wood) AddMaterialOnce(scene, wood);
}

void PaintWallsNeutral(SceneRng& rng, Scene& scene) {
  // Warm white, cool white, off-white, greige: the walls of most homes.
  const std::vector<Vec3> whites = {Vec3(0.9, 0.89, 0.86), Vec3(0.86, 0.87, 0.88), Vec3(0.88, 0.85, 0.79),
                                    Vec3(0.8, 0.78, 0.74)};
  for (Material& m : scene.materials) {
    if (m.name == "wall") {
      m.base_color = Jitter(rng, Pick(rng, whites), 0.02);
      m.secondary_color = 0.95 * m.base_color;
      if (m.texture == TextureKind::kWallpaper || m.texture == TextureKind::kConcrete) m.texture = TextureKind::kPaint;
    } else if (m.name == "ceiling") {
      m.base_color = Jitter(rng, Vec3(0.92, 0.92, 0.9), 0.015);
    }
  }
}

void AddWindowSun(SceneRng& rng, Scene& scene) {
  const Room& room = scene.rooms[0];
  std::vector<const Opening*> windows;
  for (const Opening& op : room.openings) {
    if (op.kind == OpeningKind::kWindow && op.glass) windows.push_back(&op);
  }
  if (windows.empty()) return;
  const Opening* w = Pick(rng, windows);
  Vec2 out = WallOutwardNormal(room, w->wall);
  Light sun{.kind = LightKind::kSun,
            .color = Jitter(rng, Vec3(1.0, 0.93, 0.82), 0.04),
            .intensity = rng.Uniform(2.0, 4.5),
            .azimuth_deg = RadToDeg(std::atan2(out.y(), out.x())) + rng.Uniform(-50.0, 50.0),
            .elevation_deg = rng.Uniform(12.0, 45.0)};
  std::erase_if(scene.lights, [](const Light& l) { return l.kind == LightKind::kSun; });
  scene.lights.push_back(sun);
}

void AddKitchen(SceneRng& rng, Scene& scene) {
  const Room& room = scene.rooms[0];
  const bool white_units = rng.Chance(0.45);
  const std::vector<Vec3> woods = {Vec3(0.6, 0.36, 0.16), Vec3(0.5, 0.3, 0.15), Vec3(0.7, 0.52, 0.32)};
  Material cabinet{
      .name = "cabinet",
      .base_color = white_units ? Jitter(rng, Vec3(0.86, 0.86, 0.83), 0.03) : Jitter(rng, Pick(rng, woods), 0.04),
      .roughness = rng.Uniform(0.3, 0.6),
      .texture = TextureKind::kTiles,  // Tiles of door size: the gaps between fronts.
      .texture_scale_m = rng.Uniform(0.4, 0.6)};
  cabinet.secondary_color = 0.45 * cabinet.base_color;
  Material worktop{
      .name = "worktop",
      .base_color = Jitter(
          rng, Pick(rng, std::vector<Vec3>{Vec3(0.8, 0.78, 0.72), Vec3(0.2, 0.2, 0.2), Vec3(0.55, 0.5, 0.45)}), 0.04),
      .roughness = 0.3,
      .texture = TextureKind::kConcrete,
      .texture_scale_m = 0.3};
  worktop.secondary_color = 0.8 * worktop.base_color;
  Material appliance{.name = "appliance", .base_color = Jitter(rng, Vec3(0.9, 0.9, 0.88), 0.02), .roughness = 0.2};
  AddMaterialOnce(scene, cabinet);
  AddMaterialOnce(scene, worktop);
  AddMaterialOnce(scene, appliance);

  const std::size_t first = scene.furniture.size();
  const double fridge_width = rng.Uniform(0.6, 0.9);
  const double fridge_height = rng.Uniform(1.65, 1.85);
  std::vector<FurnitureSpec> pieces = {{"kitchen units", Vec3(rng.Uniform(1.2, 3.2), 0.6, 0.88), true, "cabinet"},
                                       {"fridge", Vec3(fridge_width, 0.7, fridge_height), true, "appliance"},
                                       {"range", Vec3(0.76, 0.65, 0.92), true, "appliance"}};
  if (rng.Chance(0.5)) pieces.push_back({"dishwasher", Vec3(0.6, 0.6, 0.85), true, "appliance"});
  if (rng.Chance(0.5)) pieces.push_back({"kitchen units", Vec3(rng.Uniform(0.8, 2.0), 0.6, 0.88), true, "cabinet"});
  PlaceFurnitureOptions placing;
  placing.piece_gap_m = 0.0;
  PlaceFurniture(scene, 0, pieces, rng.Next(), placing);
  // Worktops on the units, wall units above them (clear of windows).
  const std::size_t placed = scene.furniture.size();
  for (std::size_t i = first; i < placed; ++i) {
    const Furniture base = scene.furniture[i];
    if (base.name != "kitchen units") continue;
    const double yaw = DegToRad(base.yaw_deg);
    const Vec2 ex(std::cos(yaw), std::sin(yaw)), ey(-std::sin(yaw), std::cos(yaw));
    scene.furniture.push_back({.name = "worktop",
                               .centre_m = base.centre_m - 0.015 * ey,
                               .yaw_deg = base.yaw_deg,
                               .size_m = Vec3(base.size_m.x() + 0.02, 0.63, 0.04),
                               .elevation_m = base.size_m.z(),
                               .material = "worktop"});
    const double bottom = rng.Uniform(1.4, 1.55);
    const double height = std::min(rng.Uniform(0.6, 0.8), room.height_m - bottom - 0.05);
    bool clear = height > 0.3 && rng.Chance(0.75);
    for (const Opening& op : room.openings) {
      Vec2 a = WallStart(room, op.wall), d = (WallEnd(room, op.wall) - a).normalized();
      Vec2 c = a + (op.offset_m + 0.5 * op.width_m) * d;
      Vec2 r = c - base.centre_m;
      if (std::abs(r.dot(ey)) < 0.8 && std::abs(r.dot(ex)) < 0.5 * (base.size_m.x() + op.width_m) + 0.15 &&
          op.sill_m + op.height_m > bottom) {
        clear = false;
      }
    }
    if (clear) {
      scene.furniture.push_back({.name = "wall units",
                                 .centre_m = base.centre_m - (0.3 - 0.18) * ey,
                                 .yaw_deg = base.yaw_deg,
                                 .size_m = Vec3(base.size_m.x(), 0.34, height),
                                 .elevation_m = bottom,
                                 .material = "cabinet"});
    }
  }
}

void AddWallDetails(SceneRng& rng, Scene& scene) {
  const Room& room = scene.rooms[0];
  Material fitting{.name = "fitting", .base_color = Jitter(rng, Vec3(0.88, 0.88, 0.85), 0.03), .roughness = 0.4};
  AddMaterialOnce(scene, fitting);
  // Radiators under windows.
  for (const Opening& op : room.openings) {
    if (op.kind != OpeningKind::kWindow || op.sill_m < 0.65 || !rng.Chance(0.6)) continue;
    double width = std::clamp(op.width_m * rng.Uniform(0.6, 1.0), 0.4, 1.8);
    double height = std::min(rng.Uniform(0.4, 0.65), op.sill_m - 0.25);
    scene.furniture.push_back(WallBox(room, op.wall, op.offset_m + 0.5 * op.width_m, 0.04, Vec3(width, 0.09, height),
                                      0.12, "radiator", "fitting"));
  }
  // Sockets near the floor (or above a worktop's height), switches by doors.
  const int walls = WallCount(room);
  const int sockets = rng.UniformInt(2, 6);
  for (int k = 0; k < sockets; ++k) {
    int wall = rng.UniformInt(0, walls - 1);
    double len = WallLength(room, wall);
    if (len < 0.8) continue;
    double s = rng.Uniform(0.3, len - 0.3);
    if (!ClearOfOpenings(room, wall, s - 0.05, s + 0.05, 0.1)) continue;
    double z = rng.Chance(0.8) ? rng.Uniform(0.2, 0.4) : rng.Uniform(1.0, 1.15);
    Vec3 size = rng.Chance(0.5) ? Vec3(0.08, 0.012, 0.08) : Vec3(0.15, 0.012, 0.08);
    scene.furniture.push_back(WallBox(room, wall, s, 0.0, size, z, "socket", "fitting"));
  }
  for (const Opening& op : room.openings) {
    if (op.kind != OpeningKind::kDoor || !rng.Chance(0.8)) continue;
    double len = WallLength(room, op.wall);
    bool before = rng.Chance(0.5);
    double s =
        before ? op.offset_m - 0.1 - rng.Uniform(0.1, 0.25) : op.offset_m + op.width_m + 0.1 + rng.Uniform(0.1, 0.25);
    if (s < 0.08 || s > len - 0.08 || !ClearOfOpenings(room, op.wall, s - 0.04, s + 0.04, -0.09)) continue;
    scene.furniture.push_back(
        WallBox(room, op.wall, s, 0.0, Vec3(0.08, 0.012, 0.12), rng.Uniform(1.0, 1.2), "switch", "fitting"));
  }
}

void DressWindows(SceneRng& rng, const RandomSceneOptions& o, Scene& scene) {
  const Room& room = scene.rooms[0];
  const std::vector<Vec3> fabrics = {Vec3(0.85, 0.82, 0.75), Vec3(0.6, 0.55, 0.45), Vec3(0.4, 0.45, 0.55),
                                     Vec3(0.7, 0.6, 0.5),    Vec3(0.3, 0.3, 0.3),   Vec3(0.75, 0.7, 0.72)};
  Material curtain{.name = "curtain",
                   .base_color = Jitter(rng, Pick(rng, fabrics), 0.05),
                   .roughness = 1.0,
                   .texture = TextureKind::kCarpet,
                   .texture_scale_m = 0.15};
  curtain.secondary_color = 0.7 * curtain.base_color;
  Material blind{.name = "blind",
                 .base_color = Jitter(rng, Vec3(0.85, 0.84, 0.8), 0.05),
                 .roughness = 0.8,
                 .texture = TextureKind::kPaint,
                 .texture_scale_m = 0.2};
  bool used_curtain = false, used_blind = false;
  for (const Opening& op : room.openings) {
    if (op.kind != OpeningKind::kWindow || !rng.Chance(o.window_dressing_probability)) continue;
    const double top = op.sill_m + op.height_m;
    if (rng.Chance(0.55)) {
      // Two curtains drawn aside, hanging from above the opening in front of the wall.
      const double hang_top = std::min(room.height_m - 0.02, top + rng.Uniform(0.1, 0.3));
      const double bottom = rng.Chance(0.5) ? 0.02 : std::max(0.02, op.sill_m - rng.Uniform(0.1, 0.3));
      for (int side = 0; side < 2; ++side) {
        double width = rng.Uniform(0.25, 0.55);
        double cover = rng.Uniform(0.0, 0.45) * width;  // How far it reaches over the opening.
        double s = side == 0 ? op.offset_m - 0.5 * width + cover : op.offset_m + op.width_m + 0.5 * width - cover;
        scene.furniture.push_back(WallBox(room, op.wall, s, rng.Uniform(0.06, 0.12),
                                          Vec3(width, 0.06, hang_top - bottom), bottom, "curtain", "curtain"));
      }
      used_curtain = true;
    } else if (op.glass) {
      // A roller blind in the opening, between the inner face and the glass.
      double drop = op.height_m * rng.Uniform(0.1, 0.75);
      scene.furniture.push_back(WallBox(room, op.wall, op.offset_m + 0.5 * op.width_m, -0.045,
                                        Vec3(op.width_m - 0.01, 0.02, drop), top - drop, "blind", "blind"));
      used_blind = true;
    }
  }
  if (used_curtain) AddMaterialOnce(scene, curtain);
  if (used_blind) AddMaterialOnce(scene, blind);
}

// True when no furniture stands within `depth_m` in front of [s0, s1] on `wall`.
bool ClearOfFurniture(const Scene& scene, const Room& room, int wall, double s0, double s1, double depth_m) {
  Vec2 a = WallStart(room, wall);
  Vec2 d = (WallEnd(room, wall) - a).normalized();
  Vec2 inward(-d.y(), d.x());
  for (const Furniture& f : scene.furniture) {
    Vec2 r = f.centre_m - a;
    double reach = 0.5 * std::max(f.size_m.x(), f.size_m.y());
    if (r.dot(inward) < depth_m + reach && r.dot(d) > s0 - reach && r.dot(d) < s1 + reach) return false;
  }
  return true;
}

void GlazeDoors(SceneRng& rng, const RandomSceneOptions& o, Scene& scene) {
  Room& room = scene.rooms[0];
  Material dark{.name = "door_frame_dark",
                .base_color = Jitter(rng, Vec3(0.12, 0.12, 0.13), 0.03),
                .roughness = 0.3,
                .texture = TextureKind::kPaint,
                .texture_scale_m = 0.3};
  dark.secondary_color = 0.9 * dark.base_color;
  bool used_dark = false;
  for (std::size_t k = 0; k < room.openings.size(); ++k) {
    Opening& op = room.openings[k];
    if (op.kind != OpeningKind::kDoor || !rng.Chance(o.glazed_door_probability)) continue;
    op.glazed = true;
    // Patio doors: wider and taller, where the wall and the room in front allow.
    const double width = rng.Uniform(1.4, 2.4), height = rng.Uniform(2.0, 2.3);
    const double len = WallLength(room, op.wall);
    const double centre = op.offset_m + 0.5 * op.width_m;
    const double s0 = std::clamp(centre - 0.5 * width, 0.1, std::max(0.1, len - width - 0.1));
    if (rng.Chance(0.6) && width > op.width_m && s0 + width <= len - 0.1) {
      Room without = room;
      without.openings.erase(without.openings.begin() + static_cast<std::ptrdiff_t>(k));
      if (ClearOfOpenings(without, op.wall, s0, s0 + width, 0.0) &&
          ClearOfFurniture(scene, room, op.wall, s0, s0 + width, 0.9)) {
        op.offset_m = s0;
        op.width_m = width;
        op.height_m = std::max(op.height_m, std::min(height, room.height_m - 0.1));
      }
    }
    if (rng.Chance(0.3)) {
      op.material = "door_frame_dark";  // Aluminium or uPVC patio frames.
      used_dark = true;
    }
  }
  if (used_dark) AddMaterialOnce(scene, dark);
}

void PaintCeilingLikeWalls(SceneRng& rng, Scene& scene) {
  Room& room = scene.rooms[0];
  for (Material& m : scene.materials) {
    if (m.name == room.wall_material && (m.texture == TextureKind::kWallpaper || m.texture == TextureKind::kConcrete)) {
      m.texture = TextureKind::kPaint;  // Paint that also suits a ceiling.
    }
  }
  room.ceiling_material = room.wall_material;
  // Soft light: more fill, so wall and ceiling differ by shading only.
  scene.environment.ambient = std::max(scene.environment.ambient, rng.Uniform(0.15, 0.3));
}

// Framed pictures, mirrors and a TV on plain stretches of wall, clear of openings.
void AddWallArt(SceneRng& rng, Scene& scene) {
  const Room& room = scene.rooms[0];
  const std::vector<Vec3> frames = {Vec3(0.08, 0.07, 0.06), Vec3(0.85, 0.84, 0.8), Vec3(0.55, 0.38, 0.2),
                                    Vec3(0.7, 0.6, 0.35)};
  Material frame{.name = "art_frame", .base_color = Jitter(rng, Pick(rng, frames), 0.03), .roughness = 0.4};
  Material picture{.name = "art_picture",
                   .base_color = Vec3(rng.Uniform(0.2, 0.9), rng.Uniform(0.2, 0.9), rng.Uniform(0.2, 0.9)),
                   .roughness = 0.5,
                   .texture = Pick(rng, std::vector<TextureKind>{TextureKind::kWallpaper, TextureKind::kConcrete,
                                                                 TextureKind::kTiles}),
                   .texture_scale_m = rng.Uniform(0.05, 0.3)};
  picture.secondary_color = Vec3(rng.Uniform(0.05, 0.9), rng.Uniform(0.05, 0.9), rng.Uniform(0.05, 0.9));
  Material mirror{.name = "mirror", .base_color = Vec3(0.9, 0.9, 0.9), .roughness = 0.02};
  Material screen{.name = "tv_screen", .base_color = Jitter(rng, Vec3(0.03, 0.03, 0.035), 0.01), .roughness = 0.1};
  const int items = rng.UniformInt(1, 4);
  bool used[4] = {false, false, false, false};
  for (int k = 0; k < items; ++k) {
    const int wall = rng.UniformInt(0, WallCount(room) - 1);
    const double len = WallLength(room, wall);
    const int kind = rng.Chance(0.5) ? 0 : (rng.Chance(0.5) ? 1 : 2);  // Picture, mirror, TV.
    double w, h, z;
    if (kind == 2) {
      w = rng.Uniform(0.8, 1.5);
      h = w * 9.0 / 16.0;
      z = rng.Uniform(0.9, 1.4);
    } else {
      w = rng.Uniform(0.3, 1.2);
      h = w * rng.Uniform(0.6, 1.5);
      z = std::max(0.9, rng.Uniform(1.3, 1.7) - 0.5 * h);
    }
    if (len < w + 0.4 || z + h > room.height_m - 0.15) continue;
    const double s = rng.Uniform(0.2 + 0.5 * w, len - 0.2 - 0.5 * w);
    if (!ClearOfOpenings(room, wall, s - 0.5 * w, s + 0.5 * w, 0.1)) continue;
    const double border = kind == 2 ? 0.015 : rng.Uniform(0.02, 0.06);
    const char* face = kind == 0 ? "art_picture" : (kind == 1 ? "mirror" : "tv_screen");
    const char* name = kind == 0 ? "picture" : (kind == 1 ? "mirror" : "tv");
    scene.furniture.push_back(WallBox(room, wall, s, 0.005, Vec3(w, kind == 2 ? 0.05 : 0.025, h), z,
                                      std::string(name) + " frame", kind == 2 ? "tv_screen" : "art_frame"));
    scene.furniture.push_back(WallBox(
        room, wall, s, 0.01, Vec3(w - 2 * border, kind == 2 ? 0.05 : 0.025, h - 2 * border), z + border, name, face));
    used[kind] = true;
    used[3] = used[3] || kind != 2;
  }
  if (used[3]) AddMaterialOnce(scene, frame);
  if (used[0]) AddMaterialOnce(scene, picture);
  if (used[1]) AddMaterialOnce(scene, mirror);
  if (used[2]) AddMaterialOnce(scene, screen);
}

// Brighter, shinier kitchens (after AddKitchen, own stream): more white
// units, light worktops, steel or white gloss appliances, a steel sink.
void BrightenKitchen(SceneRng& rng, Scene& scene) {
  for (Material& m : scene.materials) {
    if (m.name == "cabinet" && rng.Chance(0.4)) {
      m.base_color = Jitter(rng, Vec3(0.9, 0.9, 0.88), 0.02);
      m.secondary_color = 0.45 * m.base_color;
      m.roughness = rng.Uniform(0.15, 0.4);  // Gloss fronts.
    } else if (m.name == "worktop" && rng.Chance(0.5)) {
      m.base_color = Jitter(rng, Vec3(0.88, 0.87, 0.84), 0.03);
      m.secondary_color = 0.85 * m.base_color;
      m.roughness = 0.2;
    } else if (m.name == "appliance") {
      m.base_color =
          rng.Chance(0.45) ? Jitter(rng, Vec3(0.62, 0.63, 0.64), 0.03) : Jitter(rng, Vec3(0.93, 0.93, 0.92), 0.02);
      m.roughness = rng.Uniform(0.08, 0.2);
    }
  }
  Material steel{.name = "steel", .base_color = Jitter(rng, Vec3(0.65, 0.66, 0.67), 0.02), .roughness = 0.12};
  bool sink = false;
  for (std::size_t i = 0, n = scene.furniture.size(); i < n; ++i) {
    const Furniture top = scene.furniture[i];
    if (top.name != "worktop" || top.size_m.x() < 1.0 || !rng.Chance(0.8)) continue;
    const double yaw = DegToRad(top.yaw_deg);
    const Vec2 ex(std::cos(yaw), std::sin(yaw)), ey(-std::sin(yaw), std::cos(yaw));
    const double width = rng.Uniform(0.45, 0.8);
    const Vec2 c = top.centre_m + rng.Uniform(-0.5, 0.5) * (top.size_m.x() - width) * ex + 0.03 * ey;
    const double z = top.elevation_m + top.size_m.z();
    scene.furniture.push_back({.name = "sink",
                               .centre_m = c,
                               .yaw_deg = top.yaw_deg,
                               .size_m = Vec3(width, 0.42, 0.012),
                               .elevation_m = z,
                               .material = "steel"});
    scene.furniture.push_back({.name = "tap",
                               .centre_m = c - 0.24 * ey,
                               .yaw_deg = top.yaw_deg,
                               .size_m = Vec3(0.04, 0.04, rng.Uniform(0.2, 0.32)),
                               .elevation_m = z,
                               .material = "steel"});
    sink = true;
  }
  if (sink) AddMaterialOnce(scene, steel);
}

}  // namespace

const char* RigSpotName(RigSpot spot) { return spot == RigSpot::kSurvey ? "survey" : "random"; }

RigSpot ParseRigSpot(std::string_view name) {
  for (RigSpot s : {RigSpot::kRandom, RigSpot::kSurvey}) {
    if (name == RigSpotName(s)) return s;
  }
  throw InvalidArgument(fmt::format("rig spot \"{}\": expected random or survey", name));
}

void RandomSceneOptions::Check() const {
  CheckArgument(min_side_m >= 1.5, fmt::format("RandomSceneOptions.min_side_m = {}, must be >= 1.5", min_side_m));
  CheckArgument(max_side_m >= min_side_m,
                fmt::format("RandomSceneOptions.max_side_m = {}, must be >= min_side_m ({})", max_side_m, min_side_m));
  CheckArgument(min_height_m >= 2.2, fmt::format("RandomSceneOptions.min_height_m = {}, must be >= 2.2", min_height_m));
  CheckArgument(
      max_height_m >= min_height_m,
      fmt::format("RandomSceneOptions.max_height_m = {}, must be >= min_height_m ({})", max_height_m, min_height_m));
  CheckArgument(l_shape_probability >= 0 && l_shape_probability <= 1,
                fmt::format("RandomSceneOptions.l_shape_probability = {}, must be in [0, 1]", l_shape_probability));
  CheckArgument(rotated_probability >= 0 && rotated_probability <= 1,
                fmt::format("RandomSceneOptions.rotated_probability = {}, must be in [0, 1]", rotated_probability));
  CheckArgument(min_openings >= 1, fmt::format("RandomSceneOptions.min_openings = {}, must be >= 1", min_openings));
  CheckArgument(max_openings >= min_openings && max_openings <= 12,
                fmt::format("RandomSceneOptions.max_openings = {}, must be in [min_openings, 12]", max_openings));
  CheckArgument(same_wall_probability >= 0 && same_wall_probability <= 1,
                fmt::format("RandomSceneOptions.same_wall_probability = {}, must be in [0, 1]", same_wall_probability));
  CheckArgument(
      corner_door_probability >= 0 && corner_door_probability <= 1,
      fmt::format("RandomSceneOptions.corner_door_probability = {}, must be in [0, 1]", corner_door_probability));
  CheckArgument(min_furniture >= 0 && max_furniture >= min_furniture,
                fmt::format("RandomSceneOptions.min_furniture/max_furniture = {}/{}, need 0 <= min <= max",
                            min_furniture, max_furniture));
  for (auto [name, p] : {std::pair{"styled_door_probability", styled_door_probability},
                         {"open_door_probability", open_door_probability},
                         {"neutral_wall_probability", neutral_wall_probability},
                         {"window_sun_probability", window_sun_probability},
                         {"kitchen_probability", kitchen_probability},
                         {"wall_details_probability", wall_details_probability},
                         {"window_dressing_probability", window_dressing_probability},
                         {"glazed_door_probability", glazed_door_probability},
                         {"ceiling_like_walls_probability", ceiling_like_walls_probability},
                         {"wall_art_probability", wall_art_probability}}) {
    CheckArgument(p >= 0 && p <= 1, fmt::format("RandomSceneOptions.{} = {}, must be in [0, 1]", name, p));
  }
  CheckArgument(turn_step_deg > 0 && turn_step_deg <= 360,
                fmt::format("RandomSceneOptions.turn_step_deg = {}, must be in (0, 360]", turn_step_deg));
  rig.Camera().Check();
  CheckArgument(rig.baseline_m > 0, fmt::format("RandomSceneOptions.rig.baseline_m = {}, must be > 0", rig.baseline_m));
}

Scene RandomScene(const RandomSceneOptions& options, std::uint64_t seed) {
  options.Check();
  // Decorrelate neighbouring seeds.
  SceneRng rng(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull);
  Scene scene;
  scene.name = fmt::format("random-{}", seed);
  scene.seed = seed;
  scene.rig = options.rig;

  Room room;
  room.name = "room";
  room.polygon = RandomPolygon(rng, options, rng.Chance(options.l_shape_probability));
  if (rng.Chance(options.rotated_probability)) {
    Eigen::Rotation2Dd rot(DegToRad(rng.Uniform(5.0, 85.0) + 90.0 * rng.UniformInt(0, 3)));
    Vec2 shift(rng.Uniform(-3, 3), rng.Uniform(-3, 3));
    for (Vec2& p : room.polygon) p = rot * p + shift;
  }
  room.height_m = rng.Uniform(options.min_height_m, options.max_height_m);
  room.wall_thickness_m = rng.Uniform(0.1, 0.35);
  room.skirting = rng.Chance(0.7);

  // Openings: the first is a door.
  int n_openings = rng.UniformInt(options.min_openings, options.max_openings);
  std::vector<int> used_walls;
  for (int i = 0; i < n_openings; ++i) {
    OpeningKind kind = (i == 0 || rng.Chance(0.3)) ? OpeningKind::kDoor : OpeningKind::kWindow;
    AddOpening(rng, options, room, kind, used_walls);
  }
  scene.rooms.push_back(room);
  RandomMaterials(rng, scene);

  // Rig first, so furniture keeps clear of it.
  std::optional<Vec2> spot = InteriorPoint(rng, room.polygon, 0.8);
  if (!spot) spot = InteriorPoint(rng, room.polygon, 0.3);
  if (!spot) spot = PolygonCentroid(room.polygon);
  if (options.rig_spot == RigSpot::kSurvey) {
    // The random spot is drawn all the same, so the seed's furniture pieces,
    // lights and sky stay the same (placed clear of this spot instead).
    if (std::optional<Vec2> survey = SurveySpot(room.polygon)) spot = survey;
  }
  scene.turn =
      TurnInPlace{.position_m = Vec3(spot->x(), spot->y(), std::min(rng.Uniform(1.2, 1.7), room.height_m - 0.3)),
                  .start_deg = rng.Uniform(0.0, options.turn_step_deg),
                  .step_deg = options.turn_step_deg,
                  .count = 0};

  // Furniture from the whole catalogue, against walls mostly.
  static const std::vector<std::string> kPieces = {"desk",     "table",     "chair",   "bed",     "sofa",   "armchair",
                                                   "wardrobe", "bookshelf", "cabinet", "counter", "fridge", "dresser",
                                                   "plant",    "box",       "tv",      "piano"};
  std::vector<FurnitureSpec> pieces;
  int n_pieces = rng.UniformInt(options.min_furniture, options.max_furniture);
  for (int i = 0; i < n_pieces; ++i) {
    FurnitureSpec spec = *FurnitureByName(Pick(rng, kPieces));
    spec.size_m =
        spec.size_m.cwiseProduct(Vec3(rng.Uniform(0.85, 1.15), rng.Uniform(0.85, 1.15), rng.Uniform(0.9, 1.1)));
    pieces.push_back(spec);
  }
  PlaceFurniture(scene, 0, pieces, rng.Next());

  // Lights and environment.
  AddCeilingLights(scene, 0, rng.Chance(0.7) ? 0 : rng.UniformInt(1, 3), rng.Uniform(0.7, 1.5));
  if (rng.Chance(0.25)) {
    std::optional<Vec2> lamp = InteriorPoint(rng, room.polygon, 0.3);
    if (lamp) {
      scene.lights.push_back({.kind = LightKind::kPoint,
                              .position_m = Vec3(lamp->x(), lamp->y(), rng.Uniform(1.0, room.height_m - 0.3)),
                              .color = Jitter(rng, Vec3(1.0, 0.85, 0.7), 0.05),
                              .intensity = rng.Uniform(0.3, 1.0)});
    }
  }
  if (rng.Chance(0.7)) {
    scene.lights.push_back({.kind = LightKind::kSun,
                            .intensity = rng.Uniform(0.5, 2.0),
                            .azimuth_deg = rng.Uniform(0.0, 360.0),
                            .elevation_deg = rng.Uniform(10.0, 70.0)});
  }
  scene.environment.sky_color = Jitter(rng, Vec3(0.55, 0.7, 0.95), 0.1);
  scene.environment.ground_color = Jitter(rng, Vec3(0.35, 0.4, 0.3), 0.08);
  scene.environment.exterior_objects = rng.Chance(0.7);
  scene.environment.ambient = rng.Uniform(0.05, 0.3);

  // Realism levers: each its own stream, so the room above stays as it was
  // and turning one lever on or off leaves the others' choices alone.
  auto stream = [seed](std::uint64_t lever) {
    return SceneRng(seed * 0xD1B54A32D192ED03ull + lever * 0x8CB92BA72F3D8DD7ull + 0x2545F4914F6CDD1Dull);
  };
  if (options.styled_door_probability > 0 || options.open_door_probability > 0) {
    SceneRng r = stream(1);
    StyleDoors(r, options, scene);
  }
  if (options.glazed_door_probability > 0) {
    SceneRng r = stream(7);
    GlazeDoors(r, options, scene);
  }
  if (SceneRng r = stream(6); options.neutral_wall_probability > 0 && r.Chance(options.neutral_wall_probability)) {
    PaintWallsNeutral(r, scene);
  }
  if (SceneRng r = stream(2); options.window_sun_probability > 0 && r.Chance(options.window_sun_probability)) {
    AddWindowSun(r, scene);
  }
  if (SceneRng r = stream(3); options.kitchen_probability > 0 && r.Chance(options.kitchen_probability)) {
    AddKitchen(r, scene);
    SceneRng bright = stream(8);
    BrightenKitchen(bright, scene);
  }
  if (SceneRng r = stream(4); options.wall_details_probability > 0 && r.Chance(options.wall_details_probability)) {
    AddWallDetails(r, scene);
  }
  if (options.window_dressing_probability > 0) {
    SceneRng r = stream(5);
    DressWindows(r, options, scene);
  }
  if (SceneRng r = stream(9);
      options.ceiling_like_walls_probability > 0 && r.Chance(options.ceiling_like_walls_probability)) {
    PaintCeilingLikeWalls(r, scene);
  }
  if (SceneRng r = stream(10); options.wall_art_probability > 0 && r.Chance(options.wall_art_probability)) {
    AddWallArt(r, scene);
  }

  std::vector<Problem> problems = ValidateScene(scene, scene.name);
  if (!problems.empty()) {
    // A generator bug, not bad input: say how to reproduce it.
    throw Error(fmt::format("RandomScene(seed {}) made an invalid scene: {}", seed, problems.front().ToString()));
  }
  return scene;
}

std::string RandomScenesSummary::BriefReport() const {
  return fmt::format("{} scene{} in {} ({} rectangular, {} L-shaped, {} rotated; {} doors, {} windows)", written,
                     written == 1 ? "" : "s", dir.string(), rectangular, l_shaped, rotated, doors, windows);
}

RandomScenesSummary WriteRandomScenes(const RandomSceneOptions& options, std::uint64_t seed, int count,
                                      const fs::path& dir, const ProgressCallback& progress) {
  options.Check();
  CheckArgument(count >= 1, fmt::format("count = {}, must be >= 1", count));
  RandomScenesSummary summary;
  summary.dir = dir;
  for (int i = 0; i < count; ++i) {
    Scene scene = RandomScene(options, seed + static_cast<std::uint64_t>(i));
    WriteScene(scene, dir / fmt::format("scene_{:04d}.json", i));
    const Room& room = scene.rooms[0];
    (room.polygon.size() == 4 ? summary.rectangular : summary.l_shaped)++;
    if (IsRotated(room)) summary.rotated++;
    for (const Opening& o : room.openings) (o.kind == OpeningKind::kDoor ? summary.doors : summary.windows)++;
    ++summary.written;
    ReportProgress(progress, {.stage = "scenes", .done = i + 1, .total = count});
  }
  return summary;
}

}  // namespace asbuilt
