// docs/mcp.md's tool reference is generated from the tools' field lists
// (STYLE.md 13); this test fails when it is stale and, with
// ASBUILT_UPDATE_DOCS=1, rewrites it.

#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include "asbuilt/mcp/tools.h"
#include "asbuilt/util/file.h"

namespace asbuilt::mcp {
namespace {
namespace fs = std::filesystem;

TEST(McpDocs, ToolReferenceIsUpToDate) {
  const fs::path doc = fs::path(ASBUILT_SOURCE_DIR) / "docs" / "mcp.md";
  std::string text = ReadFile(doc);
  const std::string begin = "<!-- tools:begin -->\n", end = "<!-- tools:end -->";
  auto b = text.find(begin), e = text.find(end);
  ASSERT_NE(b, std::string::npos) << doc << " lacks " << begin;
  ASSERT_NE(e, std::string::npos) << doc << " lacks " << end;
  fs::path ws = fs::temp_directory_path() / "asbuilt_docs_test_ws";
  SceneTools tools{Workspace(ws)};
  std::string generated = tools.ToolsMarkdown();
  generated.insert(0, 1, '\n');
  std::string current = text.substr(b + begin.size(), e - b - begin.size());
  fs::remove_all(ws);
  if (current == generated) return;
  if (const char* update = std::getenv("ASBUILT_UPDATE_DOCS"); update && std::string(update) == "1") {
    WriteFileAtomic(doc, text.substr(0, b + begin.size()) + generated + text.substr(e));
    return;
  }
  FAIL() << "docs/mcp.md's tool reference is stale; run with ASBUILT_UPDATE_DOCS=1 to rewrite it";
}

}  // namespace
}  // namespace asbuilt::mcp
