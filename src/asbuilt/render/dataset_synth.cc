#include "asbuilt/render/dataset_synth.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "asbuilt/formats/synth_dataset.h"
#include "asbuilt/geometry/polygon.h"
#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/scene/furnish.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/hash.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

constexpr double kMinWallClearanceM = 0.3;
constexpr double kCloseViewShare = 0.3;  // Of all views, with the close_views lever.
constexpr double kCloseDoorShare = 0.2;  // Of all views, with the close_doors lever.

double DistanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  Vec2 ab = b - a;
  double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// A camera spot inside the room, clear of walls and furniture.
bool FreeSpot(const Scene& scene, const Room& room, const Vec3& p) {
  Vec2 q = p.head<2>();
  if (!PointInPolygon(room.polygon, q)) return false;
  const int n = static_cast<int>(room.polygon.size());
  for (int i = 0; i < n; ++i) {
    if (DistanceToSegment(q, room.polygon[i], room.polygon[(i + 1) % n]) < kMinWallClearanceM) return false;
  }
  for (const Furniture& f : scene.furniture) {
    double y = DegToRad(f.yaw_deg);
    Vec2 ex(std::cos(y), std::sin(y)), ey(-std::sin(y), std::cos(y));
    Vec2 r = q - f.centre_m;
    if (std::abs(r.dot(ex)) < 0.5 * f.size_m.x() + 0.2 && std::abs(r.dot(ey)) < 0.5 * f.size_m.y() + 0.2) return false;
  }
  return p.z() > 0.3 && p.z() < room.height_m - 0.3;
}

Vec2 Centroid(const std::vector<Vec2>& poly) {
  Vec2 c = Vec2::Zero();
  for (const Vec2& p : poly) c += p;
  return c / std::max<std::size_t>(poly.size(), 1);
}

// True when the floor-plan segment p–q crosses no furniture footprint (grown by 0.1 m).
bool ClearSightline(const Scene& scene, const Vec2& p, const Vec2& q) {
  for (const Furniture& f : scene.furniture) {
    double y = DegToRad(f.yaw_deg);
    Vec2 ex(std::cos(y), std::sin(y)), ey(-std::sin(y), std::cos(y));
    for (int k = 0; k <= 20; ++k) {
      Vec2 r = p + (k / 20.0) * (q - p) - f.centre_m;
      if (std::abs(r.dot(ex)) < 0.5 * f.size_m.x() + 0.1 && std::abs(r.dot(ey)) < 0.5 * f.size_m.y() + 0.1) {
        return false;
      }
    }
  }
  return true;
}

// A close view (SynthLevers::close_views): 0.4–1.5 m in front of a plain
// stretch of wall (clear of openings by 0.5 m) or into a convex corner (no
// opening within 1 m of it), at
// eye or rig height (1.2–1.75 m), level or pitched up (5–45°) so that the
// wall–ceiling edge is in the upper part of the frame, with nothing in
// between. False when no spot is found.
bool PlanCloseView(SceneRng& rng, const Scene& scene, SynthItem& item) {
  const Room& room = scene.rooms.at(0);
  const int n = static_cast<int>(room.polygon.size());
  for (int attempt = 0; attempt < 40; ++attempt) {
    const int wall = rng.UniformInt(0, n - 1);
    const Vec2 a = room.polygon[wall], b = room.polygon[(wall + 1) % n];
    const double len = (b - a).norm();
    const Vec2 d = (b - a) / len;
    const Vec2 inward(-d.y(), d.x());
    const double dist = rng.Uniform(0.4, 1.5);
    Vec2 cam2, target2;
    if (rng.Chance(0.3)) {
      // Into the corner at the wall's start, along the bisector of a convex corner.
      const Vec2 prev = room.polygon[(wall + n - 1) % n];
      const Vec2 d_prev = (a - prev).normalized();
      if (d_prev.x() * d.y() - d_prev.y() * d.x() <= 0.1) continue;
      const int prev_wall = (wall + n - 1) % n;
      const double prev_len = (a - prev).norm();
      bool plain = true;
      for (const Opening& o : room.openings) {
        if ((o.wall == wall && o.offset_m < 1.0) || (o.wall == prev_wall && o.offset_m + o.width_m > prev_len - 1.0)) {
          plain = false;  // An opening within 1 m of the corner.
        }
      }
      if (!plain) continue;
      const Vec2 bisector = (d - d_prev).normalized();
      target2 = a;
      cam2 = a + (dist + 0.3) * bisector;
      item.target = "corner";
    } else {
      if (len < 1.2) continue;
      const double s = rng.Uniform(0.5, len - 0.5);
      bool plain = true;
      for (const Opening& o : room.openings) {
        if (o.wall == wall && s > o.offset_m - 0.5 - 0.5 * dist && s < o.offset_m + o.width_m + 0.5 + 0.5 * dist) {
          plain = false;
        }
      }
      if (!plain) continue;
      target2 = a + s * d;
      const double side = DegToRad(rng.Uniform(-25.0, 25.0));
      cam2 = target2 + dist * (std::cos(side) * inward + std::sin(side) * d);
      item.target = "close_wall";
    }
    const Vec3 cam(cam2.x(), cam2.y(), std::min(rng.Uniform(1.2, 1.75), room.height_m - 0.4));
    if (!FreeSpot(scene, room, cam) || !ClearSightline(scene, cam2, target2)) continue;
    const Vec2 v = target2 - cam2;
    item.kind = "photo";
    item.camera.viewpoint.position_m = cam;
    item.camera.viewpoint.yaw_deg = RadToDeg(std::atan2(-v.x(), v.y())) + rng.Uniform(-10.0, 10.0);
    if (rng.Chance(0.5)) {
      item.camera.viewpoint.pitch_deg = rng.Uniform(-5.0, 5.0);
    } else {
      // Up, so that the wall–ceiling edge is in the upper part of the frame.
      const PinholeCamera& k = item.camera.camera;
      const double half_vfov = RadToDeg(std::atan(0.5 * k.height_px / k.fy));
      const double edge = RadToDeg(std::atan2(room.height_m - cam.z(), v.norm()));
      item.camera.viewpoint.pitch_deg = std::clamp(edge - rng.Uniform(0.2, 0.8) * half_vfov, 5.0, 45.0);
    }
    return true;
  }
  return false;
}

// A close view of a door (SynthLevers::close_doors): 0.5–1.6 m in front of
// one of the room's doors, up to 40° off its normal, at eye or rig height,
// looking at a point of the opening: what real photos of hallways and closets
// show, an open leaf or the room beyond filling much of the frame. False when
// the room has no door or no clear spot is found.
bool PlanCloseDoorView(SceneRng& rng, const Scene& scene, SynthItem& item) {
  const Room& room = scene.rooms.at(0);
  std::vector<const Opening*> doors;
  for (const Opening& o : room.openings) {
    if (o.kind == OpeningKind::kDoor) doors.push_back(&o);
  }
  if (doors.empty()) return false;
  const int n = static_cast<int>(room.polygon.size());
  for (int attempt = 0; attempt < 40; ++attempt) {
    const Opening& door = *doors[rng.UniformInt(0, static_cast<int>(doors.size()) - 1)];
    const Vec2 a = room.polygon[door.wall], b = room.polygon[(door.wall + 1) % n];
    const Vec2 d = (b - a).normalized();
    const Vec2 inward(-d.y(), d.x());
    const Vec2 target2 = a + (door.offset_m + door.width_m * rng.Uniform(0.2, 0.8)) * d;
    const double dist = rng.Uniform(0.5, 1.6), side = DegToRad(rng.Uniform(-40.0, 40.0));
    const Vec2 cam2 = target2 + dist * (std::cos(side) * inward + std::sin(side) * d);
    const Vec3 cam(cam2.x(), cam2.y(), std::min(rng.Uniform(1.2, 1.75), room.height_m - 0.4));
    if (!FreeSpot(scene, room, cam) || !ClearSightline(scene, cam2, target2)) continue;
    const Vec2 v = target2 - cam2;
    item.kind = "photo";
    item.target = "close_door";
    item.camera.viewpoint.position_m = cam;
    item.camera.viewpoint.yaw_deg = RadToDeg(std::atan2(-v.x(), v.y())) + rng.Uniform(-15.0, 15.0);
    item.camera.viewpoint.pitch_deg = rng.Uniform(-10.0, 10.0);
    return true;
  }
  return false;
}

// Item `index` of `scene` with its camera's field of view drawn from `rng`
// (the first draw of the item's stream); pose and kind still to plan.
SynthItem NewSynthItem(const DatasetSynthOptions& options, const Scene& scene, int index, SceneRng& rng) {
  SynthItem item;
  item.index = index;
  item.scene_seed = scene.seed;
  const double hfov = rng.Uniform(options.min_hfov_deg, options.max_hfov_deg);
  item.camera.camera = PinholeCamera::FromHorizontalFov(options.width_px, options.height_px, hfov);
  item.camera.baseline_m = scene.rig.baseline_m;
  return item;
}

nlohmann::json Vec3Json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

template <typename T>
const T& PickOne(SceneRng& rng, const std::vector<T>& items) {
  return items[rng.UniformInt(0, static_cast<int>(items.size()) - 1)];
}

// The levers as (name, member) pairs, in declaration order.
std::vector<std::pair<std::string, bool SynthLevers::*>> LeverFields() {
  return {{"photo_textures", &SynthLevers::photo_textures},
          {"outside_photos", &SynthLevers::outside_photos},
          {"next_rooms", &SynthLevers::next_rooms},
          {"door_leaves", &SynthLevers::door_leaves},
          {"home_palette", &SynthLevers::home_palette},
          {"sunlight", &SynthLevers::sunlight},
          {"kitchens", &SynthLevers::kitchens},
          {"wall_details", &SynthLevers::wall_details},
          {"window_dressing", &SynthLevers::window_dressing},
          {"phone_camera", &SynthLevers::phone_camera},
          {"glass_doors", &SynthLevers::glass_doors},
          {"close_views", &SynthLevers::close_views},
          {"ceiling_like_walls", &SynthLevers::ceiling_like_walls},
          {"wall_art", &SynthLevers::wall_art},
          {"close_doors", &SynthLevers::close_doors}};
}

}  // namespace

bool SynthLevers::Any() const {
  for (const auto& [name, field] : LeverFields()) {
    if (this->*field) return true;
  }
  return false;
}

std::string SynthLevers::ToString() const {
  std::string s;
  for (const auto& [name, field] : LeverFields()) {
    if (this->*field) s += (s.empty() ? "" : ",") + name;
  }
  return s.empty() ? "none" : s;
}

const std::vector<std::string>& SynthLeverNames() {
  static const std::vector<std::string> kNames = [] {
    std::vector<std::string> names;
    for (const auto& [name, field] : LeverFields()) names.push_back(name);
    return names;
  }();
  return kNames;
}

SynthLevers ParseSynthLevers(std::string_view list) {
  SynthLevers levers;
  std::size_t start = 0;
  while (start <= list.size()) {
    std::size_t end = list.find(',', start);
    if (end == std::string_view::npos) end = list.size();
    std::string_view word = list.substr(start, end - start);
    start = end + 1;
    if (word.empty()) continue;
    const bool on = word.front() != '-';
    if (!on) word.remove_prefix(1);
    bool known = false;
    for (const auto& [name, field] : LeverFields()) {
      if (word == "all" || word == name) {
        levers.*field = on;
        known = true;
      }
    }
    if (word == "none") {
      levers = SynthLevers{};
      known = true;
    }
    if (!known) {
      std::string names = "all, none";
      for (const std::string& n : SynthLeverNames()) names += ", " + n;
      throw InvalidArgument(fmt::format("lever \"{}\": expected one of {}", word, names));
    }
  }
  return levers;
}

RandomSceneOptions LeveredSceneOptions(const DatasetSynthOptions& options) {
  RandomSceneOptions o = options.scene;
  const SynthLevers& l = options.levers;
  auto at_least = [](double& field, double value) { field = std::max(field, value); };
  if (l.door_leaves) at_least(o.styled_door_probability, 0.8);
  if (l.home_palette) at_least(o.neutral_wall_probability, 0.65);
  if (l.next_rooms) at_least(o.open_door_probability, 0.45);
  if (l.sunlight) at_least(o.window_sun_probability, 0.5);
  if (l.kitchens) at_least(o.kitchen_probability, 0.35);
  if (l.wall_details) at_least(o.wall_details_probability, 0.7);
  if (l.window_dressing) at_least(o.window_dressing_probability, 0.5);
  if (l.glass_doors) at_least(o.glazed_door_probability, 0.3);
  if (l.ceiling_like_walls) at_least(o.ceiling_like_walls_probability, 0.5);
  if (l.wall_art) at_least(o.wall_art_probability, 0.6);
  return o;
}

SceneLook MakeSceneLook(const SynthLevers& levers, const PhotoLibrary& photos, Scene& scene, std::uint64_t seed) {
  SceneLook look;
  SceneRng rng(SplitMix64(seed ^ 0x1005C0DEULL));
  if (levers.photo_textures && !photos.empty()) {
    const auto wood = photos.OfKind(PhotoKind::kWood), stone = photos.OfKind(PhotoKind::kStone),
               fabric = photos.OfKind(PhotoKind::kFabric), paper = photos.OfKind(PhotoKind::kPaper);
    // Doors, cabinets and furniture take plain grain, not parquet or burl.
    std::vector<std::shared_ptr<const Photo>> grain;
    for (const auto& p : wood) {
      const std::string name = std::filesystem::path(p->path).stem().string();
      if (name.find("parque") == std::string::npos && name.find("burl") == std::string::npos) grain.push_back(p);
    }
    if (grain.empty()) grain = wood;
    // `choices` empty: the material keeps its procedural texture.
    auto assign = [&](const std::string& material, const std::vector<std::shared_ptr<const Photo>>& choices,
                      double chance, double min_size_m, double max_size_m, double colour, double detail,
                      bool keep_procedural = false) {
      if (choices.empty() || FindMaterial(scene, material) == nullptr || !rng.Chance(chance)) return;
      // One draw per statement: argument evaluation order is unspecified.
      PhotoAlbedo pa{
          .photo = PickOne(rng, choices), .colour = colour, .detail = detail, .keep_procedural = keep_procedural};
      pa.size_m = rng.Uniform(min_size_m, max_size_m);
      pa.swap_uv = rng.Chance(0.5);
      pa.offset_m.x() = rng.Uniform(0, 5);
      pa.offset_m.y() = rng.Uniform(0, 5);
      look.albedo[material] = pa;
    };
    // Painted walls and ceilings: only the paper's relief, faint.
    assign("wall", paper, 0.7, 0.4, 1.5, 0.0, rng.Uniform(0.1, 0.45));
    assign("ceiling", paper, 0.5, 0.4, 1.5, 0.0, rng.Uniform(0.05, 0.25));
    if (const Material* floor = FindMaterial(scene, "floor")) {
      switch (floor->texture) {
        case TextureKind::kWood:
          assign("floor", wood, 0.9, 0.6, 2.0, rng.Uniform(0.6, 1.0), 1.0);
          break;
        case TextureKind::kTiles:
          assign("floor", stone, 0.8, 0.3, 1.0, rng.Uniform(0.5, 1.0), 1.0, true);
          break;
        case TextureKind::kCarpet:
          assign("floor", fabric, 0.8, 0.2, 0.6, 0.2, rng.Uniform(0.3, 0.6));
          break;
        default:
          assign("floor", stone, 0.6, 0.5, 1.5, 0.4, 0.8);
          break;
      }
    }
    assign("door_wood", grain, 0.9, 0.5, 1.2, rng.Uniform(0.6, 1.0), 1.0);
    assign("door_white", paper, 0.5, 0.5, 1.0, 0.0, 0.1);
    if (const Material* cabinet = FindMaterial(scene, "cabinet"); cabinet && cabinet->base_color.minCoeff() < 0.6) {
      assign("cabinet", grain, 0.9, 0.5, 1.2, rng.Uniform(0.6, 1.0), 1.0, true);
    }
    assign("worktop", stone, 0.8, 0.6, 1.5, rng.Uniform(0.5, 1.0), 1.0);
    if (rng.Chance(0.6)) {
      assign("furniture", grain, 0.7, 0.4, 1.2, rng.Uniform(0.3, 0.8), 1.0);
    } else {
      assign("furniture", fabric, 0.7, 0.2, 0.6, 0.2, 0.5);  // Upholstery: the weave's relief, not its colours.
    }
    assign("curtain", fabric, 0.7, 0.3, 0.8, 0.2, 0.5);
  }
  if (levers.outside_photos) {
    auto outside = photos.OfKind(PhotoKind::kEnvironment);
    auto views = photos.OfKind(PhotoKind::kView);
    outside.insert(outside.end(), views.begin(), views.end());
    if (!outside.empty()) {
      look.outside = PickOne(rng, outside);
      look.outside_yaw_deg = rng.Uniform(0, 360);
      look.outside_gain = std::exp(rng.Uniform(std::log(0.7), std::log(5.0)));
    }
  }
  if (levers.next_rooms) {
    const std::vector<Vec3> walls = {Vec3(0.9, 0.9, 0.88), Vec3(0.86, 0.82, 0.72), Vec3(0.8, 0.8, 0.78),
                                     Vec3(0.75, 0.8, 0.85), Vec3(0.92, 0.85, 0.7)};
    Material next_wall{.name = "next_wall",
                       .base_color = PickOne(rng, walls),
                       .roughness = 0.9,
                       .texture = TextureKind::kPlaster,
                       .texture_scale_m = 0.4};
    next_wall.secondary_color = 0.9 * next_wall.base_color;
    const Material* floor = FindMaterial(scene, "floor");
    Material next_floor = floor ? *floor : Material{};
    next_floor.name = "next_floor";
    if (rng.Chance(0.5)) next_floor.base_color = (0.8 * next_floor.base_color).cwiseMin(Vec3::Ones());
    scene.materials.push_back(next_wall);
    scene.materials.push_back(next_floor);
    look.mesh.next_room_depth_m = rng.Uniform(2.5, 5.0);
    look.mesh.next_room_side_m = rng.Uniform(0.8, 2.5);
    look.mesh.next_room_light = rng.Uniform(0.4, 1.5);
    look.mesh.next_room_wall_material = "next_wall";
    look.mesh.next_room_floor_material = "next_floor";
    if (auto it = look.albedo.find("floor"); it != look.albedo.end()) look.albedo["next_floor"] = it->second;
  }
  return look;
}

const FieldList<DatasetSynthOptions>& DatasetSynthOptionFields() {
  using O = DatasetSynthOptions;
  static const std::string kLeversText = fmt::format(
      "Realism levers: all, none or a comma list of {} (\"all,-sunlight\" turns one off); docs/render.md "
      "\"Realism levers\".",
      fmt::join(SynthLeverNames(), ", "));
  static const FieldList<O> kList = [] {
    FieldList<O> list = {
        Bind(&O::count,
             {.name = "count", .description = "Items in the whole dataset.", .minimum = 1.0, .maximum = 99999999.0}),
        Bind(&O::seed, {.name = "seed", .description = "Scenes, views and rendering seed.", .minimum = 0.0}),
        Bind(&O::width_px, {.name = "width_px", .description = "Image width, px.", .minimum = 8.0, .maximum = 8192.0}),
        Bind(&O::height_px,
             {.name = "height_px", .description = "Image height, px.", .minimum = 8.0, .maximum = 8192.0}),
        Bind(&O::min_hfov_deg, {.name = "min_hfov_deg",
                                .description = "Horizontal field of view, drawn per item: smallest, degrees.",
                                .exclusive_minimum = 10.0,
                                .exclusive_maximum = 170.0}),
        Bind(&O::max_hfov_deg, {.name = "max_hfov_deg",
                                .description = "… largest, degrees.",
                                .exclusive_minimum = 10.0,
                                .exclusive_maximum = 170.0}),
        Bind(&O::rig_view_share, {.name = "rig_view_share",
                                  .description = "Share of level rig views (the rest: photo-like views).",
                                  .minimum = 0.0,
                                  .maximum = 1.0}),
        Bind(&O::items_per_scene, {.name = "items_per_scene",
                                   .description = "Consecutive items that share a room (amortises building it).",
                                   .minimum = 1.0}),
        BindWith<O>(
            {.name = "levers", .kind = FieldKind::kString, .description = kLeversText},
            [](const O& o) { return nlohmann::json(o.levers.ToString()); },
            [](O& o, const nlohmann::json& v) { o.levers = ParseSynthLevers(v.get<std::string>()); }),
    };
    list.Nest("", &O::render, RenderOptionFields(),
              {"samples_per_pixel", "camera_effects", "id_drift", "indirect_light", "layout_labels"});
    return list;
  }();
  return kList;
}

void DatasetSynthOptions::Check() const {
  DatasetSynthOptionFields().CheckValues(*this, "DatasetSynthOptions");
  CheckArgument(shard_count >= 1, fmt::format("DatasetSynthOptions.shard_count = {}, must be >= 1", shard_count));
  CheckArgument(shard_index >= 0 && shard_index < shard_count,
                fmt::format("DatasetSynthOptions.shard_index = {}, must be in [0, {})", shard_index, shard_count));
  CheckArgument(min_hfov_deg <= max_hfov_deg,
                fmt::format("DatasetSynthOptions.min_hfov_deg/max_hfov_deg = {}/{}, need min <= max", min_hfov_deg,
                            max_hfov_deg));
  render.Check();
  scene.Check();
}

std::string DatasetSynthSummary::BriefReport() const {
  std::int64_t total = 0;
  for (auto c : class_pixels) total += c;
  auto pct = [&](int k) { return total > 0 ? 100.0 * class_pixels[k] / total : 0.0; };
  return fmt::format(
      "rendered {} of {} items ({} already done, {} rooms) in {:.1f} s → {}; pixels: background {:.1f}%, "
      "wall {:.1f}%, door {:.1f}%, window {:.1f}%",
      rendered, items, skipped, scenes, seconds, dir, pct(0), pct(1), pct(2), pct(3));
}

std::uint64_t SynthSceneSeed(const DatasetSynthOptions& options, int index) {
  return SplitMix64(options.seed ^ 0x5CE4E5EEDULL) + static_cast<std::uint64_t>(index / options.items_per_scene);
}

SynthItem PlanSynthItem(const DatasetSynthOptions& options, const Scene& scene, int index) {
  if (options.levers.close_views) {
    // Own stream: with the lever off, items are exactly as before.
    SceneRng close(SplitMix64(options.seed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(index) + 0xC105E));
    if (close.Chance(kCloseViewShare)) {
      SynthItem item = NewSynthItem(options, scene, index, close);
      if (PlanCloseView(close, scene, item)) return item;
    }
  }
  if (options.levers.close_doors) {
    // Own stream too: the other levers' items stay as they were.
    SceneRng close(SplitMix64(options.seed * 0xD1B54A32D192ED03ULL + static_cast<std::uint64_t>(index) + 0xD00125));
    if (close.Chance(kCloseDoorShare)) {
      SynthItem item = NewSynthItem(options, scene, index, close);
      if (PlanCloseDoorView(close, scene, item)) return item;
    }
  }
  SceneRng rng(SplitMix64(options.seed * 0x100000001B3ULL + static_cast<std::uint64_t>(index)));
  SynthItem item = NewSynthItem(options, scene, index, rng);
  const Room& room = scene.rooms.at(0);
  const int n = static_cast<int>(room.polygon.size());

  bool rig_view = rng.Chance(options.rig_view_share);
  if (!rig_view) {
    // Pick what the photo is of.
    std::vector<const Opening*> doors, windows;
    for (const Opening& o : room.openings) (o.kind == OpeningKind::kDoor ? doors : windows).push_back(&o);
    double r = rng.Uniform(0, 1);
    const Opening* target_opening = nullptr;
    if (r < 0.3 && !doors.empty()) {
      target_opening = doors[rng.UniformInt(0, static_cast<int>(doors.size()) - 1)];
      item.target = "door";
    } else if (r < 0.65 && !windows.empty()) {
      target_opening = windows[rng.UniformInt(0, static_cast<int>(windows.size()) - 1)];
      item.target = "window";
    } else {
      item.target = "wall";
    }
    for (int attempt = 0; attempt < 40; ++attempt) {
      int wall = target_opening ? target_opening->wall : rng.UniformInt(0, n - 1);
      Vec2 a = room.polygon[wall], b = room.polygon[(wall + 1) % n];
      double len = (b - a).norm();
      Vec2 d = (b - a) / len;
      Vec2 inward(-d.y(), d.x());
      double s, z;
      if (target_opening) {
        s = target_opening->offset_m + target_opening->width_m * rng.Uniform(0.3, 0.7);
        z = target_opening->sill_m + target_opening->height_m * rng.Uniform(0.35, 0.65);
      } else {
        s = rng.Uniform(std::min(0.3, 0.5 * len), std::max(len - 0.3, 0.5 * len));
        z = rng.Uniform(0.6, std::min(2.0, room.height_m - 0.3));
      }
      Vec3 target(a.x() + s * d.x(), a.y() + s * d.y(), z);
      double dist = rng.Uniform(1.5, 3.0) * (attempt < 20 ? 1.0 : 0.6);
      double side = DegToRad(rng.Uniform(-35.0, 35.0));
      Vec2 dir2 = std::cos(side) * inward + std::sin(side) * d;
      Vec3 cam(target.x() + dist * dir2.x(), target.y() + dist * dir2.y(),
               rng.Uniform(1.0, std::min(1.9, room.height_m - 0.4)));
      if (!FreeSpot(scene, room, cam)) continue;
      Vec3 v = target - cam;
      double horizontal = v.head<2>().norm();
      item.kind = "photo";
      item.camera.viewpoint.position_m = cam;
      item.camera.viewpoint.yaw_deg = RadToDeg(std::atan2(-v.x(), v.y())) + rng.Uniform(-8.0, 8.0);
      item.camera.viewpoint.pitch_deg =
          std::clamp(RadToDeg(std::atan2(v.z(), horizontal)) + rng.Uniform(-8.0, 8.0), -35.0, 35.0);
      return item;
    }
  }
  // A level rig view from the room's turn-in-place spot (or its centre).
  item.kind = "rig";
  item.target = "turn";
  Vec3 pos = scene.turn ? scene.turn->position_m : Vec3(Centroid(room.polygon).x(), Centroid(room.polygon).y(), 1.5);
  pos.z() += rng.Uniform(-0.2, 0.2);
  item.camera.viewpoint = {pos, rng.Uniform(0.0, 360.0), 0.0};
  return item;
}

namespace {

// Every file of an item to its temp name first, then the renames, meta last:
// a kill leaves at most a few microseconds in which an item is part-renamed
// (and then it is incomplete, so resume re-makes it).
void WriteSynthItem(const std::array<fs::path, 5>& files, const RenderedView& view, const std::string& meta) {
  std::vector<std::unique_ptr<AtomicFile>> temps;
  for (const fs::path& file : files) temps.push_back(std::make_unique<AtomicFile>(file));
  WriteImageToTemp(*temps[0], AsMat(view.left));
  WriteImageToTemp(*temps[1], AsMat(view.labels));
  WriteImageToTemp(*temps[2], AsMat(view.idmap));
  WriteImageToTemp(*temps[3], AsMat(view.depth_mm));
  std::ofstream out(temps[4]->temp_path(), std::ios::binary);
  out << meta;
  out.close();
  if (!out) throw Error(fmt::format("{}: cannot write", files[4].string()));
  for (auto& temp : temps) temp->Commit();
}

}  // namespace

nlohmann::json SynthRecordOptions(const DatasetSynthOptions& o) {
  const RandomSceneOptions& sc = o.scene;
  const RenderOptions& r = o.render;
  nlohmann::json j = {
      {"count", o.count},
      {"seed", o.seed},
      {"size", fmt::format("{}x{}", o.width_px, o.height_px)},
      {"hfov_deg", {o.min_hfov_deg, o.max_hfov_deg}},
      {"rig_view_share", o.rig_view_share},
      {"items_per_scene", o.items_per_scene},
      {"levers", o.levers.ToString()},
      {"render",
       {{"samples_per_pixel", r.samples_per_pixel},
        {"indirect_light", r.indirect_light},
        {"denoise_passes", r.denoise_passes},
        {"id_drift", r.id_drift},
        {"camera_effects", r.camera_effects},
        {"phone_camera", r.phone_camera},
        {"layout_labels", r.layout_labels}}},
      {"scene",
       {{"side_m", {sc.min_side_m, sc.max_side_m}},
        {"height_m", {sc.min_height_m, sc.max_height_m}},
        {"l_shape_probability", sc.l_shape_probability},
        {"rotated_probability", sc.rotated_probability},
        {"openings", {sc.min_openings, sc.max_openings}},
        {"furniture", {sc.min_furniture, sc.max_furniture}}}},
  };
  if (o.levers.photo_textures || o.levers.outside_photos) {
    nlohmann::json dirs = nlohmann::json::array();
    for (const fs::path& d : o.photo_dirs) dirs.push_back(d.string());
    j["photo_dirs"] = dirs;
  }
  return j;
}

DatasetSynthSummary SynthesizeDataset(const fs::path& dir, const DatasetSynthOptions& options,
                                      const ProgressCallback& progress) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  auto [begin, end] = ShardRange(options.count, options.shard_index, options.shard_count);
  DatasetSynthSummary summary;
  summary.items = end - begin;
  summary.dir = dir.string();
  ClaimSynthDir(dir, SynthRecordOptions(options));
  for (const char* sub : kSynthItemFolders) {
    fs::create_directories(dir / sub);
    RemoveDeadAtomicTemps(dir / sub, std::chrono::minutes(10));  // A killed writer's; shards share DIR.
  }

  std::uint64_t current_seed = 0;
  std::unique_ptr<Scene> scene;
  std::unique_ptr<SceneRenderer> renderer;
  SceneLook look;
  const RandomSceneOptions scene_options_levered = LeveredSceneOptions(options);
  RenderOptions render_options = options.render;
  render_options.phone_camera = render_options.phone_camera || options.levers.phone_camera;
  PhotoLibrary photos;
  if (options.levers.photo_textures || options.levers.outside_photos) {
    photos = LoadPhotoLibrary({.dirs = options.photo_dirs});
    if (photos.empty()) {
      spdlog::warn(
          "dataset synth: no photos found in the photo folders (--photo-dir; Debian: gimp-data, "
          "blender); procedural textures and the sky gradient only");
    } else {
      spdlog::info("dataset synth: {}", photos.ToString());
    }
  }
  for (int i = begin; i < end; ++i) {
    const std::array<fs::path, 5> files = SynthItemFiles(dir, i);
    if (options.resume && IsSynthItemComplete(dir, i)) {
      ++summary.skipped;
    } else {
      std::uint64_t scene_seed = SynthSceneSeed(options, i);
      if (!renderer || scene_seed != current_seed) {
        renderer.reset();  // Free the old BVH first: memory stays flat.
        RandomSceneOptions scene_options = scene_options_levered;
        scene_options.rig.width_px = options.width_px;
        scene_options.rig.height_px = options.height_px;
        scene = std::make_unique<Scene>(RandomScene(scene_options, scene_seed));
        look = MakeSceneLook(options.levers, photos, *scene, scene_seed);
        renderer = std::make_unique<SceneRenderer>(*scene, look);
        current_seed = scene_seed;
        ++summary.scenes;
      }
      SynthItem item = PlanSynthItem(options, *scene, i);
      RenderedView view = renderer->Render(item.camera, render_options, static_cast<std::uint64_t>(i), false);
      std::array<std::int64_t, 4> counts{};
      for (int y = 0; y < view.labels.height(); ++y) {
        const auto* row = view.labels.Row<std::uint8_t>(y);
        for (int x = 0; x < view.labels.width(); ++x) counts[std::min<int>(row[x], 3)]++;
      }
      for (int k = 0; k < 4; ++k) summary.class_pixels[k] += counts[k];
      const PinholeCamera& k = item.camera.camera;
      const double total = static_cast<double>(k.width_px) * k.height_px;
      nlohmann::json meta = {
          {"version", 1},
          {"index", i},
          {"scene_seed", item.scene_seed},
          {"kind", item.kind},
          {"target", item.target},
          {"camera",
           {{"width", k.width_px}, {"height", k.height_px}, {"fx", k.fx}, {"fy", k.fy}, {"cx", k.cx}, {"cy", k.cy}}},
          {"position_m", Vec3Json(item.camera.viewpoint.position_m)},
          {"yaw_deg", item.camera.viewpoint.yaw_deg},
          {"pitch_deg", item.camera.viewpoint.pitch_deg},
          {"effects", view.effects.ToString()},
          {"class_fraction", {counts[0] / total, counts[1] / total, counts[2] / total, counts[3] / total}},
      };
      if (options.levers.Any()) {
        meta["levers"] = options.levers.ToString();
        meta["look"] = look.ToString();
      }
      WriteSynthItem(files, view, meta.dump(1) + "\n");
      ++summary.rendered;
    }
    ReportProgress(progress, {"synth", static_cast<std::int64_t>(i - begin + 1), summary.items, ""});
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace asbuilt
