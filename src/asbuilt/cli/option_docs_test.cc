// The option tables in docs/ are generated from the field lists
// (cli/option_tables.h): each `<!-- options NAME -->` … `<!-- /options -->`
// block must be what `asbuilt help options NAME` prints. With
// ASBUILT_UPDATE_DOCS=1 this test rewrites the stale blocks.

#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "asbuilt/cli/cli_test_util.h"
#include "asbuilt/util/file.h"

namespace asbuilt::cli {
namespace {
namespace fs = std::filesystem;
using testing_util::RunAsbuilt;
using testing_util::RunResult;

TEST(OptionDocs, EveryOptionTableInDocsIsGeneratedAndCurrent) {
  const bool update = std::getenv("ASBUILT_UPDATE_DOCS") && std::string(std::getenv("ASBUILT_UPDATE_DOCS")) == "1";
  std::set<std::string> documented;
  for (const auto& entry : fs::directory_iterator(fs::path(ASBUILT_SOURCE_DIR) / "docs")) {
    if (entry.path().extension() != ".md") continue;
    const std::string text = ReadFile(entry.path());
    std::string rewritten;
    std::size_t at = 0;
    const std::string open = "<!-- options ", close = "<!-- /options -->";
    for (std::size_t b = text.find(open); b != std::string::npos; b = text.find(open, at)) {
      const std::size_t name_end = text.find(" -->\n", b);
      ASSERT_NE(name_end, std::string::npos) << entry.path() << ": an unclosed options marker";
      const std::string name = text.substr(b + open.size(), name_end - b - open.size());
      const std::size_t body = name_end + 5, e = text.find(close, body);
      ASSERT_NE(e, std::string::npos) << entry.path() << ": options " << name << " has no " << close;
      RunResult r = RunAsbuilt("help options " + name);
      ASSERT_EQ(r.exit_code, 0) << entry.path() << ": " << r.out;
      EXPECT_TRUE(update || text.substr(body, e - body) == r.out)
          << entry.path() << ": the " << name << " table is stale; run with ASBUILT_UPDATE_DOCS=1 to rewrite it";
      rewritten += text.substr(at, body - at) + r.out;
      at = e;
      documented.insert(name);
    }
    rewritten += text.substr(at);
    if (update && rewritten != text) WriteFileAtomic(entry.path(), rewritten);
  }
  // docs/options.md holds every table.
  RunResult all = RunAsbuilt("help options");
  ASSERT_EQ(all.exit_code, 0) << all.out;
  for (std::size_t h = all.out.find("## "); h != std::string::npos; h = all.out.find("\n## ", h + 1)) {
    const std::size_t start = all.out[h] == '\n' ? h + 4 : h + 3;
    const std::string name = all.out.substr(start, all.out.find('\n', start) - start);
    EXPECT_TRUE(documented.count(name)) << name << " has no table in docs/ (docs/options.md)";
  }
}

TEST(OptionDocs, AnUnknownStructIsNamedWithTheKnownOnes) {
  RunResult r = RunAsbuilt("help options NoSuchOptions");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.out.find("NoSuchOptions"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("PlanOptions"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace asbuilt::cli
