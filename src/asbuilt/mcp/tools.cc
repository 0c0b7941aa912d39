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
