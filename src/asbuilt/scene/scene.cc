#include "asbuilt/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

constexpr double kEps = 1e-9;    // Metres: length comparisons.
constexpr double kSameM = 1e-6;  // Metres: two points are the same.

// Closed segments [p1, p2] and [q1, q2] share at least one point.
bool SegmentsIntersect(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2) {
  auto orient = [](const Vec2& a, const Vec2& b, const Vec2& c) {
    double v = Cross(b - a, c - a);
    return std::abs(v) < 1e-12 ? 0 : (v > 0 ? 1 : -1);
  };
  auto on_segment = [](const Vec2& a, const Vec2& b, const Vec2& c) {  // c on [a, b], collinear.
    return std::min(a.x(), b.x()) - kEps <= c.x() && c.x() <= std::max(a.x(), b.x()) + kEps &&
           std::min(a.y(), b.y()) - kEps <= c.y() && c.y() <= std::max(a.y(), b.y()) + kEps;
  };
  int o1 = orient(p1, p2, q1), o2 = orient(p1, p2, q2);
  int o3 = orient(q1, q2, p1), o4 = orient(q1, q2, p2);
  if (o1 != o2 && o3 != o4) return true;
  if (o1 == 0 && on_segment(p1, p2, q1)) return true;
  if (o2 == 0 && on_segment(p1, p2, q2)) return true;
  if (o3 == 0 && on_segment(q1, q2, p1)) return true;
  if (o4 == 0 && on_segment(q1, q2, p2)) return true;
  return false;
}

bool InUnitRange(const Vec3& c) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(c[i]) || c[i] < 0 || c[i] > 1) return false;
  }
  return true;
}

std::string Vec3Text(const Vec3& v) { return fmt::format("[{}, {}, {}]", v.x(), v.y(), v.z()); }

// Collects problems with one file name.
class Problems {
 public:
  explicit Problems(std::string file) : file_(std::move(file)) {}
  void Add(std::string path, std::string message) { list_.push_back({file_, std::move(path), std::move(message)}); }
  // Adds "must be > 0, got v" unless v > 0.
  void Positive(const std::string& path, double v) {
    if (!(std::isfinite(v) && v > 0)) Add(path, fmt::format("must be > 0, got {}", v));
  }
  void NonNegative(const std::string& path, double v) {
    if (!(std::isfinite(v) && v >= 0)) Add(path, fmt::format("must be >= 0, got {}", v));
  }
  void Range(const std::string& path, double v, double lo, double hi) {
    if (!(std::isfinite(v) && v >= lo && v <= hi)) {
      Add(path, fmt::format("must be in [{}, {}], got {}", lo, hi, v));
    }
  }
  void Colour(const std::string& path, const Vec3& c) {
    if (!InUnitRange(c)) Add(path, fmt::format("each component must be in [0, 1], got {}", Vec3Text(c)));
  }
  void Finite(const std::string& path, const Vec3& v) {
    if (!v.allFinite()) Add(path, fmt::format("must be finite, got {}", Vec3Text(v)));
  }
  std::vector<Problem>& list() { return list_; }

 private:
  std::string file_;
  std::vector<Problem> list_;
};

void CheckMaterialName(const Scene& scene, Problems& p, const std::string& path, const std::string& name) {
  if (FindMaterial(scene, name) == nullptr) {
    p.Add(path, fmt::format("unknown material \"{}\" (define it in materials, or use a built-in: "
                            "wall, floor, ceiling, door, window_frame, glass, furniture, skirting)",
                            name));
  }
}

// Problems of a polygon's shape; returns true when it is a usable simple
// counter-clockwise polygon.
bool CheckPolygon(const std::vector<Vec2>& poly, Problems& p, const std::string& path) {
  const std::size_t n = poly.size();
  if (n < 3) {
    p.Add(path, fmt::format("needs at least 3 points, got {}", n));
    return false;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!poly[i].allFinite()) {
      p.Add(fmt::format("{}[{}]", path, i), "must be finite");
      return false;
    }
  }
  bool ok = true;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if ((poly[i] - poly[j]).norm() < kSameM) {
        if (i == 0 && j == n - 1) {
          p.Add(fmt::format("{}[{}]", path, j),
                "repeats the first point; polygons are closed implicitly, list each corner once");
        } else {
          p.Add(fmt::format("{}[{}]", path, j), fmt::format("repeats point {} (zero-length wall)", i));
        }
        ok = false;
      }
    }
  }
  if (!ok) return false;
  // Crossing edges: non-adjacent edges must not touch; adjacent ones must not fold back.
  for (std::size_t i = 0; i < n && ok; ++i) {
    const Vec2& a1 = poly[i];
    const Vec2& a2 = poly[(i + 1) % n];
    for (std::size_t j = i + 1; j < n; ++j) {
      const Vec2& b1 = poly[j];
      const Vec2& b2 = poly[(j + 1) % n];
      bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      if (adjacent) {
        // Shared vertex; they only cross if they are collinear and overlap.
        Vec2 shared = j == i + 1 ? a2 : a1;
        Vec2 da = (j == i + 1 ? a1 : a2) - shared;
        Vec2 db = (j == i + 1 ? b2 : b1) - shared;
        if (std::abs(Cross(da.normalized(), db.normalized())) < 1e-9 && da.dot(db) > 0) {
          p.Add(path, fmt::format("walls {} and {} fold back on each other", i, j));
          ok = false;
          break;
        }
      } else if (SegmentsIntersect(a1, a2, b1, b2)) {
        p.Add(path, fmt::format("self-intersecting: wall {} crosses wall {}", i, j));
        ok = false;
        break;
      }
    }
  }
  if (!ok) return false;
  double area = PolygonArea(poly);
  if (area <= 0) {
    p.Add(path, fmt::format("points are clockwise (signed area {:.3f} m²); list corners "
                            "counter-clockwise seen from above",
                            area));
    return false;
  }
  return true;
}

void CheckRoom(const Scene& scene, int r, Problems& p) {
  const Room& room = scene.rooms[r];
  const std::string rp = fmt::format("rooms[{}]", r);
  bool poly_ok = CheckPolygon(room.polygon, p, rp + ".polygon");
  p.Positive(rp + ".height_m", room.height_m);
  p.Positive(rp + ".wall_thickness_m", room.wall_thickness_m);
  CheckMaterialName(scene, p, rp + ".wall_material", room.wall_material);
  CheckMaterialName(scene, p, rp + ".floor_material", room.floor_material);
  CheckMaterialName(scene, p, rp + ".ceiling_material", room.ceiling_material);

  const int n_walls = static_cast<int>(room.polygon.size());
  for (std::size_t k = 0; k < room.openings.size(); ++k) {
    const Opening& o = room.openings[k];
    const std::string op = fmt::format("{}.openings[{}]", rp, k);
    std::size_t before = p.list().size();
    p.Positive(op + ".width_m", o.width_m);
    p.Positive(op + ".height_m", o.height_m);
    p.NonNegative(op + ".sill_m", o.sill_m);
    p.NonNegative(op + ".offset_m", o.offset_m);
    p.Range(op + ".open_deg", o.open_deg, 0, 180);
    p.NonNegative(op + ".frame_width_m", o.frame_width_m);
    if (!o.material.empty()) CheckMaterialName(scene, p, op + ".material", o.material);
    if (o.wall < 0 || o.wall >= n_walls) {
      p.Add(op + ".wall", fmt::format("wall index {} out of range (room has {} walls)", o.wall, n_walls));
      continue;
    }
    if (p.list().size() != before || !poly_ok) continue;
    double length = WallLength(room, o.wall);
    if (o.offset_m + o.width_m > length + kEps) {
      p.Add(op, fmt::format("outside its wall: offset {} + width {} = {} > wall {} length {:.3f}", o.offset_m,
                            o.width_m, o.offset_m + o.width_m, o.wall, length));
    }
    if (std::isfinite(room.height_m) && o.sill_m + o.height_m > room.height_m + kEps) {
      p.Add(op, fmt::format("above the wall: sill {} + height {} = {} > room height {}", o.sill_m, o.height_m,
                            o.sill_m + o.height_m, room.height_m));
    }
    for (std::size_t m = 0; m < k; ++m) {
      const Opening& q = room.openings[m];
      if (q.wall != o.wall) continue;
      double lo = std::max(o.offset_m, q.offset_m);
      double hi = std::min(o.offset_m + o.width_m, q.offset_m + q.width_m);
      if (hi - lo > kEps) {
        p.Add(op, fmt::format("overlaps openings[{}] on wall {} (by {:.3f} m)", m, o.wall, hi - lo));
      }
    }
  }
}

// Index of the first room whose polygon contains the point (and whose
// height is above its z), or -1.
int RoomContaining(const Scene& scene, const Vec3& point) {
  for (std::size_t r = 0; r < scene.rooms.size(); ++r) {
    const Room& room = scene.rooms[r];
    if (room.polygon.size() >= 3 && PointInPolygon(room.polygon, point.head<2>()) && point.z() > 0 &&
        point.z() < room.height_m) {
      return static_cast<int>(r);
    }
  }
  return -1;
}

void CheckViewPosition(const Scene& scene, Problems& p, const std::string& path, const Vec3& pos) {
  if (!pos.allFinite()) {
    p.Add(path, fmt::format("must be finite, got {}", Vec3Text(pos)));
    return;
  }
  if (RoomContaining(scene, pos) < 0) {
    p.Add(path, fmt::format("rig at {} is outside every room (or not between floor and ceiling)", Vec3Text(pos)));
  }
}

std::string Count(std::size_t n, const char* one, const char* many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

bool IsRectangle(const Room& room) {
  if (room.polygon.size() != 4) return false;
  for (int i = 0; i < 4; ++i) {
    Vec2 a = (WallEnd(room, i) - WallStart(room, i)).normalized();
    Vec2 b = (WallEnd(room, (i + 1) % 4) - WallStart(room, (i + 1) % 4)).normalized();
    if (std::abs(a.dot(b)) > 1e-6) return false;
  }
  return true;
}

}  // namespace

// ---------------------------------------------------------------- names

const char* TextureKindName(TextureKind kind) {
  switch (kind) {
    case TextureKind::kNone:
      return "none";
    case TextureKind::kPlaster:
      return "plaster";
    case TextureKind::kPaint:
      return "paint";
    case TextureKind::kWallpaper:
      return "wallpaper";
    case TextureKind::kWood:
      return "wood";
    case TextureKind::kTiles:
      return "tiles";
    case TextureKind::kCarpet:
      return "carpet";
    case TextureKind::kConcrete:
      return "concrete";
  }
  return "none";
}

const char* LightKindName(LightKind kind) {
  switch (kind) {
    case LightKind::kArea:
      return "area";
    case LightKind::kPoint:
      return "point";
    case LightKind::kSun:
      return "sun";
  }
  return "area";
}

const char* HingeSideName(HingeSide side) { return side == HingeSide::kLeft ? "left" : "right"; }

std::optional<TextureKind> TextureKindFromName(const std::string& name) {
  for (TextureKind k : {TextureKind::kNone, TextureKind::kPlaster, TextureKind::kPaint, TextureKind::kWallpaper,
                        TextureKind::kWood, TextureKind::kTiles, TextureKind::kCarpet, TextureKind::kConcrete}) {
    if (name == TextureKindName(k)) return k;
  }
  return std::nullopt;
}

std::optional<LightKind> LightKindFromName(const std::string& name) {
  for (LightKind k : {LightKind::kArea, LightKind::kPoint, LightKind::kSun}) {
    if (name == LightKindName(k)) return k;
  }
  return std::nullopt;
}

std::optional<HingeSide> HingeSideFromName(const std::string& name) {
  if (name == "left") return HingeSide::kLeft;
  if (name == "right") return HingeSide::kRight;
  return std::nullopt;
}

// ---------------------------------------------------------------- geometry

int WallCount(const Room& room) { return static_cast<int>(room.polygon.size()); }

Vec2 WallStart(const Room& room, int wall) { return room.polygon.at(wall); }

Vec2 WallEnd(const Room& room, int wall) { return room.polygon.at((wall + 1) % room.polygon.size()); }

double WallLength(const Room& room, int wall) { return (WallEnd(room, wall) - WallStart(room, wall)).norm(); }

Vec2 WallOutwardNormal(const Room& room, int wall) {
  Vec2 d = (WallEnd(room, wall) - WallStart(room, wall)).normalized();
  return Vec2(d.y(), -d.x());  // Interior is on the left of a counter-clockwise polygon.
}

std::string WallCompassName(const Room& room, int wall) {
  static const char* kNames[] = {"east", "north-east", "north", "north-west",
                                 "west", "south-west", "south", "south-east"};
  Vec2 n = WallOutwardNormal(room, wall);
  double deg = RadToDeg(std::atan2(n.y(), n.x()));  // From +X towards +Y.
  int sector = static_cast<int>(std::lround(deg / 45.0));
  sector = ((sector % 8) + 8) % 8;
  return kNames[sector];
}

const std::vector<std::string_view>& CompassNames() {
  static const std::vector<std::string_view> kNames = {"north", "north-east", "east", "south-east",
                                                       "south", "south-west", "west", "north-west"};
  return kNames;
}

std::optional<Vec2> CompassVector(std::string_view name) {
  const auto& names = CompassNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) return std::nullopt;
  Vec2 v = Vec2::Zero();
  if (name.find("north") != std::string_view::npos) v.y() += 1;
  if (name.find("south") != std::string_view::npos) v.y() -= 1;
  if (name.find("east") != std::string_view::npos) v.x() += 1;
  if (name.find("west") != std::string_view::npos) v.x() -= 1;
  return v.normalized();
}

std::vector<double> EvenlySpacedOffsets(double length_m, std::span<const double> widths_m) {
  std::vector<double> offsets;
  const std::size_t k = widths_m.size();
  for (std::size_t i = 0; i < k; ++i) offsets.push_back((i + 0.5) * length_m / k - 0.5 * widths_m[i]);
  return offsets;
}

std::vector<int> WallsFacing(const Room& room, std::string_view compass, double max_off_deg) {
  const std::optional<Vec2> dir = CompassVector(compass);
  if (!dir) return {};
  std::vector<int> named;
  for (int w = 0; w < WallCount(room); ++w) {
    if (WallLength(room, w) >= 1e-9 && WallCompassName(room, w) == compass) named.push_back(w);
  }
  if (!named.empty()) return named;
  int best = -1;
  double best_dot = -2, best_length = 0;
  for (int w = 0; w < WallCount(room); ++w) {
    const double length = WallLength(room, w);
    if (length < 1e-9) continue;
    const double dot = WallOutwardNormal(room, w).dot(*dir);
    if (dot > best_dot + 1e-9 || (std::abs(dot - best_dot) <= 1e-9 && length > best_length)) {
      best = w, best_dot = dot, best_length = length;
    }
  }
  if (best < 0 || best_dot < std::cos(DegToRad(max_off_deg)) - 1e-12) return {};
  return {best};
}

std::optional<int> WallFacing(const Room& room, std::string_view compass, double max_off_deg) {
  const std::vector<int> walls = WallsFacing(room, compass, max_off_deg);
  if (walls.empty()) return std::nullopt;
  int best = walls.front();
  for (int w : walls) {
    if (WallLength(room, w) > WallLength(room, best) + 1e-9) best = w;
  }
  return best;
}

Vec2 PolygonCentroid(const std::vector<Vec2>& polygon) {
  double area2 = 0.0;
  Vec2 c = Vec2::Zero();
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % n];
    double w = Cross(a, b);
    area2 += w;
    c += w * (a + b);
  }
  if (std::abs(area2) < 1e-12) {
    Vec2 mean = Vec2::Zero();
    for (const Vec2& p : polygon) mean += p;
    return n ? Vec2(mean / static_cast<double>(n)) : mean;
  }
  return c / (3.0 * area2);
}

// ---------------------------------------------------------------- materials

const std::vector<Material>& BuiltinMaterials() {
  static const std::vector<Material> kBuiltins = {
      {.name = "wall",
       .base_color = Vec3(0.85, 0.83, 0.78),
       .roughness = 0.9,
       .texture = TextureKind::kPlaster,
       .texture_scale_m = 0.3,
       .secondary_color = Vec3(0.78, 0.76, 0.72)},
      {.name = "floor",
       .base_color = Vec3(0.45, 0.32, 0.2),
       .roughness = 0.6,
       .texture = TextureKind::kWood,
       .texture_scale_m = 0.15,
       .secondary_color = Vec3(0.35, 0.24, 0.15)},
      {.name = "ceiling",
       .base_color = Vec3(0.92, 0.92, 0.9),
       .roughness = 0.95,
       .texture = TextureKind::kPaint,
       .texture_scale_m = 0.5,
       .secondary_color = Vec3(0.88, 0.88, 0.86)},
      {.name = "door",
       .base_color = Vec3(0.55, 0.38, 0.22),
       .roughness = 0.5,
       .texture = TextureKind::kWood,
       .texture_scale_m = 0.1,
       .secondary_color = Vec3(0.45, 0.3, 0.17)},
      {.name = "window_frame",
       .base_color = Vec3(0.95, 0.95, 0.95),
       .roughness = 0.4,
       .texture = TextureKind::kNone,
       .texture_scale_m = 0.5,
       .secondary_color = Vec3(0.9, 0.9, 0.9)},
      {.name = "glass",
       .base_color = Vec3(0.85, 0.92, 0.95),
       .roughness = 0.05,
       .texture = TextureKind::kNone,
       .texture_scale_m = 0.5,
       .secondary_color = Vec3(0.8, 0.9, 0.95)},
      {.name = "furniture",
       .base_color = Vec3(0.6, 0.5, 0.4),
       .roughness = 0.6,
       .texture = TextureKind::kWood,
       .texture_scale_m = 0.2,
       .secondary_color = Vec3(0.5, 0.4, 0.3)},
      {.name = "skirting",
       .base_color = Vec3(0.95, 0.95, 0.93),
       .roughness = 0.5,
       .texture = TextureKind::kNone,
       .texture_scale_m = 0.5,
       .secondary_color = Vec3(0.9, 0.9, 0.88)},
  };
  return kBuiltins;
}

const Material* FindMaterial(const Scene& scene, const std::string& name) {
  for (const Material& m : scene.materials) {
    if (m.name == name) return &m;
  }
  for (const Material& m : BuiltinMaterials()) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

// ---------------------------------------------------------------- rig and views

PinholeCamera StereoRigSpec::Camera() const {
  if (!fx) return PinholeCamera::FromHorizontalFov(width_px, height_px, hfov_deg);
  return {.width_px = width_px,
          .height_px = height_px,
          .fx = *fx,
          .fy = fy.value_or(*fx),
          .cx = cx.value_or(0.5 * width_px - 0.5),
          .cy = cy.value_or(0.5 * height_px - 0.5)};
}

std::vector<Viewpoint> ResolveViewpoints(const Scene& scene) {
  std::vector<Viewpoint> views = scene.viewpoints;
  if (scene.turn && scene.turn->step_deg > 0) {
    const TurnInPlace& t = *scene.turn;
    int count = t.count > 0 ? t.count : std::max(1, static_cast<int>(std::floor(360.0 / t.step_deg + 1e-9)));
    for (int i = 0; i < count; ++i) {
      views.push_back({.position_m = t.position_m, .yaw_deg = t.start_deg + i * t.step_deg, .pitch_deg = 0.0});
    }
  }
  return views;
}

// ---------------------------------------------------------------- validation

std::vector<Problem> ValidateScene(const Scene& scene, const std::string& file) {
  Problems p(file);
  if (scene.version != 1) p.Add("version", fmt::format("unsupported version {}, expected 1", scene.version));

  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    const std::string mp = fmt::format("materials[{}]", i);
    if (m.name.empty()) p.Add(mp + ".name", "must not be empty");
    auto [it, inserted] = seen.emplace(m.name, i);
    if (!inserted) p.Add(mp + ".name", fmt::format("duplicate name \"{}\" (also materials[{}])", m.name, it->second));
    p.Colour(mp + ".base_color", m.base_color);
    p.Colour(mp + ".secondary_color", m.secondary_color);
    p.Range(mp + ".roughness", m.roughness, 0, 1);
    p.Positive(mp + ".texture_scale_m", m.texture_scale_m);
  }

  if (scene.rooms.empty()) p.Add("rooms", "needs at least one room");
  for (std::size_t r = 0; r < scene.rooms.size(); ++r) CheckRoom(scene, static_cast<int>(r), p);

  for (std::size_t i = 0; i < scene.furniture.size(); ++i) {
    const Furniture& f = scene.furniture[i];
    const std::string fp = fmt::format("furniture[{}]", i);
    if (!f.centre_m.allFinite()) p.Add(fp + ".centre_m", "must be finite");
    if (!std::isfinite(f.yaw_deg)) p.Add(fp + ".yaw_deg", "must be finite");
    for (int k = 0; k < 3; ++k) {
      if (!(std::isfinite(f.size_m[k]) && f.size_m[k] > 0)) {
        p.Add(fmt::format("{}.size_m[{}]", fp, k), fmt::format("must be > 0, got {}", f.size_m[k]));
      }
    }
    p.NonNegative(fp + ".elevation_m", f.elevation_m);
    CheckMaterialName(scene, p, fp + ".material", f.material);
  }

  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    const std::string lp = fmt::format("lights[{}]", i);
    p.Finite(lp + ".position_m", l.position_m);
    p.Positive(lp + ".intensity", l.intensity);
    if (!(l.color.allFinite() && l.color.minCoeff() >= 0)) {
      p.Add(lp + ".color", fmt::format("components must be >= 0, got {}", Vec3Text(l.color)));
    }
    if (l.kind == LightKind::kArea) {
      if (!(std::isfinite(l.size_m.x()) && l.size_m.x() > 0))
        p.Add(lp + ".size_m[0]", fmt::format("must be > 0, got {}", l.size_m.x()));
      if (!(std::isfinite(l.size_m.y()) && l.size_m.y() > 0))
        p.Add(lp + ".size_m[1]", fmt::format("must be > 0, got {}", l.size_m.y()));
    }
    if (l.kind == LightKind::kSun) {
      p.Range(lp + ".elevation_deg", l.elevation_deg, 0, 90);
      if (!std::isfinite(l.azimuth_deg)) p.Add(lp + ".azimuth_deg", "must be finite");
    }
  }

  const Environment& e = scene.environment;
  p.Colour("environment.sky_color", e.sky_color);
  p.Colour("environment.ground_color", e.ground_color);
  p.Range("environment.ambient", e.ambient, 0, 1);

  const StereoRigSpec& rig = scene.rig;
  if (rig.width_px <= 0) p.Add("rig.width_px", fmt::format("must be > 0, got {}", rig.width_px));
  if (rig.height_px <= 0) p.Add("rig.height_px", fmt::format("must be > 0, got {}", rig.height_px));
  if (!(std::isfinite(rig.hfov_deg) && rig.hfov_deg > 0 && rig.hfov_deg < 180)) {
    p.Add("rig.hfov_deg", fmt::format("must be in (0, 180), got {}", rig.hfov_deg));
  }
  if (rig.fx) p.Positive("rig.fx", *rig.fx);
  if (rig.fy) {
    p.Positive("rig.fy", *rig.fy);
    if (!rig.fx) p.Add("rig.fy", "given without rig.fx");
  }
  if (rig.cx && !std::isfinite(*rig.cx)) p.Add("rig.cx", "must be finite");
  if (rig.cy && !std::isfinite(*rig.cy)) p.Add("rig.cy", "must be finite");
  p.Positive("rig.baseline_m", rig.baseline_m);

  for (std::size_t i = 0; i < scene.viewpoints.size(); ++i) {
    const Viewpoint& v = scene.viewpoints[i];
    const std::string vp = fmt::format("viewpoints[{}]", i);
    CheckViewPosition(scene, p, vp + ".position_m", v.position_m);
    if (!std::isfinite(v.yaw_deg)) p.Add(vp + ".yaw_deg", "must be finite");
    if (!(std::isfinite(v.pitch_deg) && v.pitch_deg > -90 && v.pitch_deg < 90)) {
      p.Add(vp + ".pitch_deg", fmt::format("must be in (-90, 90), got {}", v.pitch_deg));
    }
  }
  if (scene.turn) {
    const TurnInPlace& t = *scene.turn;
    CheckViewPosition(scene, p, "turn.position_m", t.position_m);
    if (!std::isfinite(t.start_deg)) p.Add("turn.start_deg", "must be finite");
    p.Range("turn.step_deg", t.step_deg, 1e-3, 360);
    if (t.count < 0) p.Add("turn.count", fmt::format("must be >= 0, got {}", t.count));
  }
  if (scene.viewpoints.empty() && !scene.turn) {
    // Not an error: a scene can be authored before its rig is placed.
  }
  return std::move(p.list());
}

void CheckScene(const Scene& scene, const std::string& file) {
  std::vector<Problem> problems = ValidateScene(scene, file);
  if (!problems.empty()) throw InputError(std::move(problems));
}

// ---------------------------------------------------------------- truth

Plan SceneTruth(const Scene& scene) {
  Plan plan;
  for (const Room& room : scene.rooms) {
    const int first_wall = static_cast<int>(plan.walls.size());
    const int n = WallCount(room);
    for (int w = 0; w < n; ++w) {
      plan.walls.push_back({.start = WallStart(room, w),
                            .end = WallEnd(room, w),
                            .thickness = room.wall_thickness_m,
                            .height = room.height_m});
    }
    for (const Opening& o : room.openings) {
      if (o.wall < 0 || o.wall >= n) continue;
      Vec2 dir = (WallEnd(room, o.wall) - WallStart(room, o.wall)).normalized();
      Vec2 start = WallStart(room, o.wall) + o.offset_m * dir;
      plan.openings.push_back({.kind = o.kind,
                               .wall = first_wall + o.wall,
                               .start = start,
                               .end = start + o.width_m * dir,
                               .width = o.width_m,
                               .height = o.height_m,
                               .sill = o.sill_m});
    }
    plan.rooms.push_back({.polygon = room.polygon, .area_m2 = PolygonArea(room.polygon)});
  }
  return plan;
}

// ---------------------------------------------------------------- printing

std::string DescribeScene(const Scene& scene) {
  std::string out = fmt::format("{}:", scene.name);
  for (std::size_t r = 0; r < scene.rooms.size(); ++r) {
    const Room& room = scene.rooms[r];
    if (r > 0) out += ";";
    std::string shape;
    if (room.polygon.size() < 3) {
      shape = "room with no valid floor polygon";
    } else if (IsRectangle(room)) {
      shape = fmt::format("{:.2f} × {:.2f} m room", WallLength(room, 0), WallLength(room, 1));
    } else {
      shape = fmt::format("{}-sided room", room.polygon.size());
    }
    out += fmt::format(" {}{} ({:.2f} m²), {:.2f} m high", room.name.empty() ? "" : room.name + ": ", shape,
                       room.polygon.size() >= 3 ? PolygonArea(room.polygon) : 0.0, room.height_m);
    std::size_t doors = 0, windows = 0;
    for (const Opening& o : room.openings) (o.kind == OpeningKind::kDoor ? doors : windows)++;
    out += fmt::format(", {}, {}", Count(doors, "door", "doors"), Count(windows, "window", "windows"));
    std::vector<std::string> details;
    for (const Opening& o : room.openings) {
      if (o.wall < 0 || o.wall >= WallCount(room)) continue;
      details.push_back(fmt::format("{} {:.2f} × {:.2f} m on the {} wall (wall {})", OpeningKindName(o.kind), o.width_m,
                                    o.height_m, WallCompassName(room, o.wall), o.wall));
    }
    if (!details.empty()) {
      out += " (";
      for (std::size_t i = 0; i < details.size(); ++i) out += (i ? ", " : "") + details[i];
      out += ")";
    }
  }
  std::vector<Viewpoint> views = ResolveViewpoints(scene);
  out += fmt::format("; {}, {}, {}", Count(scene.furniture.size(), "piece of furniture", "pieces of furniture"),
                     Count(scene.lights.size(), "light", "lights"), Count(views.size(), "view", "views"));
  try {
    PinholeCamera cam = scene.rig.Camera();
    out += fmt::format(" ({}×{} px, {:.0f}° HFOV, baseline {:.3f} m)", cam.width_px, cam.height_px,
                       cam.HorizontalFovDeg(), scene.rig.baseline_m);
  } catch (const InvalidArgument&) {
    out += " (invalid rig)";
  }
  out += ".";
  return out;
}

std::string Scene::ToString() const {
  std::size_t openings = 0;
  for (const Room& r : rooms) openings += r.openings.size();
  return fmt::format("Scene({}: {} rooms, {} openings, {} furniture, {} lights, {} views)", name, rooms.size(),
                     openings, furniture.size(), lights.size(), ResolveViewpoints(*this).size());
}

std::optional<Vec2> SurveySpot(const std::vector<Vec2>& polygon) {
  const std::size_t n = polygon.size();
  if (n < 3) return std::nullopt;
  Vec2 lo = polygon[0], hi = polygon[0];
  for (const Vec2& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // Signed distance to the nearest wall line, positive on the inner (left)
  // side of every wall: positive exactly inside the kernel. Outside it only
  // the sign matters, so the first wall that has p behind it ends the search
  // (this runs on a 200 × 200 grid for every text scene: it must be cheap).
  std::vector<Vec2> dirs(n);
  for (std::size_t i = 0; i < n; ++i) dirs[i] = (polygon[(i + 1) % n] - polygon[i]).normalized();
  auto clearance = [&](const Vec2& p) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n && nearest > 0; ++i) nearest = std::min(nearest, Cross(dirs[i], p - polygon[i]));
    return nearest;
  };
  const double step = std::max(hi.x() - lo.x(), hi.y() - lo.y()) / 200.0;
  if (!(step > 0)) return std::nullopt;
  std::vector<std::pair<Vec2, double>> grid;
  double best = 0;
  for (double y = lo.y() + 0.5 * step; y < hi.y(); y += step) {
    for (double x = lo.x() + 0.5 * step; x < hi.x(); x += step) {
      const Vec2 p(x, y);
      const double c = clearance(p);
      if (c <= 0) continue;
      grid.emplace_back(p, c);
      best = std::max(best, c);
    }
  }
  if (grid.empty()) return std::nullopt;
  // A convex room's centroid is as clear as any grid point (on the ridge of a
  // rectangle, at its middle): take it exactly. Else the clearest grid point,
  // on an equal-clearance ridge the one nearest the centroid.
  const Vec2 centroid = PolygonCentroid(polygon);
  if (clearance(centroid) >= best - 1e-9) return centroid;
  std::optional<Vec2> spot;
  for (const auto& [p, c] : grid) {
    if (c >= best - 1e-9 && (!spot || (p - centroid).squaredNorm() < (*spot - centroid).squaredNorm())) spot = p;
  }
  return spot;
}

}  // namespace asbuilt
