#include "asbuilt/mcp/tools.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "asbuilt/mcp/tools_common.h"
#include "asbuilt/util/error.h"

// The tools that build a scene piece by piece (new_scene, add_room, add_door,
// add_window, add_furniture), each tool's schema beside its handler.

namespace asbuilt::mcp {

namespace {

ToolSpec NewSceneSpec() {
  return {.name = "new_scene",
          .title = "New scene",
          .description = WithConventions("Start a new, empty scene (discards the current one). Then add rooms "
                                         "with add_room."),
          .fields = {{.name = "name",
                      .kind = FieldKind::kString,
                      .description = "Scene name.",
                      .max_length = 128,
                      .default_value = "room"},
                     {.name = "seed",
                      .kind = FieldKind::kInteger,
                      .description = "Seed for procedural textures and exterior objects.",
                      .minimum = 0.0,
                      .maximum = 4294967295.0,
                      .default_value = 0}},
          .destructive = true};
}

}  // namespace

ToolResult SceneTools::NewScene(const FieldArgs& a, const ToolCallContext&) {
  Scene s;
  s.name = a.String("name");
  s.seed = static_cast<std::uint64_t>(a.Integer("seed"));
  scene_ = std::move(s);
  return ToolResult::Text(fmt::format("New empty scene \"{}\". Next: add_room.", scene_.name));
}

namespace {

ToolSpec AddRoomSpec(const ToolLimits& L) {
  return {.name = "add_room",
          .title = "Add room",
          .description =
              WithConventions("Add a room: either a rectangle (width_m along x/east, depth_m along y/north, its "
                              "south-west corner at origin) or a polygon of inner wall-face corners. The rectangle "
                              "or polygon can be rotated about origin. The reply lists the walls with their numbers "
                              "and the compass direction each faces, for add_door/add_window."),
          .fields = {
              {.name = "width_m",
               .kind = FieldKind::kNumber,
               .description = "Rectangle size along x (east-west). Give with depth_m, or give polygon.",
               .exclusive_minimum = 0.0,
               .maximum = 200.0},
              {.name = "depth_m",
               .kind = FieldKind::kNumber,
               .description = "Rectangle size along y (north-south).",
               .exclusive_minimum = 0.0,
               .maximum = 200.0},
              {.name = "polygon",
               .kind = FieldKind::kPolygon,
               .description = "Corners [[x, y], ...] of the inner wall faces, in order around the "
                              "room, not repeating the first (counter-clockwise preferred; "
                              "clockwise is reversed).",
               .min_items = 3,
               .max_items = static_cast<std::size_t>(L.max_polygon_points)},
              {.name = "origin",
               .kind = FieldKind::kPoint2,
               .description = "Where the rectangle's south-west corner goes; for a polygon, added to "
                              "every corner.",
               .default_value = {0.0, 0.0}},
              {.name = "rotation_deg",
               .kind = FieldKind::kNumber,
               .description = "Counter-clockwise rotation about origin.",
               .minimum = -360.0,
               .maximum = 360.0,
               .default_value = 0.0},
              {.name = "height_m",
               .kind = FieldKind::kNumber,
               .description = "Floor to ceiling.",
               .exclusive_minimum = 0.0,
               .maximum = 20.0,
               .default_value = 2.7},
              {.name = "wall_thickness_m",
               .kind = FieldKind::kNumber,
               .description = "Wall thickness outwards from the inner face.",
               .exclusive_minimum = 0.0,
               .maximum = 2.0,
               .default_value = 0.2},
              {.name = "name", .kind = FieldKind::kString, .description = "Room name.", .max_length = 128},
          }};
}

}  // namespace

ToolResult SceneTools::AddRoom(const FieldArgs& a, const ToolCallContext&) {
  bool has_rect = a.Has("width_m") || a.Has("depth_m");
  bool has_poly = a.Has("polygon");
  if (has_rect == has_poly) {
    throw InvalidArgument("give either width_m and depth_m (a rectangle) or polygon (corners), not both or neither");
  }
  std::vector<Vec2> poly;
  if (has_rect) {
    if (!a.Has("width_m") || !a.Has("depth_m")) {
      throw InvalidArgument(fmt::format("arguments.{}: required with {} (a rectangle needs both)",
                                        a.Has("width_m") ? "depth_m" : "width_m",
                                        a.Has("width_m") ? "width_m" : "depth_m"));
    }
    double w = a.Number("width_m"), d = a.Number("depth_m");
    poly = {{0, 0}, {w, 0}, {w, d}, {0, d}};
  } else {
    for (const auto& p : a.Points("polygon")) poly.emplace_back(p[0], p[1]);
  }
  std::vector<double> origin = a.Numbers("origin");
  double rot = DegToRad(a.Number("rotation_deg"));
  for (Vec2& p : poly) {
    p = Vec2(std::cos(rot) * p.x() - std::sin(rot) * p.y(), std::sin(rot) * p.x() + std::cos(rot) * p.y()) +
        Vec2(origin[0], origin[1]);
  }
  std::string note;
  if (poly.size() >= 3 && PolygonArea(poly) < 0) {
    std::reverse(poly.begin(), poly.end());
    note =
        " (the corners were clockwise; they were reversed, so the walls are numbered from the "
        "last corner given)";
  }
  Room room;
  room.name = a.OptString("name").value_or(fmt::format("room {}", scene_.rooms.size()));
  room.polygon = poly;
  room.height_m = a.Number("height_m");
  room.wall_thickness_m = a.Number("wall_thickness_m");
  Scene next = scene_;
  next.rooms.push_back(room);
  Commit(std::move(next), "the room");
  const Room& added = scene_.rooms.back();
  return ToolResult::Text(
      fmt::format("Added room {} \"{}\": {} corners, {:.2f} m², {:.2f} m high{}. Walls (use these numbers "
                  "with add_door/add_window):\n{}",
                  scene_.rooms.size() - 1, added.name, added.polygon.size(), PolygonArea(added.polygon), added.height_m,
                  note, DescribeWalls(added)));
}

namespace {

// The wall of `room` facing `side` (scene.h's WallFacing, within 30°).
// Throws InvalidArgument when none faces it.
int WallFacingSide(const Room& room, std::string_view side) {
  if (const std::optional<int> wall = WallFacing(room, side, 30.0)) return *wall;
  throw InvalidArgument(
      fmt::format("arguments.side: no wall of this room faces {}; give the wall number instead. "
                  "Walls:\n{}",
                  side, DescribeWalls(room)));
}

// Tool fields shared by add_door and add_window.
std::vector<Field> OpeningFields(OpeningKind kind, const ToolLimits& limits) {
  bool door = kind == OpeningKind::kDoor;
  std::vector<Field> f = {
      {.name = "room",
       .kind = FieldKind::kInteger,
       .description = "Room index (0 = first room added).",
       .minimum = 0.0,
       .maximum = limits.max_rooms - 1.0,
       .default_value = 0},
      {.name = "wall",
       .kind = FieldKind::kInteger,
       .description = "Wall number (see add_room's reply or describe_scene). Give wall or side.",
       .minimum = 0.0,
       .maximum = limits.max_polygon_points - 1.0},
      {.name = "side",
       .kind = FieldKind::kEnum,
       .description = "Compass side instead of a wall number: the wall facing that way "
                      "(north = +y, east = +x).",
       .choices = CompassNames()},
      {.name = "offset_m",
       .kind = FieldKind::kNumber,
       .description = "Distance along the wall from its start corner to the near edge of the "
                      "opening. Omit to centre it (or to space several evenly).",
       .minimum = 0.0,
       .maximum = 1000.0},
      {.name = "width_m",
       .kind = FieldKind::kNumber,
       .description = "Clear opening width.",
       .exclusive_minimum = 0.0,
       .maximum = 20.0,
       .default_value = door ? 0.9 : 1.2},
      {.name = "height_m",
       .kind = FieldKind::kNumber,
       .description = "Clear opening height.",
       .exclusive_minimum = 0.0,
       .maximum = 20.0,
       .default_value = door ? 2.1 : 1.2},
      {.name = "count",
       .kind = FieldKind::kInteger,
       .description = door ? "How many identical doors to space evenly along the wall, each centred in one of "
                             "`count` equal bays."
                           : "How many identical windows to space evenly along the wall, each centred in one of "
                             "`count` equal bays.",
       .minimum = 1.0,
       .maximum = 8.0,
       .default_value = 1},
      {.name = "material",
       .kind = FieldKind::kString,
       .description = "Material name (set_material); default: the built-in door/window look.",
       .max_length = 64},
  };
  if (door) {
    f.push_back({.name = "open_deg",
                 .kind = FieldKind::kNumber,
                 .description = "Door leaf angle: 0 closed, 90 wide open; swings into the room.",
                 .minimum = 0.0,
                 .maximum = 180.0,
                 .default_value = 0.0});
    f.push_back({.name = "hinge",
                 .kind = FieldKind::kEnum,
                 .description = "Hinge side seen from inside the room.",
                 .choices = {"left", "right"},
                 .default_value = "left"});
  } else {
    f.push_back({.name = "sill_m",
                 .kind = FieldKind::kNumber,
                 .description = "Height of the bottom of the opening above the floor.",
                 .minimum = 0.0,
                 .maximum = 20.0,
                 .default_value = 0.9});
    f.push_back({.name = "frame_width_m",
                 .kind = FieldKind::kNumber,
                 .description = "Width of the window frame profile.",
                 .minimum = 0.0,
                 .maximum = 0.5,
                 .default_value = 0.05});
    f.push_back({.name = "glass",
                 .kind = FieldKind::kBool,
                 .description = "Whether the window is glazed.",
                 .default_value = true});
  }
  return f;
}

ToolSpec AddDoorSpec(const ToolLimits& L) {
  return {.name = "add_door",
          .title = "Add door",
          .description = WithConventions("Add a door (or several, evenly spaced) to a room's wall, by wall number "
                                         "or compass side. Offsets run from the wall's start corner."),
          .fields = OpeningFields(OpeningKind::kDoor, L)};
}

ToolSpec AddWindowSpec(const ToolLimits& L) {
  return {.name = "add_window",
          .title = "Add window",
          .description = WithConventions("Add a window (or several, evenly spaced) to a room's wall, by wall number "
                                         "or compass side, with its sill height. Offsets run from the wall's start "
                                         "corner."),
          .fields = OpeningFields(OpeningKind::kWindow, L)};
}

}  // namespace

ToolResult SceneTools::AddDoor(const FieldArgs& a, const ToolCallContext&) {
  return AddOpenings(a, OpeningKind::kDoor);
}

ToolResult SceneTools::AddWindow(const FieldArgs& a, const ToolCallContext&) {
  return AddOpenings(a, OpeningKind::kWindow);
}

ToolResult SceneTools::AddOpenings(const FieldArgs& a, OpeningKind kind) {
  const char* noun = OpeningKindName(kind);
  int r = RoomArg(a);
  const Room& room = scene_.rooms[r];
  if (a.Has("wall") == a.Has("side")) {
    throw InvalidArgument(
        fmt::format("give either wall (a number) or side (north, east, south, west…), not both or neither. "
                    "Walls of room {}:\n{}",
                    r, DescribeWalls(room)));
  }
  int wall;
  if (a.Has("wall")) {
    std::int64_t w = a.Integer("wall");
    if (w >= WallCount(room)) {
      throw InvalidArgument(fmt::format("arguments.wall: room {} has walls 0..{}, got {}. Walls:\n{}", r,
                                        WallCount(room) - 1, w, DescribeWalls(room)));
    }
    wall = static_cast<int>(w);
  } else {
    wall = WallFacingSide(room, a.String("side"));
  }
  const double length = WallLength(room, wall);
  const double width = a.Number("width_m");
  const double height = a.Number("height_m");
  const double sill = kind == OpeningKind::kWindow ? a.Number("sill_m") : 0.0;
  const int count = static_cast<int>(a.Integer("count"));
  if (sill + height > room.height_m + 1e-9) {
    throw InvalidArgument(
        fmt::format("arguments.height_m: sill {:.2f} m + height {:.2f} m = {:.2f} m is above the {:.2f} m "
                    "ceiling; lower height_m{}",
                    sill, height, sill + height, room.height_m, kind == OpeningKind::kWindow ? " or sill_m" : ""));
  }
  std::vector<double> offsets;
  if (a.Has("offset_m")) {
    if (count != 1) {
      throw InvalidArgument(
          "arguments.offset_m: give offset_m only with count 1; several "
          "openings are spaced evenly along the wall");
    }
    double off = a.Number("offset_m");
    if (off + width > length + 1e-9) {
      throw InvalidArgument(
          fmt::format("arguments.offset_m: the {} would end at {:.2f} m but wall {} is {:.2f} m long; use "
                      "offset_m <= {:.2f} or a narrower width_m",
                      noun, off + width, wall, length, std::max(0.0, length - width)));
    }
    offsets.push_back(off);
  } else {
    // Each in one of `count` equal bays, 5 cm clear of its bay's ends at least.
    if (length / count - width < 0.1) {
      throw InvalidArgument(
          fmt::format("arguments.width_m: {} {}{} {:.2f} m wide do not fit on wall {} ({:.2f} m long)", count, noun,
                      count == 1 ? "" : "s", width, wall, length));
    }
    offsets = EvenlySpacedOffsets(length, std::vector<double>(count, width));
  }

  Scene next = scene_;
  Room& target = next.rooms[r];
  for (double off : offsets) {
    Opening o;
    o.kind = kind;
    o.wall = wall;
    o.offset_m = off;
    o.width_m = width;
    o.height_m = height;
    o.sill_m = sill;
    if (auto m = a.OptString("material")) o.material = *m;
    if (kind == OpeningKind::kDoor) {
      o.open_deg = a.Number("open_deg");
      o.hinge = a.String("hinge") == "right" ? HingeSide::kRight : HingeSide::kLeft;
    } else {
      o.frame_width_m = a.Number("frame_width_m");
      o.glass = a.Bool("glass");
    }
    target.openings.push_back(o);
  }
  // `room` refers into scene_, which Commit replaces: name the wall first
  // (ASan found the use after free).
  const std::string facing = WallCompassName(room, wall);
  Commit(std::move(next), fmt::format("the {}", noun));
  std::vector<std::string> placed;
  for (double off : offsets) {
    placed.push_back(fmt::format("{:.2f}–{:.2f} m", off, off + width));
  }
  return ToolResult::Text(
      fmt::format("Added {} {}{} to room {} wall {} (faces {}, {:.2f} m long) at {} along the wall; {:.2f} m "
                  "wide, {:.2f} m high{}.",
                  count, noun, count == 1 ? "" : "s", r, wall, facing, length, fmt::join(placed, ", "), width, height,
                  kind == OpeningKind::kWindow ? fmt::format(", sill {:.2f} m", sill) : ""));
}

namespace {

struct FurniturePreset {
  std::string_view kind;
  Vec3 size_m;
};
const FurniturePreset kFurniturePresets[] = {
    {"box", {1.0, 0.6, 0.75}},     {"table", {1.6, 0.9, 0.75}}, {"desk", {1.4, 0.7, 0.75}},
    {"chair", {0.5, 0.5, 0.9}},    {"bed", {1.6, 2.0, 0.5}},    {"sofa", {2.0, 0.9, 0.85}},
    {"wardrobe", {1.2, 0.6, 2.0}}, {"shelf", {0.9, 0.35, 1.8}}, {"cabinet", {0.8, 0.45, 0.9}},
};

std::vector<std::string_view> FurnitureKinds() {
  std::vector<std::string_view> out;
  for (const auto& p : kFurniturePresets) out.push_back(p.kind);
  return out;
}

ToolSpec AddFurnitureSpec() {
  return {
      .name = "add_furniture",
      .title = "Add furniture",
      .description = WithConventions("Add a furniture box standing on the floor (it hides parts of walls in "
                                     "renders, like real furniture). Pick a kind for typical sizes, or give "
                                     "size_m."),
      .fields = {
          {.name = "centre",
           .kind = FieldKind::kPoint2,
           .description = "Footprint centre [x, y].",
           .required = true,
           .minimum = -1000.0,
           .maximum = 1000.0},
          {.name = "kind",
           .kind = FieldKind::kEnum,
           .description = "Preset that sets a typical size (size_m overrides it).",
           .choices = FurnitureKinds(),
           .default_value = "box"},
          {.name = "size_m",
           .kind = FieldKind::kPoint3,
           .description = "[width (local x), depth (local y), height], each > 0.",
           .exclusive_minimum = 0.0,
           .maximum = 20.0},
          {.name = "yaw_deg",
           .kind = FieldKind::kNumber,
           .description = "Counter-clockwise rotation of the footprint.",
           .minimum = -360.0,
           .maximum = 360.0,
           .default_value = 0.0},
          {.name = "elevation_m",
           .kind = FieldKind::kNumber,
           .description = "Bottom above the floor (wall shelves).",
           .minimum = 0.0,
           .maximum = 20.0,
           .default_value = 0.0},
          {.name = "material",
           .kind = FieldKind::kString,
           .description = "Material name.",
           .max_length = 64,
           .default_value = "furniture"},
          {.name = "name", .kind = FieldKind::kString, .description = "Name; default: the kind.", .max_length = 128},
      }};
}

}  // namespace

ToolResult SceneTools::AddFurniture(const FieldArgs& a, const ToolCallContext&) {
  std::string kind = a.String("kind");
  Furniture f;
  for (const auto& p : kFurniturePresets) {
    if (p.kind == kind) f.size_m = p.size_m;
  }
  if (a.Has("size_m")) {
    auto s = a.Numbers("size_m");
    f.size_m = Vec3(s[0], s[1], s[2]);
  }
  auto c = a.Numbers("centre");
  f.centre_m = Vec2(c[0], c[1]);
  f.yaw_deg = a.Number("yaw_deg");
  f.elevation_m = a.Number("elevation_m");
  f.material = a.String("material");
  f.name = a.OptString("name").value_or(kind);
  Scene next = scene_;
  next.furniture.push_back(f);
  Commit(std::move(next), "the furniture");
  bool inside = false;
  for (const Room& r : scene_.rooms) inside = inside || PointInPolygon(r.polygon, f.centre_m);
  return ToolResult::Text(fmt::format("Added furniture {} \"{}\": {:.2f} × {:.2f} × {:.2f} m at {}{}.",
                                      scene_.furniture.size() - 1, f.name, f.size_m.x(), f.size_m.y(), f.size_m.z(),
                                      P2(f.centre_m), inside ? "" : " (warning: its centre is outside every room)"));
}

// In tools/list order.
void SceneTools::RegisterBuildTools() {
  Register(NewSceneSpec(), &SceneTools::NewScene);
  Register(AddRoomSpec(limits_), &SceneTools::AddRoom);
  Register(AddDoorSpec(limits_), &SceneTools::AddDoor);
  Register(AddWindowSpec(limits_), &SceneTools::AddWindow);
  Register(AddFurnitureSpec(), &SceneTools::AddFurniture);
}

}  // namespace asbuilt::mcp
