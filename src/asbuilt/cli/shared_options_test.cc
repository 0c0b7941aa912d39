// STYLE.md 13: a CLI command and the MCP tool that share an Options struct
// take the same options, both built from one field list
// (mcp/option_fields.h). These tests read the real `asbuilt … --help` and the
// real tools/list schema, so a flag added by hand on either side fails them.

#include <algorithm>
#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "asbuilt/cli/cli_test_util.h"
#include "asbuilt/mcp/option_fields.h"
#include "asbuilt/mcp/tools.h"

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
  std::regex flag("--[a-z][a-z0-9-]*");
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

// The flags a field list makes (cli/field_flags.h): --name, --no-name for
// booleans, and the field's extra CLI names.
Names FlagsOf(const std::vector<mcp::ToolField>& fields) {
  Names flags;
  for (const mcp::ToolField& f : fields) {
    flags.insert(Dashed(f.name));
    if (f.type == mcp::ArgType::kBool) flags.insert("--no-" + Dashed(f.name).substr(2));
    std::string extra(f.cli_names);
    std::regex flag("--[a-z][a-z0-9-]*");
    for (auto it = std::sregex_iterator(extra.begin(), extra.end(), flag); it != std::sregex_iterator(); ++it) {
      flags.insert(it->str());
    }
  }
  return flags;
}

Names NamesOf(const std::vector<mcp::ToolField>& fields) {
  Names names;
  for (const mcp::ToolField& f : fields) names.insert(std::string(f.name));
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
  auto fields = mcp::CaptureRenderOptionFields();
  EXPECT_EQ(ToolProperties("render_capture"), Union(NamesOf(fields), {"output", "overwrite"}));
  // CLI-only: the output folder, --size WxH (short for --width-px/--height-px), --no-resume.
  EXPECT_EQ(HelpFlags("render"), Union(Union(FlagsOf(fields), kCommon), {"--out", "--size", "--no-resume"}));
}

TEST(SharedOptions, SceneTextAndSceneFromTextTakeTheSameFields) {
  auto fields = mcp::SceneTextOptionFields();
  EXPECT_EQ(ToolProperties("scene_from_text"), Union(NamesOf(fields), {"text"}));
  // CLI-only: the output file and the LLM front end.
  EXPECT_EQ(HelpFlags("scene text"), Union(Union(FlagsOf(fields), kSubcommand),
                                           {"--output", "--llm", "--llm-model", "--llm-rounds", "--llm-timeout"}));
}

TEST(SharedOptions, SceneRandomAndRandomSceneTakeTheSameFields) {
  auto fields = mcp::RandomSceneOptionFields();
  EXPECT_EQ(ToolProperties("random_scene"), NamesOf(fields));
  EXPECT_EQ(HelpFlags("scene random"), Union(Union(FlagsOf(fields), kSubcommand), {"--output", "--count"}));
}

TEST(SharedOptions, CliChecksBoundsLikeTheTool) {
  RunResult r = RunAsbuilt("render missing.json -o /tmp/x --samples-per-pixel 0");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--samples-per-pixel: must be"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace asbuilt::cli
