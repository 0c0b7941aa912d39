#include "asbuilt/mcp/tools.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <new>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "asbuilt/mcp/tools_common.h"
#include "asbuilt/util/error.h"

// The tool table, its dispatch and the checks every tool shares; the tools
// themselves, each schema beside its handler, are in tools_build.cc,
// tools_style_rig.cc, tools_whole_scene.cc and tools_output.cc.

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
  positive(max_samples_per_pixel, "max_samples_per_pixel");
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

}  // namespace asbuilt::mcp
