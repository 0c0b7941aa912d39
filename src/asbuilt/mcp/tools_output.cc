#include "asbuilt/mcp/tools.h"

#include <filesystem>

#include <fmt/format.h>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/mcp/jsonrpc.h"
#include "asbuilt/mcp/tools_common.h"
#include "asbuilt/render/capture_render.h"
#include "asbuilt/scene/scene_json.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"

// The tools that write or read files of the workspace (render_capture,
// export_plan, save_scene, load_scene), each tool's schema beside its
// handler.

namespace asbuilt::mcp {
namespace fs = std::filesystem;

namespace {

// render_capture's options: CaptureRenderOptions' field list with the view
// count, image size and samples capped by the server's limits.
std::vector<Field> CaptureRenderToolFields(const ToolLimits& limits) {
  std::vector<Field> fields = CaptureRenderOptionFields().Fields();
  for (Field& f : fields) {
    if (f.name == "views") f.maximum = limits.max_views;
    if (f.name == "width_px") f.maximum = limits.max_image_width_px;
    if (f.name == "height_px") f.maximum = limits.max_image_height_px;
    if (f.name == "samples_per_pixel") f.maximum = limits.max_samples_per_pixel;
  }
  return fields;
}

ToolSpec RenderCaptureSpec(const ToolLimits& L) {
  return {.name = "render_capture",
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
}

}  // namespace

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

namespace {

ToolSpec ExportPlanSpec() {
  return {.name = "export_plan",
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
}

}  // namespace

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

namespace {

// A required path argument, relative to the workspace.
Field PathField(std::string_view description) {
  return {.name = "path", .kind = FieldKind::kString, .description = description, .required = true, .max_length = 512};
}

ToolSpec SaveSceneSpec() {
  return {.name = "save_scene",
          .title = "Save scene",
          .description =
              "Write the current scene as scene JSON into the workspace (replacing the "
              "file if it exists).",
          .fields = {PathField("File to write, relative to the workspace, ending in .json.")}};
}

}  // namespace

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

namespace {

ToolSpec LoadSceneSpec(const ToolLimits& L) {
  return {.name = "load_scene",
          .title = "Load scene",
          .description = fmt::format("Replace the current scene with a scene JSON file from the "
                                     "workspace (validated; at most {} bytes).",
                                     L.max_file_bytes),
          .fields = {PathField("Scene JSON file relative to the workspace.")},
          .destructive = true};
}

}  // namespace

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

// In tools/list order.
void SceneTools::RegisterOutputTools() {
  Register(RenderCaptureSpec(limits_), &SceneTools::RenderCapture);
  Register(ExportPlanSpec(), &SceneTools::ExportPlan);
  Register(SaveSceneSpec(), &SceneTools::SaveScene);
  Register(LoadSceneSpec(limits_), &SceneTools::LoadScene);
}

}  // namespace asbuilt::mcp
