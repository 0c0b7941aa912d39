// STYLE.md 13: a CLI command and the MCP tool that share an Options struct
// take the same options, both built from one field list (util/fields.h,
// declared beside each struct). These tests read the real `asbuilt … --help`
// and the real tools/list schema, so a flag added by hand on either side
// fails them.

#include <algorithm>
#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "asbuilt/cli/cli_test_util.h"
#include "asbuilt/mcp/tools.h"
#include "asbuilt/render/capture_render.h"
#include "asbuilt/scene/procedural.h"
#include "asbuilt/scene/scene_text.h"

namespace asbuilt::cli {
namespace {
namespace fs = std::filesystem;
using Names = std::set<std::string>;
using testing_util::FreshTestDir;
using testing_util::RunAsbuilt;
using testing_util::RunResult;

// Every --flag the command's help lists.
Names HelpFlags(const std::string& command) {
  RunResult r = RunAsbuilt(command + " --help");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  Names flags;
  std::regex flag("--[a-z][a-z0-9.-]*[a-z0-9]");
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), flag); it != std::sregex_iterator(); ++it) {
    flags.insert(it->str());
  }
  return flags;
}

std::string Dashed(std::string_view name) {
  std::string s = "--" + std::string(name);
  std::replace(s.begin(), s.end(), '_', '-');
  return s;
}

// The flags a field list makes (cli/field_flags.h): --name, and for booleans
// the negation with "no-" before the last name part (--no-normals,
// --points.no-use-corners).
Names FlagsOf(const std::vector<Field>& fields) {
  Names flags;
  for (const Field& f : fields) {
    const std::string dashed = Dashed(f.name);
    flags.insert(dashed);
    if (f.kind == FieldKind::kBool) {
      const std::size_t dot = dashed.rfind('.');
      const std::size_t leaf = dot == std::string::npos ? 2 : dot + 1;
      flags.insert(dashed.substr(0, leaf) + "no-" + dashed.substr(leaf));
    }
  }
  return flags;
}

Names NamesOf(const std::vector<Field>& fields) {
  Names names;
  for (const Field& f : fields) names.insert(std::string(f.name));
  return names;
}

Names Union(Names a, const Names& b) {
  a.insert(b.begin(), b.end());
  return a;
}

Names ToolProperties(const std::string& tool) {
  fs::path ws = FreshTestDir("shared_options_ws");
  mcp::SceneTools tools{mcp::Workspace(ws)};
  const mcp::ToolSpec* spec = tools.Find(tool);
  EXPECT_NE(spec, nullptr) << tool;
  Names names;
  if (spec) {
    const nlohmann::json tool = spec->ToJson();
    for (const auto& [name, schema] : tool["inputSchema"]["properties"].items()) names.insert(name);
  }
  fs::remove_all(ws);
  return names;
}

const Names kCommon = {"--help", "--quiet", "--verbose"};
const Names kSubcommand = {"--help"};  // --quiet/--verbose belong to `asbuilt scene`.

TEST(SharedOptions, RenderAndRenderCaptureTakeTheSameFields) {
  auto fields = CaptureRenderOptionFields().Fields();
  EXPECT_EQ(ToolProperties("render_capture"), Union(NamesOf(fields), {"output", "overwrite"}));
  // CLI-only: the output folder, --size WxH (short for --width-px/--height-px), --no-resume, --home
  // (a capture per room of a home); and the older spellings kept as aliases.
  EXPECT_EQ(HelpFlags("render"),
            Union(Union(FlagsOf(fields), kCommon),
                  {"--out", "--size", "--no-resume", "--home", "--spp", "--effects", "--no-indirect", "--instances"}));
}

TEST(SharedOptions, SceneTextAndSceneFromTextTakeTheSameFields) {
  auto fields = SceneTextOptionFields().Fields();
  EXPECT_EQ(ToolProperties("scene_from_text"), Union(NamesOf(fields), {"text"}));
  // CLI-only: the output file and the LLM front end; aliases.
  EXPECT_EQ(HelpFlags("scene text"), Union(Union(FlagsOf(fields), kSubcommand),
                                           {"--output", "--llm", "--llm-model", "--llm-rounds", "--llm-timeout",
                                            "--no-furniture", "--no-default-door", "--rig-height", "--step"}));
}

TEST(SharedOptions, SceneRandomAndRandomSceneTakeTheSameFields) {
  auto fields = RandomSceneOptionFields().Fields();
  fields.push_back(RandomSceneSeedField());
  EXPECT_EQ(ToolProperties("random_scene"), NamesOf(fields));
  EXPECT_EQ(HelpFlags("scene random"),
            Union(Union(FlagsOf(fields), kSubcommand), {"--output", "--count", "--min-side", "--max-side", "--step"}));
}

TEST(SharedOptions, CliChecksBoundsLikeTheTool) {
  RunResult r = RunAsbuilt("render missing.json -o /tmp/x --samples-per-pixel 0");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--samples-per-pixel: must be"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace asbuilt::cli
