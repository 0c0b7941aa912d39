#include "asbuilt/mcp/tools.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "asbuilt/mcp/tools_common.h"
#include "asbuilt/util/error.h"

// The tools that style a scene and place its rig (set_material,
// set_lighting, place_rig) and remove_item, each tool's schema beside its
// handler.

namespace asbuilt::mcp {

namespace {

std::vector<std::string_view> TextureNames() {
  std::vector<std::string_view> out;
  for (TextureKind k : {TextureKind::kNone, TextureKind::kPlaster, TextureKind::kPaint, TextureKind::kWallpaper,
                        TextureKind::kWood, TextureKind::kTiles, TextureKind::kCarpet, TextureKind::kConcrete}) {
    out.push_back(TextureKindName(k));
  }
  return out;
}

ToolSpec SetMaterialSpec(const ToolLimits& L) {
  return {.name = "set_material",
          .title = "Set material",
          .description =
              "Define or change a material (colour, roughness, procedural texture) and "
              "optionally apply it to walls, floors, ceilings, furniture, doors or "
              "windows. Built-in names: wall, floor, ceiling, door, window_frame, glass, "
              "furniture, skirting; changing one of these restyles everything using it.",
          .fields = {
              {.name = "name",
               .kind = FieldKind::kString,
               .description = "Material name.",
               .required = true,
               .max_length = 64},
              {.name = "base_color",
               .kind = FieldKind::kColor,
               .description = "Linear RGB, each 0..1 (e.g. [0.8, 0.8, 0.75] off-white)."},
              {.name = "roughness",
               .kind = FieldKind::kNumber,
               .description = "0 glossy … 1 matte.",
               .minimum = 0.0,
               .maximum = 1.0},
              {.name = "texture",
               .kind = FieldKind::kEnum,
               .description = "Procedural texture.",
               .choices = TextureNames()},
              {.name = "texture_scale_m",
               .kind = FieldKind::kNumber,
               .description = "Feature size of the texture (tile size, plank width…).",
               .exclusive_minimum = 0.0,
               .maximum = 10.0},
              {.name = "secondary_color",
               .kind = FieldKind::kColor,
               .description = "Second colour (grout, wood grain), each 0..1."},
              {.name = "apply_to",
               .kind = FieldKind::kEnum,
               .description = "Also assign the material to these surfaces.",
               .choices = {"none", "walls", "floor", "ceiling", "furniture", "doors", "windows"},
               .default_value = "none"},
              {.name = "room",
               .kind = FieldKind::kInteger,
               .description = "With apply_to walls/floor/ceiling/doors/windows: only this room "
                              "(default: every room).",
               .minimum = 0.0,
               .maximum = L.max_rooms - 1.0},
          }};
}

}  // namespace

ToolResult SceneTools::SetMaterial(const FieldArgs& a, const ToolCallContext&) {
  Scene next = scene_;
  const std::string name = a.String("name");
  if (name.empty()) throw InvalidArgument("arguments.name: must not be empty");
  auto it =
      std::find_if(next.materials.begin(), next.materials.end(), [&](const Material& m) { return m.name == name; });
  bool created = it == next.materials.end();
  if (created) {
    const Material* base = FindMaterial(next, name);  // A built-in of that name, if any.
    Material m = base ? *base : Material{};
    m.name = name;
    next.materials.push_back(m);
    it = next.materials.end() - 1;
  }
  Material& m = *it;
  if (a.Has("base_color")) {
    auto v = a.Numbers("base_color");
    m.base_color = Vec3(v[0], v[1], v[2]);
  }
  if (a.Has("secondary_color")) {
    auto v = a.Numbers("secondary_color");
    m.secondary_color = Vec3(v[0], v[1], v[2]);
  }
  if (a.Has("roughness")) m.roughness = a.Number("roughness");
  if (a.Has("texture")) m.texture = *TextureKindFromName(a.String("texture"));
  if (a.Has("texture_scale_m")) m.texture_scale_m = a.Number("texture_scale_m");

  const std::string apply = a.String("apply_to");
  std::optional<int> only_room;
  if (a.Has("room")) only_room = RoomArg(a);
  int assigned = 0;
  for (int r = 0; r < static_cast<int>(next.rooms.size()); ++r) {
    if (only_room && r != *only_room) continue;
    Room& room = next.rooms[r];
    if (apply == "walls") room.wall_material = name, ++assigned;
    if (apply == "floor") room.floor_material = name, ++assigned;
    if (apply == "ceiling") room.ceiling_material = name, ++assigned;
    for (Opening& o : room.openings) {
      if ((apply == "doors" && o.kind == OpeningKind::kDoor) ||
          (apply == "windows" && o.kind == OpeningKind::kWindow)) {
        o.material = name, ++assigned;
      }
    }
  }
  if (apply == "furniture") {
    for (Furniture& f : next.furniture) f.material = name, ++assigned;
  }
  Commit(std::move(next), "the material");
  const Material& done = *FindMaterial(scene_, name);
  return ToolResult::Text(
      fmt::format("{} material \"{}\": colour [{:.2f}, {:.2f}, {:.2f}], roughness {:.2f}, texture {} "
                  "(scale {:.2f} m){}.",
                  created ? "Defined" : "Updated", name, done.base_color.x(), done.base_color.y(), done.base_color.z(),
                  done.roughness, TextureKindName(done.texture), done.texture_scale_m,
                  apply == "none" ? "" : fmt::format("; applied to {} {}", assigned, apply)));
}

namespace {

ToolSpec SetLightingSpec() {
  return {.name = "set_lighting",
          .title = "Set lighting",
          .description = WithConventions("Set the lights: replace all lights with one (mode replace) or add one "
                                         "(mode add): a ceiling area light, a point light or the sun; and the "
                                         "ambient level and sky. kind none with mode replace removes all lights."),
          .fields = {
              {.name = "mode",
               .kind = FieldKind::kEnum,
               .description = "Replace all lights or add one.",
               .choices = {"replace", "add"},
               .default_value = "replace"},
              {.name = "kind",
               .kind = FieldKind::kEnum,
               .description = "Light type.",
               .choices = {"area", "point", "sun", "none"},
               .default_value = "area"},
              {.name = "position_m",
               .kind = FieldKind::kPoint3,
               .description = "[x, y, z]; default: above the first room's centre, just under the "
                              "ceiling. Ignored for the sun.",
               .minimum = -1000.0,
               .maximum = 1000.0},
              {.name = "size_m",
               .kind = FieldKind::kPoint2,
               .description = "Area light panel size [x, y].",
               .exclusive_minimum = 0.0,
               .maximum = 20.0,
               .default_value = {1.2, 0.3}},
              {.name = "color",
               .kind = FieldKind::kColor,
               .description = "Linear RGB, each 0..1.",
               .default_value = {1.0, 0.95, 0.9}},
              {.name = "intensity",
               .kind = FieldKind::kNumber,
               .description = "Relative brightness (1 = typical).",
               .exclusive_minimum = 0.0,
               .maximum = 100.0,
               .default_value = 1.0},
              {.name = "azimuth_deg",
               .kind = FieldKind::kNumber,
               .description = "Sun: direction it shines from, counter-clockwise from east.",
               .minimum = -360.0,
               .maximum = 360.0,
               .default_value = 135.0},
              {.name = "elevation_deg",
               .kind = FieldKind::kNumber,
               .description = "Sun: height above the horizon.",
               .minimum = 0.0,
               .maximum = 90.0,
               .default_value = 35.0},
              {.name = "ambient",
               .kind = FieldKind::kNumber,
               .description = "Ambient fill light, 0..1.",
               .minimum = 0.0,
               .maximum = 1.0},
              {.name = "sky", .kind = FieldKind::kBool, .description = "Whether a sky is seen through windows."},
          }};
}

}  // namespace

ToolResult SceneTools::SetLighting(const FieldArgs& a, const ToolCallContext&) {
  Scene next = scene_;
  const std::string kind = a.String("kind");
  if (a.String("mode") == "replace") next.lights.clear();
  if (kind != "none") {
    Light l;
    l.kind = *LightKindFromName(kind);
    if (a.Has("position_m")) {
      auto p = a.Numbers("position_m");
      l.position_m = Vec3(p[0], p[1], p[2]);
    } else if (l.kind != LightKind::kSun) {
      if (next.rooms.empty() || next.rooms[0].polygon.size() < 3) {
        throw InvalidArgument("arguments.position_m: required while the scene has no room");
      }
      const Room& room = next.rooms[0];
      Vec2 c = PolygonCentroid(room.polygon);
      double z = room.height_m - (l.kind == LightKind::kArea ? 0.02 : 0.3);
      l.position_m = Vec3(c.x(), c.y(), z);
    }
    auto s = a.Numbers("size_m");
    l.size_m = Vec2(s[0], s[1]);
    auto col = a.Numbers("color");
    l.color = Vec3(col[0], col[1], col[2]);
    l.intensity = a.Number("intensity");
    l.azimuth_deg = a.Number("azimuth_deg");
    l.elevation_deg = a.Number("elevation_deg");
    next.lights.push_back(l);
  }
  if (a.Has("ambient")) next.environment.ambient = a.Number("ambient");
  if (a.Has("sky")) next.environment.sky = a.Bool("sky");
  Commit(std::move(next), "the light");
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < scene_.lights.size(); ++i) {
    const Light& l = scene_.lights[i];
    lines.push_back(l.kind == LightKind::kSun
                        ? fmt::format("light {}: sun from azimuth {:.0f}°, elevation {:.0f}°, "
                                      "intensity {:.2f}",
                                      i, l.azimuth_deg, l.elevation_deg, l.intensity)
                        : fmt::format("light {}: {} at ({:.2f}, {:.2f}, {:.2f}), intensity {:.2f}", i,
                                      LightKindName(l.kind), l.position_m.x(), l.position_m.y(), l.position_m.z(),
                                      l.intensity));
  }
  return ToolResult::Text(fmt::format("Lighting set: {} light{}, ambient {:.2f}, sky {}.{}", scene_.lights.size(),
                                      scene_.lights.size() == 1 ? "" : "s", scene_.environment.ambient,
                                      scene_.environment.sky ? "on" : "off", Bullets(lines)));
}

namespace {

ToolSpec PlaceRigSpec(const ToolLimits& L) {
  return {
      .name = "place_rig",
      .title = "Place stereo rig",
      .description = fmt::format("Place the stereo camera rig and choose its views: either a turn in place (step_deg, "
                                 "start_deg, count; count 0 = a full turn) or a list of yaws. Yaw 0 looks north (+y), "
                                 "90 looks west (counter-clockwise). Also sets the image size, field of view and "
                                 "baseline. Limits: at most {} views, images at most {}×{} px.",
                                 L.max_views, L.max_image_width_px, L.max_image_height_px),
      .fields = {
          {.name = "position",
           .kind = FieldKind::kPoint2,
           .description = "Rig centre [x, y]; default: the centre of the room.",
           .minimum = -1000.0,
           .maximum = 1000.0},
          {.name = "room",
           .kind = FieldKind::kInteger,
           .description = "Room whose centre is the default position.",
           .minimum = 0.0,
           .maximum = L.max_rooms - 1.0,
           .default_value = 0},
          {.name = "height_m",
           .kind = FieldKind::kNumber,
           .description = "Camera height above the floor.",
           .exclusive_minimum = 0.0,
           .maximum = 20.0,
           .default_value = 1.5},
          {.name = "yaws_deg",
           .kind = FieldKind::kNumberList,
           .description = "Explicit view directions (instead of a turn).",
           .minimum = -360.0,
           .maximum = 360.0,
           .min_items = 1,
           .max_items = static_cast<std::size_t>(L.max_views)},
          {.name = "step_deg",
           .kind = FieldKind::kNumber,
           .description = "Turn step.",
           .exclusive_minimum = 0.0,
           .maximum = 360.0,
           .default_value = 30.0},
          {.name = "start_deg",
           .kind = FieldKind::kNumber,
           .description = "Yaw of the first view.",
           .minimum = -360.0,
           .maximum = 360.0,
           .default_value = 0.0},
          {.name = "count",
           .kind = FieldKind::kInteger,
           .description = "Views in the turn; 0 = a full turn (360 / step_deg).",
           .minimum = 0.0,
           .maximum = static_cast<double>(L.max_views),
           .default_value = 0},
          {.name = "width_px",
           .kind = FieldKind::kInteger,
           .description = "Image width.",
           .minimum = 16.0,
           .maximum = static_cast<double>(L.max_image_width_px)},
          {.name = "height_px",
           .kind = FieldKind::kInteger,
           .description = "Image height.",
           .minimum = 16.0,
           .maximum = static_cast<double>(L.max_image_height_px)},
          {.name = "hfov_deg",
           .kind = FieldKind::kNumber,
           .description = "Horizontal field of view.",
           .minimum = 10.0,
           .maximum = 150.0},
          {.name = "baseline_m",
           .kind = FieldKind::kNumber,
           .description = "Distance between the two cameras.",
           .minimum = 0.01,
           .maximum = 2.0},
      }};
}

}  // namespace

ToolResult SceneTools::PlaceRig(const FieldArgs& a, const ToolCallContext&) {
  Scene next = scene_;
  Vec2 xy;
  if (a.Has("position")) {
    auto p = a.Numbers("position");
    xy = Vec2(p[0], p[1]);
  } else {
    int r = RoomArg(a);
    xy = PolygonCentroid(scene_.rooms[r].polygon);
  }
  Vec3 pos(xy.x(), xy.y(), a.Number("height_m"));
  next.viewpoints.clear();
  next.turn.reset();
  if (a.Has("yaws_deg")) {
    if (a.Has("count") && a.Integer("count") != 0) {
      throw InvalidArgument("arguments.count: give either yaws_deg or a turn (step_deg, count)");
    }
    for (double yaw : a.Numbers("yaws_deg")) {
      next.viewpoints.push_back({.position_m = pos, .yaw_deg = yaw, .pitch_deg = 0.0});
    }
  } else {
    TurnInPlace t;
    t.position_m = pos;
    t.step_deg = a.Number("step_deg");
    t.start_deg = a.Number("start_deg");
    t.count = static_cast<int>(a.Integer("count"));
    next.turn = t;
    std::size_t views = CountViews(next);
    if (views > static_cast<std::size_t>(limits_.max_views)) {
      throw InvalidArgument(
          fmt::format("arguments.step_deg: a full turn at {} ° steps is {} views; the limit is {}: use "
                      "step_deg >= {:.1f} or give count <= {}",
                      t.step_deg, views, limits_.max_views, 360.0 / limits_.max_views, limits_.max_views));
    }
  }
  if (a.Has("width_px")) next.rig.width_px = static_cast<int>(a.Integer("width_px"));
  if (a.Has("height_px")) next.rig.height_px = static_cast<int>(a.Integer("height_px"));
  if (a.Has("hfov_deg")) {
    next.rig.hfov_deg = a.Number("hfov_deg");
    next.rig.fx.reset(), next.rig.fy.reset(), next.rig.cx.reset(), next.rig.cy.reset();
  }
  if (a.Has("baseline_m")) next.rig.baseline_m = a.Number("baseline_m");
  Commit(std::move(next), "the rig position");
  std::vector<Viewpoint> views = ResolveViewpoints(scene_);
  std::vector<std::string> yaws;
  for (const Viewpoint& v : views) yaws.push_back(fmt::format("{:g}", v.yaw_deg));
  return ToolResult::Text(fmt::format(
      "Rig at ({:.2f}, {:.2f}), {:.2f} m high: {} view{} (yaw {} °), {}×{} px, {:.0f}° HFOV, "
      "baseline {:.3f} m.",
      pos.x(), pos.y(), pos.z(), views.size(), views.size() == 1 ? "" : "s", fmt::join(yaws, ", "), scene_.rig.width_px,
      scene_.rig.height_px, scene_.rig.Camera().HorizontalFovDeg(), scene_.rig.baseline_m));
}

namespace {

ToolSpec RemoveItemSpec(const ToolLimits& L) {
  return {.name = "remove_item",
          .title = "Remove item",
          .description =
              "Remove a room, an opening (door/window) of a room, a piece of furniture, a "
              "light or a scene material, by index (describe_scene lists them).",
          .fields =
              {
                  {.name = "what",
                   .kind = FieldKind::kEnum,
                   .description = "What to remove.",
                   .required = true,
                   .choices = {"room", "opening", "furniture", "light", "material"}},
                  {.name = "index",
                   .kind = FieldKind::kInteger,
                   .description = "Index of the item (openings: within the room).",
                   .required = true,
                   .minimum = 0.0,
                   .maximum = 100000.0},
                  {.name = "room",
                   .kind = FieldKind::kInteger,
                   .description = "Room of the opening.",
                   .minimum = 0.0,
                   .maximum = L.max_rooms - 1.0,
                   .default_value = 0},
              },
          .destructive = true};
}

}  // namespace

ToolResult SceneTools::RemoveItem(const FieldArgs& a, const ToolCallContext&) {
  const std::string what = a.String("what");
  const std::int64_t i = a.Integer("index");
  Scene next = scene_;
  auto erase = [&](auto& list, std::string_view noun) {
    if (i >= static_cast<std::int64_t>(list.size())) {
      throw InvalidArgument(
          list.empty() ? fmt::format("arguments.index: there is no {} to remove", noun)
                       : fmt::format("arguments.index: {} indices are 0..{}, got {}", noun, list.size() - 1, i));
    }
    list.erase(list.begin() + i);
  };
  if (what == "room") erase(next.rooms, "room");
  if (what == "opening") erase(next.rooms.at(RoomArg(a)).openings, "opening");
  if (what == "furniture") erase(next.furniture, "furniture");
  if (what == "light") erase(next.lights, "light");
  if (what == "material") erase(next.materials, "material");
  // Indices shift on removal, so compare problem counts, not texts.
  std::size_t before = ValidateScene(scene_).size();
  std::vector<Problem> after = ValidateScene(next);
  scene_ = std::move(next);
  std::string warning;
  if (after.size() > before) {
    std::vector<std::string> lines;
    for (const Problem& p : after) lines.push_back(ProblemText(p));
    warning = fmt::format(" The scene now has problems to fix:{}", Bullets(lines));
  }
  return ToolResult::Text(fmt::format("Removed {} {}.{}", what, i, warning));
}

// In tools/list order.
void SceneTools::RegisterStyleTools() {
  Register(SetMaterialSpec(limits_), &SceneTools::SetMaterial);
  Register(SetLightingSpec(), &SceneTools::SetLighting);
}

void SceneTools::RegisterRigTools() {
  Register(PlaceRigSpec(limits_), &SceneTools::PlaceRig);
  Register(RemoveItemSpec(limits_), &SceneTools::RemoveItem);
}

}  // namespace asbuilt::mcp
