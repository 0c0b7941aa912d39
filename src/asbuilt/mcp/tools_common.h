#ifndef ASBUILT_MCP_TOOLS_COMMON_H_
#define ASBUILT_MCP_TOOLS_COMMON_H_

// What the tool files share (internal to mcp/; the API is mcp/tools.h): the
// coordinate conventions, pieces of reply text and field lists.

#include <string>
#include <string_view>
#include <vector>

#include "asbuilt/scene/scene.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/fields.h"

namespace asbuilt::mcp {

// Ends the description of every tool that takes coordinates; docs/mcp.md
// states it once instead (SceneTools::ToolsMarkdown leaves it out).
inline constexpr std::string_view kConventions =
    " Units are metres and degrees. Plan coordinates: +x is east, +y is north, the floor is "
    "z = 0. A room's walls are numbered from its first corner: wall i runs from corner i to "
    "corner i+1, counter-clockwise seen from above (add_room's reply lists them with the "
    "direction each faces).";

// `description` followed by kConventions.
std::string WithConventions(std::string_view description);

// "(x, y)" to the centimetre.
std::string P2(const Vec2& p);

// "field: message" without the "scene: " file prefix.
std::string ProblemText(const Problem& p);

// Each line as "\n- line".
std::string Bullets(const std::vector<std::string>& lines);

// A tool's own fields followed by a shared Options field list.
std::vector<Field> Concat(std::vector<Field> own, std::vector<Field> shared);

}  // namespace asbuilt::mcp

#endif  // ASBUILT_MCP_TOOLS_COMMON_H_
