#ifndef ASBUILT_MCP_OPTION_FIELDS_H_
#define ASBUILT_MCP_OPTION_FIELDS_H_

// One field list per Options struct (STYLE.md 13) for the operations that a
// CLI command and an MCP tool share:
//
//   Options struct        CLI command      MCP tool
//   SceneTextOptions      scene text       scene_from_text
//   RandomSceneOptions    scene random     random_scene
//   CaptureRenderOptions  render           render_capture
//
// The list builds the tool's JSON Schema and argument parsing (tools.h), the
// command's flags (cli/field_flags.h: `seed` → --seed, `samples_per_pixel` →
// --samples-per-pixel) and both references (docs/mcp.md, --help). Defaults come
// from the Options struct itself. Adding an option is one field in the list
// plus one line in the matching *FromArgs.

#include <vector>

#include "asbuilt/mcp/tool_args.h"
#include "asbuilt/mcp/tools.h"
#include "asbuilt/render/capture_render.h"
#include "asbuilt/scene/procedural.h"
#include "asbuilt/scene/scene_text.h"

namespace asbuilt::mcp {

std::vector<ToolField> SceneTextOptionFields();
SceneTextOptions SceneTextOptionsFromArgs(const ToolArgs& args);

// Includes `seed` (the scene's seed; not part of RandomSceneOptions).
std::vector<ToolField> RandomSceneOptionFields();
RandomSceneOptions RandomSceneOptionsFromArgs(const ToolArgs& args);

// With `limits`, the view count and image size are capped by them (the MCP
// server); without, only by what the renderer accepts (the CLI). `resume`
// stays a CLI flag: a tool always renders a fresh folder.
std::vector<ToolField> CaptureRenderOptionFields(const ToolLimits* limits = nullptr);
CaptureRenderOptions CaptureRenderOptionsFromArgs(const ToolArgs& args);

}  // namespace asbuilt::mcp

#endif  // ASBUILT_MCP_OPTION_FIELDS_H_
