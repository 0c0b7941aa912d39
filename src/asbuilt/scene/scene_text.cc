#include "asbuilt/scene/scene_text.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/scene/furnish.h"
#include "asbuilt/scene/scene_text_layout.h"
#include "asbuilt/scene/scene_text_parser.h"
#include "asbuilt/scene/scene_text_tokens.h"
#include "asbuilt/scene/scene_text_vocabulary.h"
#include "asbuilt/util/error.h"

// SceneFromText in stages: the text's words (scene_text_tokens.h) → what it
// asks for (scene_text_parser.h) → the room's size → the room with its
// openings (scene_text_layout.h) → materials, rig, furniture and lights.

namespace asbuilt {
namespace {

using scene_text::OpeningRequest;
using scene_text::Request;
using scene_text::RoomKind;

std::string Join(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "\"" : ", \"") + w + "\"";
  return out;
}

// Reads the text; the words no parser step used go to result.unused_words.
// Throws when the text holds nothing to build from.
Request ReadRequest(std::string_view text, SceneTextResult& result) {
  scene_text::Parser parser(scene_text::Tokenize(text));
  Request r = parser.Parse(result.assumptions);

  bool understood = false;
  for (const scene_text::Token& t : parser.tokens()) {
    if (t.used && !scene_text::IsBreakWord(t.text)) understood = true;
    if (!t.used && !scene_text::IsStopWord(t.text) && !scene_text::IsBreakWord(t.text)) {
      result.unused_words.push_back(t.text);
    }
  }
  if (!understood && r.openings.empty() && !r.kind) {
    throw InputError("text", "",
                     fmt::format("nothing to build from \"{}\": no room kind, size, door or window found "
                                 "(see docs/scene.md for the phrases understood)",
                                 text));
  }
  return r;
}

// The room's kind and size: what the text gave, else the kind's defaults.
struct RoomSize {
  const RoomKind* kind = nullptr;
  double width_m = 0, depth_m = 0, height_m = 0;
};

// Throws when the size is not a room's.
RoomSize SizeOfRoom(const Request& r, std::vector<std::string>& notes) {
  const RoomKind* kind = r.kind;
  if (!kind) {
    kind = &scene_text::RoomKinds().back();
    notes.push_back("no room kind given: a generic room");
  }
  double w, d;
  if (r.width && r.depth) {
    w = *r.width;
    d = *r.depth;
  } else if (r.area) {
    double aspect = kind->width_m / kind->depth_m;
    if (r.square) aspect = 1.0;
    w = std::sqrt(*r.area * aspect);
    d = *r.area / w;
    notes.push_back(fmt::format("{:.1f} m² as {:.2f} × {:.2f} m", *r.area, w, d));
  } else if (r.side || (r.width && r.square)) {
    w = d = r.side.value_or(r.width.value_or(0));
  } else if (r.width || r.depth) {
    w = r.width.value_or(kind->width_m);
    d = r.depth.value_or(kind->depth_m);
    notes.push_back(fmt::format("only one side given: {:.2f} × {:.2f} m", w, d));
  } else {
    w = kind->width_m;
    d = r.square ? kind->width_m : kind->depth_m;
    notes.push_back(fmt::format("no size given: {} default {:.2f} × {:.2f} m", kind->name, w, d));
  }
  if (!(w > 0.5 && d > 0.5 && w < 200 && d < 200)) {
    throw InputError("text", "",
                     fmt::format("room size {:.2f} × {:.2f} m is not a room (each side must be in "
                                 "0.5 … 200 m)",
                                 w, d));
  }
  double height = r.height.value_or(kind->height_m);
  if (!r.height) notes.push_back(fmt::format("no height given: {:.2f} m", height));
  if (!(height > 1.0 && height < 30)) {
    throw InputError("text", "", fmt::format("room height {:.2f} m is not a room height (1 … 30 m)", height));
  }
  return {kind, w, d, height};
}

// The room's outline (rotated as asked), height, walls and openings; a room
// with no door gets one when the options ask for it.
Room BuildRoom(const Request& r, const RoomSize& size, const SceneTextOptions& options,
               std::vector<std::string>& notes) {
  Room room;
  room.name = size.kind->name;
  room.polygon = scene_text::RoomPolygon(r, size.width_m, size.depth_m, notes);
  if (r.rotation_deg != 0) {
    double a = DegToRad(r.rotation_deg);
    Eigen::Rotation2Dd rot(a);
    for (Vec2& p : room.polygon) p = rot * p;
  }
  room.height_m = size.height_m;
  if (r.thickness) room.wall_thickness_m = *r.thickness;

  bool has_door = false;
  for (const OpeningRequest& q : r.openings) has_door = has_door || (q.kind == OpeningKind::kDoor && q.count > 0);
  Request with_door = r;
  if (!has_door && options.add_door_if_none) {
    OpeningRequest door;
    door.kind = OpeningKind::kDoor;
    door.text = "(default door)";
    door.walls = {"south"};
    with_door.openings.push_back(door);
    notes.push_back("no door mentioned: added a 0.90 m door on the south wall");
  }
  room.openings = scene_text::BuildOpenings(with_door, room, notes);
  return room;
}

// A scene material for each surface the text styled.
void AddMaterials(const Request& r, Scene& scene) {
  for (const auto& [surface, style] : r.surfaces) {
    Material m = *FindMaterial(scene, surface);
    if (style.color) {
      m.base_color = *style.color;
      m.secondary_color = 0.85 * *style.color;
    }
    if (style.texture) m.texture = *style.texture;
    scene.materials.push_back(m);
  }
}

// Turn in place where a surveyor would stand, below the ceiling.
void PlaceRig(const Request& r, const SceneTextOptions& options, double height_m, Scene& scene) {
  double rig_h = std::min(r.rig_height.value_or(options.rig_height_m), height_m - 0.2);
  Vec2 spot = scene_text::TurnSpot(scene.rooms[0].polygon);
  scene.turn = TurnInPlace{.position_m = Vec3(spot.x(), spot.y(), rig_h),
                           .start_deg = 0.0,
                           .step_deg = r.rig_step.value_or(options.turn_step_deg),
                           .count = 0};
  if (r.baseline) scene.rig.baseline_m = *r.baseline;
}

// The furniture the text names, else the kind's usual pieces.
void Furnish(const Request& r, const RoomKind& kind, const SceneTextOptions& options, Scene& scene,
             std::vector<std::string>& notes) {
  std::vector<FurnitureSpec> pieces;
  for (const auto& [spec, count] : r.furniture) {
    for (int i = 0; i < count; ++i) pieces.push_back(spec);
  }
  if (pieces.empty() && options.furnish && !r.no_furniture) {
    for (const auto& [word, count] : kind.furniture) {
      auto spec = FurnitureByName(word);
      if (!spec) continue;
      for (int i = 0; i < count; ++i) pieces.push_back(*spec);
    }
  }
  // Classroom-like rooms: desks in rows, the rest against the walls.
  if (kind.free_standing_desks) {
    int desks = 0;
    std::optional<FurnitureSpec> desk;
    std::vector<FurnitureSpec> others;
    for (const FurnitureSpec& p : pieces) {
      if (p.name == "desk") {
        ++desks;
        desk = p;
      } else {
        others.push_back(p);
      }
    }
    if (desk) {
      int left = PlaceInRows(scene, 0, *desk, desks);
      if (left > 0) notes.push_back(fmt::format("no space for {} of the {} desks", left, desks));
      pieces = others;
    }
  }
  if (!pieces.empty()) {
    std::vector<std::string> left = PlaceFurniture(scene, 0, pieces, options.seed);
    if (!left.empty()) notes.push_back(fmt::format("no space for: {}", Join(left)));
  }
}

// Ceiling lights; the sun through the first window's wall, unless at night.
void AddLights(const Request& r, Scene& scene) {
  AddCeilingLights(scene, 0, r.light_count.value_or(0), r.light_intensity);
  bool has_window = false;
  int window_wall = -1;
  for (const Opening& o : scene.rooms[0].openings) {
    if (o.kind == OpeningKind::kWindow && window_wall < 0) window_wall = o.wall;
    has_window = has_window || o.kind == OpeningKind::kWindow;
  }
  if (r.sun.value_or(has_window) && !r.night) {
    Vec2 n = window_wall >= 0 ? WallOutwardNormal(scene.rooms[0], window_wall) : Vec2(0, -1);
    scene.lights.push_back({.kind = LightKind::kSun,
                            .intensity = 1.0,
                            .azimuth_deg = RadToDeg(std::atan2(n.y(), n.x())),
                            .elevation_deg = 35.0});
  }
  if (r.night) {
    scene.environment.sky_color = Vec3(0.02, 0.02, 0.05);
    scene.environment.ground_color = Vec3(0.02, 0.02, 0.02);
    scene.environment.ambient = 0.05;
  }
}

}  // namespace

void SceneTextOptions::Check() const {
  CheckArgument(rig_height_m > 0, fmt::format("SceneTextOptions.rig_height_m = {}, must be > 0", rig_height_m));
  CheckArgument(turn_step_deg > 0 && turn_step_deg <= 360,
                fmt::format("SceneTextOptions.turn_step_deg = {}, must be in (0, 360]", turn_step_deg));
}

std::string SceneTextResult::BriefReport() const {
  std::string shape;
  if (!scene.rooms.empty()) {
    const Room& r = scene.rooms[0];
    shape = r.polygon.size() == 4 ? fmt::format("{:.2f} × {:.2f} m", WallLength(r, 0), WallLength(r, 1))
                                  : fmt::format("{}-sided, {:.2f} m²", r.polygon.size(), PolygonArea(r.polygon));
  }
  std::size_t openings = 0;
  for (const Room& r : scene.rooms) openings += r.openings.size();
  std::string out =
      fmt::format("{}: {}, {} opening{}, {} view{}", scene.name, shape, openings, openings == 1 ? "" : "s",
                  ResolveViewpoints(scene).size(), ResolveViewpoints(scene).size() == 1 ? "" : "s");
  if (!unused_words.empty()) {
    out += fmt::format("; {} word{} not understood: {}", unused_words.size(), unused_words.size() == 1 ? "" : "s",
                       Join(unused_words));
  }
  return out;
}

SceneTextResult SceneFromText(std::string_view text, const SceneTextOptions& options) {
  options.Check();
  SceneTextResult result;
  std::vector<std::string>& notes = result.assumptions;
  const Request r = ReadRequest(text, result);
  const RoomSize size = SizeOfRoom(r, notes);

  Scene& scene = result.scene;
  scene.name = size.kind->name;
  scene.seed = options.seed;
  scene.rooms.push_back(BuildRoom(r, size, options, notes));
  AddMaterials(r, scene);
  PlaceRig(r, options, size.height_m, scene);
  Furnish(r, *size.kind, options, scene, notes);
  AddLights(r, scene);

  CheckScene(scene, "text");
  if (!result.unused_words.empty()) {
    spdlog::warn("scene text: {} word{} not understood: {}", result.unused_words.size(),
                 result.unused_words.size() == 1 ? "" : "s", Join(result.unused_words));
  }
  return result;
}

}  // namespace asbuilt
