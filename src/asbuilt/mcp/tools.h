#ifndef ASBUILT_MCP_TOOLS_H_
#define ASBUILT_MCP_TOOLS_H_

// The MCP server's tools, independent of the protocol: a session holding one
// scene in memory, a table of tools (name, description, one field list that
// gives both the JSON Schema and the argument parsing), and Call(), which
// never throws for anything a client can send — bad arguments, invalid
// scenes, paths outside the workspace and exceeded limits all come back as
// results with is_error set and a message that names the argument and what
// is allowed. No tool runs code: every tool maps typed arguments onto the
// scene model.

#include <cstddef>
#include <functional>
#include <optional>
#include <stop_token>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/mcp/workspace.h"
#include "asbuilt/scene/scene.h"
#include "asbuilt/util/fields.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::mcp {

// Hardening limits (issue 10): every one gives a clear tool error when hit.
struct ToolLimits {
  int max_rooms = 16;
  int max_polygon_points = 64;  // Corners per room.
  int max_openings = 128;       // Doors + windows, all rooms.
  int max_furniture = 256;
  int max_lights = 32;
  int max_materials = 64;
  int max_views = 72;             // Viewpoints per capture.
  int max_image_width_px = 1920;  // Rendered images (capture, camera preview).
  int max_image_height_px = 1440;
  int max_samples_per_pixel = 256;        // render_capture: an agent's render stays minutes, not hours.
  int max_preview_width_px = 2048;        // Top-down plan picture.
  std::size_t max_text_chars = 4000;      // scene_from_text input.
  std::size_t max_file_bytes = 4u << 20;  // Files load_scene reads.

  // Throws InvalidArgument naming the field ("ToolLimits.max_views = 0, must be > 0").
  void Check() const;
};

// Thrown inside a tool when its request was cancelled or the client left.
class Cancelled : public Error {
 public:
  using Error::Error;
};

// One block of a tool result (MCP content): text, or a base64 image.
struct ToolContent {
  enum class Kind { kText, kImage } kind = Kind::kText;
  std::string text;       // kText.
  std::string data;       // kImage: base64.
  std::string mime_type;  // kImage: "image/png".
};

struct ToolResult {
  std::vector<ToolContent> content;
  bool is_error = false;
  nlohmann::json structured = nullptr;  // structuredContent, when the tool has one.

  static ToolResult Text(std::string text);
  static ToolResult Failure(std::string message);
  nlohmann::json ToJson() const;  // The tools/call result object.
};

// What a call may use besides its arguments.
struct ToolCallContext {
  ProgressCallback progress;  // Long tools report here (→ notifications/progress).
  std::stop_token stop;       // Requested on cancel or disconnect: stop and clean up.
};

// One tool's entry in the table.
struct ToolSpec {
  std::string name;
  std::string title;
  std::string description;
  std::vector<Field> fields;
  bool read_only = false;    // annotations.readOnlyHint
  bool destructive = false;  // annotations.destructiveHint (replaces state or files)

  nlohmann::json ToJson() const;  // The tools/list entry.
};

class SceneTools {
 public:
  SceneTools(Workspace workspace, ToolLimits limits = {});

  const std::vector<ToolSpec>& specs() const { return specs_; }
  const ToolSpec* Find(std::string_view name) const;
  // The tools/list result's "tools" array.
  nlohmann::json ListJson() const;

  // Runs one tool. The tool must exist (Find); bad arguments and every
  // failure a client can cause come back as is_error results.
  ToolResult Call(std::string_view name, const nlohmann::json& arguments, const ToolCallContext& ctx = {});

  const Scene& scene() const { return scene_; }
  const Workspace& workspace() const { return workspace_; }
  const ToolLimits& limits() const { return limits_; }

  // docs/mcp.md's tool reference, generated from the table.
  std::string ToolsMarkdown() const;

 private:
  using Handler = ToolResult (SceneTools::*)(const FieldArgs&, const ToolCallContext&);
  // The table, registered by group, each group with its tools' handlers
  // (tools_build.cc, tools_style_rig.cc, tools_whole_scene.cc, tools_output.cc).
  void RegisterBuildTools();
  void RegisterStyleTools();
  void RegisterRigTools();
  void RegisterWholeSceneTools();
  void RegisterOutputTools();
  void Register(ToolSpec spec, Handler handler);

  ToolResult NewScene(const FieldArgs& a, const ToolCallContext&);
  ToolResult AddRoom(const FieldArgs& a, const ToolCallContext&);
  ToolResult AddDoor(const FieldArgs& a, const ToolCallContext&);
  ToolResult AddWindow(const FieldArgs& a, const ToolCallContext&);
  ToolResult AddOpenings(const FieldArgs& a, OpeningKind kind);
  ToolResult AddFurniture(const FieldArgs& a, const ToolCallContext&);
  ToolResult SetMaterial(const FieldArgs& a, const ToolCallContext&);
  ToolResult SetLighting(const FieldArgs& a, const ToolCallContext&);
  ToolResult PlaceRig(const FieldArgs& a, const ToolCallContext&);
  ToolResult RemoveItem(const FieldArgs& a, const ToolCallContext&);
  ToolResult SceneFromText(const FieldArgs& a, const ToolCallContext&);
  ToolResult RandomSceneTool(const FieldArgs& a, const ToolCallContext&);
  ToolResult RandomHomeTool(const FieldArgs& a, const ToolCallContext&);
  ToolResult Describe(const FieldArgs& a, const ToolCallContext&);
  ToolResult Validate(const FieldArgs& a, const ToolCallContext&);
  ToolResult GetScene(const FieldArgs& a, const ToolCallContext&);
  ToolResult RenderPreview(const FieldArgs& a, const ToolCallContext&);
  ToolResult CameraPreview(const FieldArgs& a);
  ToolResult RenderCapture(const FieldArgs& a, const ToolCallContext& ctx);
  ToolResult ExportPlan(const FieldArgs& a, const ToolCallContext&);
  ToolResult SaveScene(const FieldArgs& a, const ToolCallContext&);
  ToolResult LoadScene(const FieldArgs& a, const ToolCallContext&);

  // Replaces the scene with `next` if that adds no validation problem (and
  // keeps within the limits); otherwise throws InvalidArgument listing the
  // new problems, prefixed by `what` ("the door"). The scene is unchanged.
  void Commit(Scene next, std::string_view what);
  // Throws InvalidArgument when `scene` exceeds a count limit.
  void CheckSceneLimits(const Scene& scene) const;
  // The room index argument, checked against the scene.
  int RoomArg(const FieldArgs& a) const;

  Workspace workspace_;
  ToolLimits limits_;
  Scene scene_;
  std::vector<ToolSpec> specs_;
  std::vector<Handler> handlers_;
};

// Views a scene would render, counted without building them (a scene file
// may ask for billions).
std::size_t CountViews(const Scene& scene);

// Walls of a room as a list an LLM can use: "wall 0: (0.00, 0.00) → (6.00,
// 0.00), 6.00 m, faces south".
std::string DescribeWalls(const Room& room);

}  // namespace asbuilt::mcp

#endif  // ASBUILT_MCP_TOOLS_H_
