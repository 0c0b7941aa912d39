#include "asbuilt/mcp/tools.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <new>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/mcp/jsonrpc.h"
#include "asbuilt/mcp/plan_preview.h"
#include "asbuilt/render/capture_render.h"
#include "asbuilt/render/renderer.h"
#include "asbuilt/scene/procedural.h"
#include "asbuilt/scene/procedural_home.h"
#include "asbuilt/scene/scene_json.h"
#include "asbuilt/scene/scene_text.h"
#include "asbuilt/util/base64.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"
#include "asbuilt/mcp/tools_common.h"

namespace asbuilt::mcp {

// ------------------------------------------------------------------ shared by the tool files

std::string WithConventions(std::string_view description) {
  return std::string(description) + std::string(kConventions);
}

std::string P2(const Vec2& p) { return fmt::format("({:.2f}, {:.2f})", p.x(), p.y()); }

std::string ProblemText(const Problem& p) {
  return p.field_path.empty() ? p.message : fmt::format("{}: {}", p.field_path, p.message);
}

std::string Bullets(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += "\n- " + l;
  return out;
}

std::vector<Field> Concat(std::vector<Field> own, std::vector<Field> shared) {
  own.insert(own.end(), shared.begin(), shared.end());
  return own;
}

namespace fs = std::filesystem;
namespace {

std::vector<std::string_view> TextureNames() {
  std::vector<std::string_view> out;
  for (TextureKind k : {TextureKind::kNone, TextureKind::kPlaster, TextureKind::kPaint, TextureKind::kWallpaper,
                        TextureKind::kWood, TextureKind::kTiles, TextureKind::kCarpet, TextureKind::kConcrete}) {
    out.push_back(TextureKindName(k));
  }
  return out;
}

// render_capture's options: CaptureRenderOptions' field list with the view
// count and image size capped by the server's limits.
std::vector<Field> CaptureRenderToolFields(const ToolLimits& limits) {
  std::vector<Field> fields = CaptureRenderOptionFields().Fields();
  for (Field& f : fields) {
    if (f.name == "views") f.maximum = limits.max_views;
    if (f.name == "width_px") f.maximum = limits.max_image_width_px;
    if (f.name == "height_px") f.maximum = limits.max_image_height_px;
  }
  return fields;
}

}  // namespace

// ------------------------------------------------------------------ values

void ToolLimits::Check() const {
  auto positive = [](int v, const char* name) {
    CheckArgument(v > 0, fmt::format("ToolLimits.{} = {}, must be > 0", name, v));
  };
  positive(max_rooms, "max_rooms");
  CheckArgument(max_polygon_points >= 3,
                fmt::format("ToolLimits.max_polygon_points = {}, must be >= 3", max_polygon_points));
  positive(max_openings, "max_openings");
  positive(max_furniture, "max_furniture");
  positive(max_lights, "max_lights");
  positive(max_materials, "max_materials");
  positive(max_views, "max_views");
  CheckArgument(max_image_width_px >= 16,
                fmt::format("ToolLimits.max_image_width_px = {}, must be >= 16", max_image_width_px));
  CheckArgument(max_image_height_px >= 16,
                fmt::format("ToolLimits.max_image_height_px = {}, must be >= 16", max_image_height_px));
  CheckArgument(max_preview_width_px >= 64 && max_preview_width_px <= 4096,
                fmt::format("ToolLimits.max_preview_width_px = {}, must be in 64..4096", max_preview_width_px));
  CheckArgument(max_text_chars > 0, "ToolLimits.max_text_chars = 0, must be > 0");
  CheckArgument(max_file_bytes > 0, "ToolLimits.max_file_bytes = 0, must be > 0");
}

ToolResult ToolResult::Text(std::string text) {
  ToolResult r;
  r.content.push_back({.kind = ToolContent::Kind::kText, .text = std::move(text)});
  return r;
}

ToolResult ToolResult::Failure(std::string message) {
  ToolResult r = Text(std::move(message));
  r.is_error = true;
  return r;
}

nlohmann::json ToolResult::ToJson() const {
  nlohmann::json blocks = nlohmann::json::array();
  for (const ToolContent& c : content) {
    if (c.kind == ToolContent::Kind::kText) {
      blocks.push_back({{"type", "text"}, {"text", c.text}});
    } else {
      blocks.push_back({{"type", "image"}, {"data", c.data}, {"mimeType", c.mime_type}});
    }
  }
  nlohmann::json out = {{"content", blocks}, {"isError", is_error}};
  if (!structured.is_null()) out["structuredContent"] = structured;
  return out;
}

nlohmann::json ToolSpec::ToJson() const {
  return {
      {"name", name},
      {"title", title},
      {"description", description},
      {"inputSchema", FieldsSchema(fields)},
      {"annotations",
       {{"title", title}, {"readOnlyHint", read_only}, {"destructiveHint", destructive}, {"openWorldHint", false}}}};
}

std::size_t CountViews(const Scene& scene) {
  double n = static_cast<double>(scene.viewpoints.size());
  if (scene.turn && scene.turn->step_deg > 0) {
    const TurnInPlace& t = *scene.turn;
    n += t.count > 0 ? t.count : std::max(1.0, std::floor(360.0 / t.step_deg + 1e-9));
  }
  return n >= 1e15 ? static_cast<std::size_t>(1e15) : static_cast<std::size_t>(n);
}

std::string DescribeWalls(const Room& room) {
  std::string out;
  for (int w = 0; w < WallCount(room); ++w) {
    if (!out.empty()) out += "\n";
    std::vector<std::string> on_wall;
    for (const Opening& o : room.openings) {
      if (o.wall == w) {
        on_wall.push_back(
            fmt::format("{} {:.2f} m at offset {:.2f} m", OpeningKindName(o.kind), o.width_m, o.offset_m));
      }
    }
    out += fmt::format("  wall {}: {} → {}, {:.2f} m, faces {}{}", w, P2(WallStart(room, w)), P2(WallEnd(room, w)),
                       WallLength(room, w), WallCompassName(room, w),
                       on_wall.empty() ? "" : fmt::format(" ({})", fmt::join(on_wall, "; ")));
  }
  return out;
}

// ------------------------------------------------------------------ table

SceneTools::SceneTools(Workspace workspace, ToolLimits limits) : workspace_(std::move(workspace)), limits_(limits) {
  limits_.Check();
  // In tools/list order.
  RegisterBuildTools();
  RegisterStyleTools();
  RegisterRigTools();
  RegisterWholeSceneTools();
  RegisterOutputTools();
}

// set_material, set_lighting.
void SceneTools::RegisterStyleTools() {
  const ToolLimits& L = limits_;
  ToolSpec s;
  s = {.name = "set_material",
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
  Register(s, &SceneTools::SetMaterial);

  s = {.name = "set_lighting",
       .title = "Set lighting",
       .description =
           "Set the lights: replace all lights with one (mode replace) or add one "
           "(mode add): a ceiling area light, a point light or the sun; and the "
           "ambient level and sky. kind none with mode replace removes all lights." +
           std::string(kConventions),
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
  Register(s, &SceneTools::SetLighting);
}

// place_rig, remove_item.
void SceneTools::RegisterRigTools() {
  const ToolLimits& L = limits_;
  ToolSpec s;
  s = {.name = "place_rig",
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
  Register(s, &SceneTools::PlaceRig);

  s = {.name = "remove_item",
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
  Register(s, &SceneTools::RemoveItem);
}

// scene_from_text, random_scene, describe_scene, validate_scene, get_scene,
// render_preview.
void SceneTools::RegisterWholeSceneTools() {
  const ToolLimits& L = limits_;
  ToolSpec s;
  s = {.name = "scene_from_text",
       .title = "Scene from text",
       .description =
           fmt::format("Build a whole scene from an English description with the built-in parser (no "
                       "network), replacing the current scene, e.g. \"a 6 by 8 m classroom, 3 m high, a 1 m "
                       "door on the east wall and two 1.5 m windows on the north wall\". The reply says which "
                       "words were not used. At most {} characters.",
                       L.max_text_chars),
       .fields = Concat({{.name = "text",
                          .kind = FieldKind::kString,
                          .description = "The description.",
                          .required = true,
                          .max_length = L.max_text_chars}},
                        SceneTextOptionFields().Fields()),
       .destructive = true};
  Register(s, &SceneTools::SceneFromText);

  s = {.name = "random_scene",
       .title = "Random scene",
       .description =
           "Replace the current scene with a procedural room (the generator of "
           "`asbuilt scene random`): rectangular, L-shaped or rotated, 1-4 doors and "
           "windows, furniture, random materials and lights, a turn-in-place rig. "
           "Deterministic per seed.",
       .fields = Concat({RandomSceneSeedField()}, RandomSceneOptionFields().Fields()),
       .destructive = true};
  Register(s, &SceneTools::RandomSceneTool);

  s = {.name = "random_home",
       .title = "Random home",
       .description =
           "Replace the current scene with a procedural home of several rooms (the generator of "
           "`asbuilt scene home`): a floor cut into rectangular rooms, 0.10 m partitions, a door "
           "between rooms that share a partition, windows on exterior walls. Render it room by room "
           "with `asbuilt render SCENE --home` for a home.json. Deterministic per seed.",
       .fields = {RandomSceneSeedField(),
                  {.name = "rooms",
                   .kind = FieldKind::kInteger,
                   .description = "Number of rooms (0: 5 to 10).",
                   .minimum = 0.0,
                   .maximum = std::min(10.0, static_cast<double>(L.max_rooms)),
                   .default_value = 0}},
       .destructive = true};
  Register(s, &SceneTools::RandomHomeTool);

  s = {.name = "describe_scene",
       .title = "Describe scene",
       .description =
           "Plain-language summary of the current scene (rooms, walls with numbers "
           "and directions, openings, furniture, lights, rig) and warnings.",
       .fields = {},
       .read_only = true};
  Register(s, &SceneTools::Describe);

  s = {.name = "validate_scene",
       .title = "Validate scene",
       .description =
           "Check the current scene and list every problem with its field path "
           "(open or crossing polygons, openings off their wall or overlapping, sills "
           "too high, rig outside the room, unknown materials…).",
       .fields = {},
       .read_only = true};
  Register(s, &SceneTools::Validate);

  s = {.name = "get_scene",
       .title = "Get scene JSON",
       .description = "The current scene as scene JSON (the format save_scene writes).",
       .fields = {},
       .read_only = true};
  Register(s, &SceneTools::GetScene);

  s = {.name = "render_preview",
       .title = "Render preview",
       .description = fmt::format("A PNG picture of the scene: view plan (default) draws it from above with walls, "
                                  "doors, windows, furniture, lights, the rig and wall numbers; view camera renders "
                                  "what the left camera of viewpoint view_index sees. Width at most {} px (plan) or "
                                  "{} px (camera).",
                                  L.max_preview_width_px, L.max_image_width_px),
       .fields =
           {
               {.name = "view",
                .kind = FieldKind::kEnum,
                .description = "plan (top-down) or camera.",
                .choices = {"plan", "camera"},
                .default_value = "plan"},
               {.name = "width_px",
                .kind = FieldKind::kInteger,
                .description = "Image width.",
                .minimum = 64.0,
                .maximum = static_cast<double>(L.max_preview_width_px),
                .default_value = 768},
               {.name = "view_index",
                .kind = FieldKind::kInteger,
                .description = "Camera view: which viewpoint (place_rig).",
                .minimum = 0.0,
                .maximum = L.max_views - 1.0,
                .default_value = 0},
           },
       .read_only = true};
  Register(s, &SceneTools::RenderPreview);
}

// render_capture, export_plan, save_scene, load_scene.
void SceneTools::RegisterOutputTools() {
  const ToolLimits& L = limits_;
  const Field path_field_required = {.name = "path", .kind = FieldKind::kString, .required = true, .max_length = 512};
  ToolSpec s;
  s = {.name = "render_capture",
       .title = "Render capture",
       .description = fmt::format("Render a labelled stereo capture of every viewpoint (left/right images, labels, "
                                  "depth, capture.json, truth.json) into a folder of the workspace. Long: sends "
                                  "progress notifications when the request has a progressToken. The folder appears "
                                  "only when complete. At most {} views.",
                                  L.max_views),
       .fields = Concat({{.name = "output",
                          .kind = FieldKind::kString,
                          .description = "Folder to create, relative to the workspace (e.g. \"captures/a\").",
                          .required = true,
                          .max_length = 512},
                         {.name = "overwrite",
                          .kind = FieldKind::kBool,
                          .description = "Replace the folder if it exists.",
                          .default_value = false}},
                        CaptureRenderToolFields(L))};
  Register(s, &SceneTools::RenderCapture);

  s = {.name = "export_plan",
       .title = "Export plan",
       .description =
           "The exact floor plan of the scene as plan JSON (version, units, walls "
           "as inner-face lines, openings with width/height/sill on their wall, "
           "rooms with area); with path, also written into the workspace.",
       .fields = {{.name = "path",
                   .kind = FieldKind::kString,
                   .description = "Optional file to write, ending in .json (e.g. "
                                  "\"plans/truth.json\").",
                   .max_length = 512}},
       .read_only = false};
  Register(s, &SceneTools::ExportPlan);

  Field save_path = path_field_required;
  save_path.description = "File to write, relative to the workspace, ending in .json.";
  s = {.name = "save_scene",
       .title = "Save scene",
       .description =
           "Write the current scene as scene JSON into the workspace (replacing the "
           "file if it exists).",
       .fields = {save_path}};
  Register(s, &SceneTools::SaveScene);

  Field load_path = path_field_required;
  load_path.description = "Scene JSON file relative to the workspace.";
  s = {.name = "load_scene",
       .title = "Load scene",
       .description = fmt::format("Replace the current scene with a scene JSON file from the "
                                  "workspace (validated; at most {} bytes).",
                                  L.max_file_bytes),
       .fields = {load_path},
       .destructive = true};
  Register(s, &SceneTools::LoadScene);
}

void SceneTools::Register(ToolSpec spec, Handler handler) {
  specs_.push_back(std::move(spec));
  handlers_.push_back(handler);
}

const ToolSpec* SceneTools::Find(std::string_view name) const {
  for (const ToolSpec& s : specs_) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

nlohmann::json SceneTools::ListJson() const {
  nlohmann::json tools = nlohmann::json::array();
  for (const ToolSpec& s : specs_) tools.push_back(s.ToJson());
  return tools;
}

std::string SceneTools::ToolsMarkdown() const {
  std::string out;
  for (const ToolSpec& s : specs_) {
    // The conventions are documented once in docs/mcp.md, not per tool.
    std::string description = s.description;
    if (auto at = description.find(kConventions); at != std::string::npos) {
      description.erase(at, kConventions.size());
    }
    out += fmt::format("### `{}` — {}\n\n{}\n\n{}\n", s.name, s.title, description, FieldsMarkdown(s.fields));
  }
  return out;
}

ToolResult SceneTools::Call(std::string_view name, const nlohmann::json& arguments, const ToolCallContext& ctx) {
  std::size_t index = 0;
  while (index < specs_.size() && specs_[index].name != name) ++index;
  if (index == specs_.size()) {
    return ToolResult::Failure(fmt::format("unknown tool \"{}\"", name));
  }
  const ToolSpec& spec = specs_[index];
  try {
    FieldArgs args = ParseFieldArgs(spec.fields, arguments);
    return (this->*handlers_[index])(args, ctx);
  } catch (const Cancelled& e) {
    return ToolResult::Failure(e.what());
  } catch (const FieldArgsError& e) {
    return ToolResult::Failure(
        fmt::format("{}: invalid arguments (nothing was changed):{}", spec.name, Bullets(e.problems())));
  } catch (const InputError& e) {
    std::vector<std::string> lines;
    for (const Problem& p : e.problems()) lines.push_back(p.ToString());
    return ToolResult::Failure(fmt::format("{}: {}", spec.name, Bullets(lines).substr(1)));
  } catch (const Error& e) {
    return ToolResult::Failure(fmt::format("{}: {}", spec.name, e.what()));
  } catch (const std::bad_alloc&) {
    return ToolResult::Failure(fmt::format("{}: out of memory; use smaller sizes", spec.name));
  } catch (const std::exception& e) {
    spdlog::error("mcp: tool {} failed: {}", spec.name, e.what());
    return ToolResult::Failure(fmt::format("{}: internal error: {}", spec.name, e.what()));
  }
}

// ------------------------------------------------------------------ helpers

void SceneTools::CheckSceneLimits(const Scene& s) const {
  const ToolLimits& L = limits_;
  std::vector<std::string> over;
  auto limit = [&](std::size_t n, int max, std::string_view what) {
    if (n > static_cast<std::size_t>(max)) {
      over.push_back(fmt::format("{} {}; the limit is {}", n, what, max));
    }
  };
  limit(s.rooms.size(), L.max_rooms, "rooms");
  std::size_t openings = 0;
  for (std::size_t r = 0; r < s.rooms.size(); ++r) {
    openings += s.rooms[r].openings.size();
    if (s.rooms[r].polygon.size() > static_cast<std::size_t>(L.max_polygon_points)) {
      over.push_back(
          fmt::format("rooms[{}] has {} corners; the limit is {}", r, s.rooms[r].polygon.size(), L.max_polygon_points));
    }
  }
  limit(openings, L.max_openings, "doors and windows");
  limit(s.furniture.size(), L.max_furniture, "pieces of furniture");
  limit(s.lights.size(), L.max_lights, "lights");
  limit(s.materials.size(), L.max_materials, "materials");
  std::size_t views = CountViews(s);
  if (views > static_cast<std::size_t>(L.max_views)) {
    over.push_back(fmt::format("{} views; the limit is {} (use a larger step_deg or a count)", views, L.max_views));
  }
  if (s.rig.width_px > L.max_image_width_px || s.rig.height_px > L.max_image_height_px) {
    over.push_back(fmt::format("images of {}×{} px; the limit is {}×{}", s.rig.width_px, s.rig.height_px,
                               L.max_image_width_px, L.max_image_height_px));
  }
  if (!over.empty()) {
    throw InvalidArgument(fmt::format("scene too large (server limits):{}", Bullets(over)));
  }
}

void SceneTools::Commit(Scene next, std::string_view what) {
  CheckSceneLimits(next);
  std::map<std::string, int> before;
  for (const Problem& p : ValidateScene(scene_)) ++before[ProblemText(p)];
  std::vector<std::string> added;
  for (const Problem& p : ValidateScene(next)) {
    auto it = before.find(ProblemText(p));
    if (it != before.end() && it->second > 0) {
      --it->second;
    } else {
      added.push_back(ProblemText(p));
    }
  }
  if (!added.empty()) {
    throw InvalidArgument(
        fmt::format("{} would make the scene invalid, so nothing was changed:{}", what, Bullets(added)));
  }
  scene_ = std::move(next);
}

int SceneTools::RoomArg(const FieldArgs& a) const {
  if (scene_.rooms.empty()) throw InvalidArgument("the scene has no room yet: call add_room first");
  std::int64_t r = a.Integer("room");
  if (r >= static_cast<std::int64_t>(scene_.rooms.size())) {
    throw InvalidArgument(fmt::format("arguments.room: the scene has rooms 0..{}, got {}", scene_.rooms.size() - 1, r));
  }
  return static_cast<int>(r);
}

// ------------------------------------------------------------------ tools

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

ToolResult SceneTools::SceneFromText(const FieldArgs& a, const ToolCallContext&) {
  SceneTextResult result = ::asbuilt::SceneFromText(a.String("text"), SceneTextOptionFields().FromArgs(a));
  CheckSceneLimits(result.scene);
  scene_ = std::move(result.scene);
  std::string out = fmt::format("New scene from the text: {}", DescribeScene(scene_));
  for (std::size_t r = 0; r < scene_.rooms.size(); ++r) {
    out += fmt::format("\nRoom {} walls:\n{}", r, DescribeWalls(scene_.rooms[r]));
  }
  if (!result.assumptions.empty()) out += "\nAssumed:" + Bullets(result.assumptions);
  if (!result.unused_words.empty()) {
    out += fmt::format(
        "\nWords not understood (not used): {}. Adjust the scene with the other "
        "tools if they mattered.",
        fmt::join(result.unused_words, ", "));
  }
  return ToolResult::Text(out);
}

ToolResult SceneTools::RandomSceneTool(const FieldArgs& a, const ToolCallContext&) {
  Scene next = RandomScene(RandomSceneOptionFields().FromArgs(a), static_cast<std::uint64_t>(a.Integer("seed")));
  CheckSceneLimits(next);
  scene_ = std::move(next);
  std::string out = fmt::format("New random scene: {}", DescribeScene(scene_));
  for (std::size_t r = 0; r < scene_.rooms.size(); ++r) {
    out += fmt::format("\nRoom {} walls:\n{}", r, DescribeWalls(scene_.rooms[r]));
  }
  return ToolResult::Text(out);
}

ToolResult SceneTools::RandomHomeTool(const FieldArgs& a, const ToolCallContext&) {
  HomeLayoutOptions layout;
  if (const int rooms = static_cast<int>(a.Integer("rooms")); rooms > 0) layout.min_rooms = layout.max_rooms = rooms;
  const auto seed = static_cast<std::uint64_t>(a.Integer("seed"));
  SceneRng rng(seed);
  Scene next = HomeScene(MakeHomeLayout(rng, layout), seed);
  CheckSceneLimits(next);
  scene_ = std::move(next);
  std::string out = fmt::format("New random home: {}", DescribeScene(scene_));
  for (std::size_t r = 0; r < scene_.rooms.size(); ++r) {
    out += fmt::format("\nRoom {} walls:\n{}", r, DescribeWalls(scene_.rooms[r]));
  }
  return ToolResult::Text(out);
}

ToolResult SceneTools::Describe(const FieldArgs&, const ToolCallContext&) {
  std::string out = DescribeScene(scene_);
  for (std::size_t r = 0; r < scene_.rooms.size(); ++r) {
    out += fmt::format("\nRoom {} walls:\n{}", r, DescribeWalls(scene_.rooms[r]));
  }
  for (std::size_t i = 0; i < scene_.furniture.size(); ++i) {
    const Furniture& f = scene_.furniture[i];
    out += fmt::format("\nFurniture {}: {} at {}, {:.2f} × {:.2f} × {:.2f} m", i, f.name, P2(f.centre_m), f.size_m.x(),
                       f.size_m.y(), f.size_m.z());
  }
  std::vector<std::string> warnings;
  for (const Problem& p : ValidateScene(scene_)) warnings.push_back(ProblemText(p));
  if (CountViews(scene_) == 0) warnings.push_back("no rig views yet: call place_rig");
  if (scene_.lights.empty()) warnings.push_back("no lights: only ambient and sky light (set_lighting)");
  std::size_t openings = 0;
  for (const Room& r : scene_.rooms) openings += r.openings.size();
  if (!scene_.rooms.empty() && openings == 0) warnings.push_back("no doors or windows");
  if (!warnings.empty()) out += "\nWarnings:" + Bullets(warnings);
  return ToolResult::Text(out);
}

ToolResult SceneTools::Validate(const FieldArgs&, const ToolCallContext&) {
  std::vector<Problem> problems = ValidateScene(scene_);
  nlohmann::json list = nlohmann::json::array();
  std::vector<std::string> lines;
  for (const Problem& p : problems) {
    list.push_back({{"path", p.field_path}, {"message", p.message}});
    lines.push_back(ProblemText(p));
  }
  ToolResult r = ToolResult::Text(problems.empty() ? "The scene is valid."
                                                   : fmt::format("The scene has {} problem{}:{}", problems.size(),
                                                                 problems.size() == 1 ? "" : "s", Bullets(lines)));
  r.structured = {{"valid", problems.empty()}, {"problems", list}};
  return r;
}

ToolResult SceneTools::GetScene(const FieldArgs&, const ToolCallContext&) {
  return ToolResult::Text(SceneToJson(scene_).dump(2));
}

ToolResult SceneTools::RenderPreview(const FieldArgs& a, const ToolCallContext&) {
  if (a.String("view") == "camera") return CameraPreview(a);
  PlanPreviewOptions options{.width_px = static_cast<int>(a.Integer("width_px"))};
  options.max_height_px = std::max(options.width_px * 2, 256);
  options.margin_px = std::min(48, options.width_px / 8);
  std::string png = RenderPlanPreviewPng(scene_, options);
  ToolResult r = ToolResult::Text(fmt::format("Top-down plan of \"{}\" ({} bytes PNG).", scene_.name, png.size()));
  r.content.insert(r.content.begin(),
                   ToolContent{.kind = ToolContent::Kind::kImage, .data = Base64Encode(png), .mime_type = "image/png"});
  return r;
}

ToolResult SceneTools::RenderCapture(const FieldArgs& a, const ToolCallContext& ctx) {
  const std::string output = a.String("output");
  const bool overwrite = a.Bool("overwrite");
  fs::path final_dir = workspace_.Resolve(output, "arguments.output");
  std::error_code ec;
  if (fs::exists(fs::symlink_status(final_dir, ec)) && !overwrite) {
    throw InvalidArgument(
        fmt::format("arguments.output: \"{}\" already exists; choose another name or pass overwrite: true", output));
  }
  std::vector<Problem> problems = ValidateScene(scene_);
  if (!problems.empty()) {
    std::vector<std::string> lines;
    for (const Problem& p : problems) lines.push_back(ProblemText(p));
    throw InvalidArgument(fmt::format("the scene is not valid yet, fix these first:{}", Bullets(lines)));
  }
  CheckSceneLimits(scene_);
  if (CountViews(scene_) == 0) {
    throw InvalidArgument("the scene has no views to render: call place_rig first");
  }
  CaptureRenderOptions options = CaptureRenderOptionFields().FromArgs(a);
  options.resume = false;
  options.Check();

  // Render into a hidden temp folder; it becomes `output` only when complete,
  // and is removed if anything stops the render (error, cancel, disconnect).
  TempOutputDir temp(workspace_, final_dir);
  auto progress = [&ctx](const ProgressUpdate& u) {
    if (ctx.stop.stop_requested()) throw Cancelled("render_capture cancelled; nothing was written");
    ReportProgress(ctx.progress, u);
  };
  progress({"render", 0, static_cast<std::int64_t>(CountViews(scene_)), ""});
  CaptureRenderSummary summary = ::asbuilt::RenderCapture(scene_, temp.path(), options, progress);
  if (ctx.stop.stop_requested()) throw Cancelled("render_capture cancelled; nothing was written");
  WriteScene(scene_, temp.path() / "scene.json");
  temp.Commit(overwrite);
  return ToolResult::Text(
      fmt::format("Rendered {} view{} in {:.1f} s into {}/: capture.json, truth.json, scene.json, left/, "
                  "right/, labels/ (0 background, 1 wall, 2 door, 3 window), depth/ (uint16 mm), idmap/.",
                  summary.views, summary.views == 1 ? "" : "s", summary.seconds, workspace_.Display(final_dir)));
}

ToolResult SceneTools::CameraPreview(const FieldArgs& a) {
  std::vector<Problem> problems = ValidateScene(scene_);
  if (!problems.empty()) {
    std::vector<std::string> lines;
    for (const Problem& p : problems) lines.push_back(ProblemText(p));
    throw InvalidArgument(fmt::format("the scene is not valid yet, fix these first:{}", Bullets(lines)));
  }
  CheckSceneLimits(scene_);
  std::vector<Viewpoint> views = ResolveViewpoints(scene_);
  if (views.empty()) throw InvalidArgument("the scene has no views yet: call place_rig first");
  const std::int64_t index = a.Integer("view_index");
  if (index >= static_cast<std::int64_t>(views.size())) {
    throw InvalidArgument(
        fmt::format("arguments.view_index: the scene has views 0..{}, got {}", views.size() - 1, index));
  }
  const int width = static_cast<int>(a.Integer("width_px"));
  if (width > limits_.max_image_width_px) {
    throw InvalidArgument(fmt::format("arguments.width_px: camera views are at most {} px wide, got {}",
                                      limits_.max_image_width_px, width));
  }
  // The rig's camera scaled to the asked width (same field of view).
  PinholeCamera rig = scene_.rig.Camera();
  const double s = static_cast<double>(width) / rig.width_px;
  PinholeCamera cam = rig;
  cam.width_px = width;
  cam.height_px = std::clamp(static_cast<int>(std::lround(rig.height_px * s)), 16, limits_.max_image_height_px);
  cam.fx = rig.fx * s;
  cam.fy = rig.fy * s;
  cam.cx = (rig.cx + 0.5) * s - 0.5;
  cam.cy = (rig.cy + 0.5) * s - 0.5;
  RenderOptions options{.samples_per_pixel = 2, .camera_effects = 0.0, .seed = scene_.seed};
  SceneRenderer renderer(scene_);
  RenderedView view = renderer.Render({cam, views[index], scene_.rig.baseline_m}, options,
                                      static_cast<std::uint64_t>(index), /*right_eye=*/false);
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", AsMat(view.left), png)) throw Error("PNG encoding failed");
  ToolResult r =
      ToolResult::Text(fmt::format("Left camera of view {} (position ({:.2f}, {:.2f}, {:.2f}), yaw {:g}°), {}×{} px.",
                                   index, views[index].position_m.x(), views[index].position_m.y(),
                                   views[index].position_m.z(), views[index].yaw_deg, cam.width_px, cam.height_px));
  r.content.insert(r.content.begin(), ToolContent{.kind = ToolContent::Kind::kImage,
                                                  .data = Base64Encode(std::string(png.begin(), png.end())),
                                                  .mime_type = "image/png"});
  return r;
}

ToolResult SceneTools::ExportPlan(const FieldArgs& a, const ToolCallContext&) {
  std::vector<Problem> problems = ValidateScene(scene_);
  if (!problems.empty()) {
    std::vector<std::string> lines;
    for (const Problem& p : problems) lines.push_back(ProblemText(p));
    throw InvalidArgument(fmt::format("the scene is not valid yet, fix these first:{}", Bullets(lines)));
  }
  Plan plan = SceneTruth(scene_);
  nlohmann::json json = PlanToJson(plan);
  ToolResult r = ToolResult::Text(json.dump(2));
  r.structured = json;
  if (auto path = a.OptString("path")) {
    if (!path->ends_with(".json")) {
      throw InvalidArgument(fmt::format("arguments.path: \"{}\" must end in .json", *path));
    }
    fs::path target = workspace_.Resolve(*path, "arguments.path");
    WritePlan(plan, target);
    r.content.push_back({.text = fmt::format("Wrote {}.", workspace_.Display(target))});
  }
  return r;
}

ToolResult SceneTools::SaveScene(const FieldArgs& a, const ToolCallContext&) {
  std::string path = a.String("path");
  if (!path.ends_with(".json")) {
    throw InvalidArgument(fmt::format("arguments.path: \"{}\" must end in .json", path));
  }
  fs::path target = workspace_.Resolve(path, "arguments.path");
  bool existed = fs::exists(target);
  WriteScene(scene_, target);
  std::size_t problems = ValidateScene(scene_).size();
  return ToolResult::Text(
      fmt::format("{} {}{}.", existed ? "Replaced" : "Wrote", workspace_.Display(target),
                  problems ? fmt::format(" (the scene has {} validation problem{}; validate_scene lists them)",
                                         problems, problems == 1 ? "" : "s")
                           : ""));
}

ToolResult SceneTools::LoadScene(const FieldArgs& a, const ToolCallContext&) {
  std::string path = a.String("path");
  fs::path source = workspace_.Resolve(path, "arguments.path");
  std::error_code ec;
  if (!fs::is_regular_file(source, ec)) {
    throw InvalidArgument(fmt::format("arguments.path: \"{}\" is not a file in the workspace", path));
  }
  auto size = fs::file_size(source, ec);
  if (ec || size > limits_.max_file_bytes) {
    throw InvalidArgument(
        fmt::format("arguments.path: \"{}\" is {} bytes; the limit is {}", path, size, limits_.max_file_bytes));
  }
  std::string text = ReadFile(source);
  JsonDiagnostics diag(path);
  if (JsonNestingDepth(text) > 64) {
    throw InvalidArgument(fmt::format("{}: nested too deeply to be a scene file", path));
  }
  nlohmann::json json = ParseJsonText(text, diag);
  diag.ThrowIfErrors();
  Scene loaded = SceneFromJson(json, path);
  CheckSceneLimits(loaded);
  scene_ = std::move(loaded);
  return ToolResult::Text(fmt::format("Loaded {}: {}", path, DescribeScene(scene_)));
}

}  // namespace asbuilt::mcp
