#include "asbuilt/scene/scene_json.h"

#include <limits>

#include <fmt/format.h>

#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"

namespace asbuilt {
namespace fs = std::filesystem;
using nlohmann::json;
namespace {

// Reading: types only here (with field paths); ranges and geometry are
// ValidateScene's job, so each rule lives in one place.

void ReadNumber(const JsonField& parent, const char* key, double& out) {
  if (auto v = parent.Optional(key).Number()) out = *v;
}

void ReadInt(const JsonField& parent, const char* key, int& out) {
  JsonField f = parent.Optional(key);
  if (auto v = f.Integer()) {
    if (*v < INT32_MIN || *v > INT32_MAX) {
      f.AddError(fmt::format("integer {} out of range", *v));
    } else {
      out = static_cast<int>(*v);
    }
  }
}

void ReadBool(const JsonField& parent, const char* key, bool& out) {
  if (auto v = parent.Optional(key).Bool()) out = *v;
}

void ReadString(const JsonField& parent, const char* key, std::string& out) {
  if (auto v = parent.Optional(key).String()) out = *v;
}

void ReadVec2(const JsonField& f, Vec2& out) {
  if (!f.present()) return;
  if (auto v = f.NumberArray(2)) out = Vec2((*v)[0], (*v)[1]);
}

void ReadVec3(const JsonField& f, Vec3& out) {
  if (!f.present()) return;
  if (auto v = f.NumberArray(3)) out = Vec3((*v)[0], (*v)[1], (*v)[2]);
}

void ReadOptionalNumber(const JsonField& parent, const char* key, std::optional<double>& out) {
  JsonField f = parent.Optional(key);
  if (f.present()) {
    if (auto v = f.Number()) out = *v;
  }
}

Material ParseMaterial(const JsonField& f) {
  Material m;
  if (!f.Object({"name", "base_color", "roughness", "texture", "texture_scale_m", "secondary_color"})) {
    return m;
  }
  if (auto n = f.Required("name").String()) m.name = *n;
  ReadVec3(f.Optional("base_color"), m.base_color);
  ReadNumber(f, "roughness", m.roughness);
  JsonField t = f.Optional("texture");
  if (auto s = t.String()) {
    if (auto k = TextureKindFromName(*s)) {
      m.texture = *k;
    } else {
      t.AddError(
          fmt::format("unknown texture \"{}\" (none, plaster, paint, wallpaper, wood, tiles, "
                      "carpet, concrete)",
                      *s));
    }
  }
  ReadNumber(f, "texture_scale_m", m.texture_scale_m);
  ReadVec3(f.Optional("secondary_color"), m.secondary_color);
  return m;
}

Opening ParseOpening(const JsonField& f) {
  Opening o;
  if (!f.Object({"kind", "wall", "offset_m", "width_m", "height_m", "sill_m", "open_deg", "hinge", "frame_width_m",
                 "glass", "glazed", "material"})) {
    return o;
  }
  JsonField kind = f.Required("kind");
  if (auto k = kind.String()) {
    if (*k == "door") {
      o.kind = OpeningKind::kDoor;
    } else if (*k == "window") {
      o.kind = OpeningKind::kWindow;
      o.sill_m = 0.9;
      o.height_m = 1.2;
      o.width_m = 1.2;
    } else {
      kind.AddError(fmt::format("expected \"door\" or \"window\", got \"{}\"", *k));
    }
  }
  ReadInt(f, "wall", o.wall);
  if (!f.Optional("wall").present()) f.Required("wall");  // Records "missing required field".
  ReadNumber(f, "offset_m", o.offset_m);
  ReadNumber(f, "width_m", o.width_m);
  ReadNumber(f, "height_m", o.height_m);
  ReadNumber(f, "sill_m", o.sill_m);
  ReadNumber(f, "open_deg", o.open_deg);
  JsonField hinge = f.Optional("hinge");
  if (auto s = hinge.String()) {
    if (auto h = HingeSideFromName(*s)) {
      o.hinge = *h;
    } else {
      hinge.AddError(fmt::format("expected \"left\" or \"right\", got \"{}\"", *s));
    }
  }
  ReadNumber(f, "frame_width_m", o.frame_width_m);
  ReadBool(f, "glass", o.glass);
  ReadBool(f, "glazed", o.glazed);
  ReadString(f, "material", o.material);
  return o;
}

Room ParseRoom(const JsonField& f) {
  Room room;
  if (!f.Object({"name", "polygon", "height_m", "wall_thickness_m", "openings", "wall_material", "floor_material",
                 "ceiling_material", "skirting"})) {
    return room;
  }
  ReadString(f, "name", room.name);
  JsonField poly = f.Required("polygon");
  if (auto n = poly.ArraySize()) {
    for (std::size_t k = 0; k < *n; ++k) {
      Vec2 p = Vec2::Constant(std::numeric_limits<double>::quiet_NaN());
      ReadVec2(poly.At(k), p);
      room.polygon.push_back(p);
    }
  }
  ReadNumber(f, "height_m", room.height_m);
  ReadNumber(f, "wall_thickness_m", room.wall_thickness_m);
  JsonField openings = f.Optional("openings");
  if (auto n = openings.ArraySize()) {
    for (std::size_t k = 0; k < *n; ++k) room.openings.push_back(ParseOpening(openings.At(k)));
  }
  ReadString(f, "wall_material", room.wall_material);
  ReadString(f, "floor_material", room.floor_material);
  ReadString(f, "ceiling_material", room.ceiling_material);
  ReadBool(f, "skirting", room.skirting);
  return room;
}

Furniture ParseFurniture(const JsonField& f) {
  Furniture x;
  if (!f.Object({"name", "centre_m", "yaw_deg", "size_m", "elevation_m", "material"})) return x;
  ReadString(f, "name", x.name);
  ReadVec2(f.Required("centre_m"), x.centre_m);
  ReadNumber(f, "yaw_deg", x.yaw_deg);
  ReadVec3(f.Optional("size_m"), x.size_m);
  ReadNumber(f, "elevation_m", x.elevation_m);
  ReadString(f, "material", x.material);
  return x;
}

Light ParseLight(const JsonField& f) {
  Light l;
  if (!f.Object({"kind", "position_m", "size_m", "color", "intensity", "azimuth_deg", "elevation_deg"})) {
    return l;
  }
  JsonField kind = f.Optional("kind");
  if (auto s = kind.String()) {
    if (auto k = LightKindFromName(*s)) {
      l.kind = *k;
    } else {
      kind.AddError(fmt::format("expected \"area\", \"point\" or \"sun\", got \"{}\"", *s));
    }
  }
  ReadVec3(f.Optional("position_m"), l.position_m);
  ReadVec2(f.Optional("size_m"), l.size_m);
  ReadVec3(f.Optional("color"), l.color);
  ReadNumber(f, "intensity", l.intensity);
  ReadNumber(f, "azimuth_deg", l.azimuth_deg);
  ReadNumber(f, "elevation_deg", l.elevation_deg);
  return l;
}

template <typename T, typename Fn>
void ParseArray(const JsonField& parent, const char* key, std::vector<T>& out, Fn parse) {
  JsonField arr = parent.Optional(key);
  if (auto n = arr.ArraySize()) {
    for (std::size_t k = 0; k < *n; ++k) out.push_back(parse(arr.At(k)));
  }
}

Scene ParseScene(const json& root, JsonDiagnostics& diag) {
  Scene scene;
  JsonField doc(root, diag);
  if (!doc.Object({"version", "name", "seed", "materials", "rooms", "furniture", "lights", "environment", "rig",
                   "viewpoints", "turn", "$schema", "description"})) {
    return scene;
  }
  JsonField version = doc.Required("version");
  if (auto v = version.Integer()) {
    if (*v != 1) {
      version.AddError(fmt::format("unsupported version {}, expected 1", *v));
    }
  }
  ReadString(doc, "name", scene.name);
  JsonField seed = doc.Optional("seed");
  if (seed.present()) {
    if (seed.raw()->is_number_unsigned()) {
      scene.seed = seed.raw()->get<std::uint64_t>();
    } else if (auto s = seed.Integer()) {
      if (*s < 0) {
        seed.AddError(fmt::format("must be >= 0, got {}", *s));
      } else {
        scene.seed = static_cast<std::uint64_t>(*s);
      }
    }
  }
  ParseArray(doc, "materials", scene.materials, ParseMaterial);
  JsonField rooms = doc.Required("rooms");
  if (auto n = rooms.ArraySize()) {
    for (std::size_t k = 0; k < *n; ++k) scene.rooms.push_back(ParseRoom(rooms.At(k)));
  }
  ParseArray(doc, "furniture", scene.furniture, ParseFurniture);
  ParseArray(doc, "lights", scene.lights, ParseLight);

  JsonField env = doc.Optional("environment");
  if (env.present() && env.Object({"sky", "sky_color", "ground_color", "exterior_objects", "ambient"})) {
    Environment& e = scene.environment;
    ReadBool(env, "sky", e.sky);
    ReadVec3(env.Optional("sky_color"), e.sky_color);
    ReadVec3(env.Optional("ground_color"), e.ground_color);
    ReadBool(env, "exterior_objects", e.exterior_objects);
    ReadNumber(env, "ambient", e.ambient);
  }

  JsonField rig = doc.Optional("rig");
  if (rig.present() && rig.Object({"width_px", "height_px", "hfov_deg", "fx", "fy", "cx", "cy", "baseline_m"})) {
    StereoRigSpec& s = scene.rig;
    ReadInt(rig, "width_px", s.width_px);
    ReadInt(rig, "height_px", s.height_px);
    ReadNumber(rig, "hfov_deg", s.hfov_deg);
    ReadOptionalNumber(rig, "fx", s.fx);
    ReadOptionalNumber(rig, "fy", s.fy);
    ReadOptionalNumber(rig, "cx", s.cx);
    ReadOptionalNumber(rig, "cy", s.cy);
    ReadNumber(rig, "baseline_m", s.baseline_m);
  }

  ParseArray(doc, "viewpoints", scene.viewpoints, [](const JsonField& f) {
    Viewpoint v;
    if (!f.Object({"position_m", "yaw_deg", "pitch_deg"})) return v;
    ReadVec3(f.Required("position_m"), v.position_m);
    ReadNumber(f, "yaw_deg", v.yaw_deg);
    ReadNumber(f, "pitch_deg", v.pitch_deg);
    return v;
  });

  JsonField turn = doc.Optional("turn");
  if (turn.present() && turn.Object({"position_m", "start_deg", "step_deg", "count"})) {
    TurnInPlace t;
    ReadVec3(turn.Required("position_m"), t.position_m);
    ReadNumber(turn, "start_deg", t.start_deg);
    ReadNumber(turn, "step_deg", t.step_deg);
    ReadInt(turn, "count", t.count);
    scene.turn = t;
  }
  return scene;
}

// Types first; semantics only when the types are right (one mistake, one message).
void ParseAndValidate(const json& root, JsonDiagnostics& diag, Scene& scene) {
  scene = ParseScene(root, diag);
  if (!diag.ok()) return;
  for (Problem& p : ValidateScene(scene, diag.file())) diag.AddError(p.field_path, p.message);
}

json J2(const Vec2& v) { return json::array({v.x(), v.y()}); }
json J3(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

}  // namespace

Scene SceneFromJson(const json& json_doc, const std::string& name) {
  JsonDiagnostics diag(name);
  Scene scene;
  ParseAndValidate(json_doc, diag, scene);
  diag.ThrowIfErrors();
  diag.LogWarnings();
  return scene;
}

Scene ReadScene(const fs::path& path) {
  JsonDiagnostics diag(path.string());
  json root = ParseJsonFile(path, diag);
  diag.ThrowIfErrors();
  Scene scene;
  ParseAndValidate(root, diag, scene);
  diag.ThrowIfErrors();
  diag.LogWarnings();
  return scene;
}

FileReport CheckSceneJson(const json& json_doc, const std::string& name) {
  JsonDiagnostics diag(name);
  Scene scene;
  ParseAndValidate(json_doc, diag, scene);
  return {diag.errors(), diag.warnings()};
}

FileReport CheckSceneFile(const fs::path& path) {
  JsonDiagnostics diag(path.string());
  json root = ParseJsonFile(path, diag);
  if (diag.ok()) {
    Scene scene;
    ParseAndValidate(root, diag, scene);
  }
  return {diag.errors(), diag.warnings()};
}

json SceneToJson(const Scene& scene) {
  json j;
  j["version"] = scene.version;
  j["name"] = scene.name;
  j["seed"] = scene.seed;
  json materials = json::array();
  for (const Material& m : scene.materials) {
    materials.push_back({{"name", m.name},
                         {"base_color", J3(m.base_color)},
                         {"roughness", m.roughness},
                         {"texture", TextureKindName(m.texture)},
                         {"texture_scale_m", m.texture_scale_m},
                         {"secondary_color", J3(m.secondary_color)}});
  }
  j["materials"] = std::move(materials);
  json rooms = json::array();
  for (const Room& r : scene.rooms) {
    json poly = json::array();
    for (const Vec2& p : r.polygon) poly.push_back(J2(p));
    json openings = json::array();
    for (const Opening& o : r.openings) {
      openings.push_back({{"kind", OpeningKindName(o.kind)},
                          {"wall", o.wall},
                          {"offset_m", o.offset_m},
                          {"width_m", o.width_m},
                          {"height_m", o.height_m},
                          {"sill_m", o.sill_m},
                          {"open_deg", o.open_deg},
                          {"hinge", HingeSideName(o.hinge)},
                          {"frame_width_m", o.frame_width_m},
                          {"glass", o.glass},
                          {"material", o.material}});
      if (o.glazed) openings.back()["glazed"] = true;  // Absent when false: older files stay as they were.
    }
    rooms.push_back({{"name", r.name},
                     {"polygon", std::move(poly)},
                     {"height_m", r.height_m},
                     {"wall_thickness_m", r.wall_thickness_m},
                     {"openings", std::move(openings)},
                     {"wall_material", r.wall_material},
                     {"floor_material", r.floor_material},
                     {"ceiling_material", r.ceiling_material},
                     {"skirting", r.skirting}});
  }
  j["rooms"] = std::move(rooms);
  json furniture = json::array();
  for (const Furniture& f : scene.furniture) {
    furniture.push_back({{"name", f.name},
                         {"centre_m", J2(f.centre_m)},
                         {"yaw_deg", f.yaw_deg},
                         {"size_m", J3(f.size_m)},
                         {"elevation_m", f.elevation_m},
                         {"material", f.material}});
  }
  j["furniture"] = std::move(furniture);
  json lights = json::array();
  for (const Light& l : scene.lights) {
    lights.push_back({{"kind", LightKindName(l.kind)},
                      {"position_m", J3(l.position_m)},
                      {"size_m", J2(l.size_m)},
                      {"color", J3(l.color)},
                      {"intensity", l.intensity},
                      {"azimuth_deg", l.azimuth_deg},
                      {"elevation_deg", l.elevation_deg}});
  }
  j["lights"] = std::move(lights);
  const Environment& e = scene.environment;
  j["environment"] = {{"sky", e.sky},
                      {"sky_color", J3(e.sky_color)},
                      {"ground_color", J3(e.ground_color)},
                      {"exterior_objects", e.exterior_objects},
                      {"ambient", e.ambient}};
  const StereoRigSpec& s = scene.rig;
  json rig = {{"width_px", s.width_px}, {"height_px", s.height_px}, {"hfov_deg", s.hfov_deg}};
  if (s.fx) rig["fx"] = *s.fx;
  if (s.fy) rig["fy"] = *s.fy;
  if (s.cx) rig["cx"] = *s.cx;
  if (s.cy) rig["cy"] = *s.cy;
  rig["baseline_m"] = s.baseline_m;
  j["rig"] = std::move(rig);
  json views = json::array();
  for (const Viewpoint& v : scene.viewpoints) {
    views.push_back({{"position_m", J3(v.position_m)}, {"yaw_deg", v.yaw_deg}, {"pitch_deg", v.pitch_deg}});
  }
  j["viewpoints"] = std::move(views);
  if (scene.turn) {
    const TurnInPlace& t = *scene.turn;
    j["turn"] = {
        {"position_m", J3(t.position_m)}, {"start_deg", t.start_deg}, {"step_deg", t.step_deg}, {"count", t.count}};
  }
  return j;
}

void WriteScene(const Scene& scene, const fs::path& path) { WriteFileAtomic(path, SceneToJson(scene).dump(2) + "\n"); }

const json& SceneJsonSchema() {
  static const json kSchema = [] {
    auto num = [](const char* d) { return json{{"type", "number"}, {"description", d}}; };
    auto pos = [](const char* d) { return json{{"type", "number"}, {"exclusiveMinimum", 0}, {"description", d}}; };
    auto nonneg = [](const char* d) { return json{{"type", "number"}, {"minimum", 0}, {"description", d}}; };
    auto str = [](const char* d) { return json{{"type", "string"}, {"description", d}}; };
    auto boolean = [](const char* d) { return json{{"type", "boolean"}, {"description", d}}; };
    auto vec = [](int n, const char* d) {
      return json{
          {"type", "array"}, {"items", {{"type", "number"}}}, {"minItems", n}, {"maxItems", n}, {"description", d}};
    };
    auto colour = [](const char* d) {
      return json{{"type", "array"},
                  {"items", {{"type", "number"}, {"minimum", 0}, {"maximum", 1}}},
                  {"minItems", 3},
                  {"maxItems", 3},
                  {"description", d}};
    };
    auto object = [](json props, json required, const char* d) {
      return json{{"type", "object"},
                  {"properties", std::move(props)},
                  {"required", std::move(required)},
                  {"additionalProperties", false},
                  {"description", d}};
    };
    json material = object(
        {{"name", str("unique name, referenced by surfaces; overrides a built-in of the same name")},
         {"base_color", colour("linear RGB in [0, 1]")},
         {"roughness", json{{"type", "number"}, {"minimum", 0}, {"maximum", 1}}},
         {"texture", json{{"enum", {"none", "plaster", "paint", "wallpaper", "wood", "tiles", "carpet", "concrete"}}}},
         {"texture_scale_m", pos("texture feature size, metres")},
         {"secondary_color", colour("second texture colour (grout, grain), linear RGB")}},
        {"name"}, "a surface material");
    json opening = object(
        {{"kind", json{{"enum", {"door", "window"}}}},
         {"wall", json{{"type", "integer"},
                       {"minimum", 0},
                       {"description", "wall index: wall i runs from polygon[i] to polygon[i+1]"}}},
         {"offset_m", nonneg("distance along the wall from its start to the opening's near edge")},
         {"width_m", pos("clear width")},
         {"height_m", pos("clear height")},
         {"sill_m", nonneg("bottom of the opening above the floor (0 for doors); sill + height <= room height")},
         {"open_deg",
          json{{"type", "number"}, {"minimum", 0}, {"maximum", 180}, {"description", "door leaf angle, 0 = closed"}}},
         {"hinge", json{{"enum", {"left", "right"}}}},
         {"frame_width_m", nonneg("window frame width")},
         {"glass", boolean("window has glass")},
         {"glazed", boolean("door leaf glazed to the floor (patio or French door); default false")},
         {"material", str("material name; empty = built-in door/window material")}},
        {"kind", "wall"}, "a door or window in one wall of its room");
    json room = object({{"name", str("room name")},
                        {"polygon", json{{"type", "array"},
                                         {"minItems", 3},
                                         {"items", vec(2, "[x, y] metres")},
                                         {"description",
                                          "inner wall faces, counter-clockwise seen from above "
                                          "(north = +y, east = +x), first point not repeated"}}},
                        {"height_m", pos("floor to ceiling")},
                        {"wall_thickness_m", pos("wall thickness outwards from the inner face")},
                        {"openings", json{{"type", "array"}, {"items", opening}}},
                        {"wall_material", str("material name")},
                        {"floor_material", str("material name")},
                        {"ceiling_material", str("material name")},
                        {"skirting", boolean("skirting boards along the walls")}},
                       {"polygon"}, "a room");
    json furniture = object({{"name", str("what it is")},
                             {"centre_m", vec(2, "footprint centre [x, y]")},
                             {"yaw_deg", num("rotation about +z, degrees")},
                             {"size_m", vec(3, "[width, depth, height] metres, each > 0")},
                             {"elevation_m", nonneg("bottom above the floor")},
                             {"material", str("material name")}},
                            {"centre_m"}, "a furniture box");
    json light = object({{"kind", json{{"enum", {"area", "point", "sun"}}}},
                         {"position_m", vec(3, "area: centre facing down; point: position")},
                         {"size_m", vec(2, "area light size")},
                         {"color", vec(3, "linear RGB")},
                         {"intensity", pos("relative power")},
                         {"azimuth_deg", num("sun: direction light comes from, from +x towards +y")},
                         {"elevation_deg", num("sun: degrees above the horizon")}},
                        json::array(), "a light");
    json environment = object({{"sky", boolean("sky visible through windows")},
                               {"sky_color", colour("linear RGB")},
                               {"ground_color", colour("linear RGB")},
                               {"exterior_objects", boolean("trees and buildings outside")},
                               {"ambient", json{{"type", "number"}, {"minimum", 0}, {"maximum", 1}}}},
                              json::array(), "outside the room");
    json rig = object({{"width_px", json{{"type", "integer"}, {"minimum", 1}}},
                       {"height_px", json{{"type", "integer"}, {"minimum", 1}}},
                       {"hfov_deg", json{{"type", "number"}, {"exclusiveMinimum", 0}, {"exclusiveMaximum", 180}}},
                       {"fx", pos("focal length, px (overrides hfov_deg)")},
                       {"fy", pos("px")},
                       {"cx", num("px")},
                       {"cy", num("px")},
                       {"baseline_m", pos("distance between the two cameras")}},
                      json::array(), "the stereo rig");
    json viewpoint = object({{"position_m", vec(3, "rig centre [x, y, z], inside a room")},
                             {"yaw_deg", num("0 looks along +y (north), counter-clockwise positive")},
                             {"pitch_deg", num("positive looks up")}},
                            {"position_m"}, "one rig pose");
    json turn = object({{"position_m", vec(3, "rig centre [x, y, z], inside a room")},
                        {"start_deg", num("first yaw")},
                        {"step_deg", pos("yaw step")},
                        {"count", json{{"type", "integer"}, {"minimum", 0}, {"description", "0 = a full turn"}}}},
                       {"position_m"}, "turn-in-place views");
    json schema = object({{"version", json{{"const", 1}}},
                          {"name", str("scene name")},
                          {"seed", json{{"type", "integer"}, {"minimum", 0}}},
                          {"materials", json{{"type", "array"}, {"items", material}}},
                          {"rooms", json{{"type", "array"}, {"minItems", 1}, {"items", room}}},
                          {"furniture", json{{"type", "array"}, {"items", furniture}}},
                          {"lights", json{{"type", "array"}, {"items", light}}},
                          {"environment", environment},
                          {"rig", rig},
                          {"viewpoints", json{{"type", "array"}, {"items", viewpoint}}},
                          {"turn", turn}},
                         {"version", "rooms"},
                         "asbuilt scene: metres and degrees; world +z up, floor z = 0, north = +y, east = +x. "
                         "Built-in materials: wall, floor, ceiling, door, window_frame, glass, furniture, skirting.");
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema";
    schema["title"] = "asbuilt scene";
    schema["properties"]["$schema"] = {{"type", "string"}};
    schema["properties"]["description"] = {{"type", "string"}};
    return schema;
  }();
  return kSchema;
}

}  // namespace asbuilt
