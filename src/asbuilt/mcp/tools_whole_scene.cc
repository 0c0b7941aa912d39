#include "asbuilt/mcp/tools.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/mcp/plan_preview.h"
#include "asbuilt/mcp/tools_common.h"
#include "asbuilt/render/renderer.h"
#include "asbuilt/scene/procedural.h"
#include "asbuilt/scene/procedural_home.h"
#include "asbuilt/scene/scene_json.h"
#include "asbuilt/scene/scene_text.h"
#include "asbuilt/util/base64.h"
#include "asbuilt/util/error.h"

// The tools on the whole scene: make one (scene_from_text, random_scene,
// random_home), look at it (describe_scene, validate_scene, get_scene,
// render_preview); each tool's schema beside its handler.

namespace asbuilt::mcp {

namespace {

ToolSpec SceneFromTextSpec(const ToolLimits& L) {
  return {.name = "scene_from_text",
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
}

}  // namespace

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

namespace {

ToolSpec RandomSceneSpec() {
  return {.name = "random_scene",
          .title = "Random scene",
          .description =
              "Replace the current scene with a procedural room (the generator of "
              "`asbuilt scene random`): rectangular, L-shaped or rotated, 1-4 doors and "
              "windows, furniture, random materials and lights, a turn-in-place rig. "
              "Deterministic per seed.",
          .fields = Concat({RandomSceneSeedField()}, RandomSceneOptionFields().Fields()),
          .destructive = true};
}

}  // namespace

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

namespace {

ToolSpec RandomHomeSpec(const ToolLimits& L) {
  return {.name = "random_home",
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
}

}  // namespace

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

namespace {

ToolSpec DescribeSceneSpec() {
  return {.name = "describe_scene",
          .title = "Describe scene",
          .description =
              "Plain-language summary of the current scene (rooms, walls with numbers "
              "and directions, openings, furniture, lights, rig) and warnings.",
          .fields = {},
          .read_only = true};
}

}  // namespace

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

namespace {

ToolSpec ValidateSceneSpec() {
  return {.name = "validate_scene",
          .title = "Validate scene",
          .description =
              "Check the current scene and list every problem with its field path "
              "(open or crossing polygons, openings off their wall or overlapping, sills "
              "too high, rig outside the room, unknown materials…).",
          .fields = {},
          .read_only = true};
}

}  // namespace

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

namespace {

ToolSpec GetSceneSpec() {
  return {.name = "get_scene",
          .title = "Get scene JSON",
          .description = "The current scene as scene JSON (the format save_scene writes).",
          .fields = {},
          .read_only = true};
}

}  // namespace

ToolResult SceneTools::GetScene(const FieldArgs&, const ToolCallContext&) {
  return ToolResult::Text(SceneToJson(scene_).dump(2));
}

namespace {

ToolSpec RenderPreviewSpec(const ToolLimits& L) {
  return {.name = "render_preview",
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
}

}  // namespace

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

// In tools/list order.
void SceneTools::RegisterWholeSceneTools() {
  Register(SceneFromTextSpec(limits_), &SceneTools::SceneFromText);
  Register(RandomSceneSpec(), &SceneTools::RandomSceneTool);
  Register(RandomHomeSpec(limits_), &SceneTools::RandomHomeTool);
  Register(DescribeSceneSpec(), &SceneTools::Describe);
  Register(ValidateSceneSpec(), &SceneTools::Validate);
  Register(GetSceneSpec(), &SceneTools::GetScene);
  Register(RenderPreviewSpec(limits_), &SceneTools::RenderPreview);
}

}  // namespace asbuilt::mcp
