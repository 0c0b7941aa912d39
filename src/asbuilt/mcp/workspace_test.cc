#include "asbuilt/mcp/workspace.h"

#include <unistd.h>

#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt::mcp {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

class WorkspaceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    base_ = fs::temp_directory_path() / ("asbuilt_ws_test_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(base_);
    fs::create_directories(base_ / "outside");
    ws_root_ = base_ / "ws";
  }
  void TearDown() override { fs::remove_all(base_); }

  std::string RefusalOf(const Workspace& ws, std::string_view path) {
    try {
      ws.Resolve(path, "arguments.path");
    } catch (const InvalidArgument& e) {
      return e.what();
    }
    return "";
  }

  fs::path base_, ws_root_;
};

TEST_F(WorkspaceTest, CreatesTheFolderAndResolvesRelativePaths) {
  Workspace ws(ws_root_);
  EXPECT_TRUE(fs::is_directory(ws_root_));
  fs::path p = ws.Resolve("scenes/a.json", "arguments.path");
  EXPECT_EQ(p, fs::canonical(ws_root_) / "scenes" / "a.json");
  EXPECT_EQ(ws.Display(p), "scenes/a.json");
  EXPECT_EQ(ws.Resolve("./b.json", "x"), fs::canonical(ws_root_) / "b.json");
}

TEST_F(WorkspaceTest, RefusesAbsolutePathsAndDotDot) {
  Workspace ws(ws_root_);
  EXPECT_THAT(RefusalOf(ws, "/etc/passwd"), HasSubstr("arguments.path: \"/etc/passwd\" is an absolute path"));
  EXPECT_THAT(RefusalOf(ws, "../outside/x.json"), HasSubstr("contains \"..\""));
  EXPECT_THAT(RefusalOf(ws, "a/../../x.json"), HasSubstr("contains \"..\""));
  EXPECT_THAT(RefusalOf(ws, ""), HasSubstr("is empty"));
  EXPECT_THAT(RefusalOf(ws, "a\nb"), HasSubstr("control character"));
  EXPECT_THAT(RefusalOf(ws, "."), HasSubstr("names the workspace itself"));
  EXPECT_THAT(RefusalOf(ws, ".asbuilt-tmp-x/y"), HasSubstr("temporary folder"));
}

TEST_F(WorkspaceTest, RefusesSymlinksLeadingOutside) {
  Workspace ws(ws_root_);
  fs::create_directory_symlink(base_ / "outside", ws_root_ / "escape");
  fs::create_symlink(base_ / "outside" / "secret.json", ws_root_ / "file_link.json");
  fs::create_symlink(base_ / "outside" / "missing.json", ws_root_ / "dangling.json");
  std::ofstream(base_ / "outside" / "secret.json") << "{}";
  EXPECT_THAT(RefusalOf(ws, "escape/x.json"), HasSubstr("leads outside the workspace"));
  EXPECT_THAT(RefusalOf(ws, "file_link.json"), HasSubstr("leads outside the workspace"));
  EXPECT_THAT(RefusalOf(ws, "dangling.json"), HasSubstr("symbolic link"));
  // A symlink that stays inside is fine.
  fs::create_directories(ws_root_ / "real");
  fs::create_directory_symlink(ws_root_ / "real", ws_root_ / "alias");
  EXPECT_EQ(ws.Resolve("alias/x.json", "p"), fs::canonical(ws_root_) / "real" / "x.json");
}

TEST_F(WorkspaceTest, TempOutputAppearsOnlyOnCommit) {
  Workspace ws(ws_root_);
  fs::path final_path = ws.Resolve("captures/a", "arguments.output");
  {
    TempOutputDir tmp(ws, final_path);
    std::ofstream(tmp.path() / "capture.json") << "{}";
    EXPECT_FALSE(fs::exists(final_path));
  }  // Destroyed without Commit: gone.
  EXPECT_FALSE(fs::exists(final_path));
  EXPECT_EQ(ws.RemoveStaleTemps(), 0);
  {
    TempOutputDir tmp(ws, final_path);
    std::ofstream(tmp.path() / "capture.json") << "{}";
    tmp.Commit(false);
  }
  EXPECT_TRUE(fs::exists(final_path / "capture.json"));
  {
    TempOutputDir tmp(ws, final_path);
    EXPECT_THROW(tmp.Commit(false), InvalidArgument);
    std::ofstream(tmp.path() / "new.json") << "{}";
    tmp.Commit(true);
  }
  EXPECT_TRUE(fs::exists(final_path / "new.json"));
  EXPECT_FALSE(fs::exists(final_path / "capture.json"));
  for (const auto& e : fs::directory_iterator(ws.root())) {
    EXPECT_FALSE(e.path().filename().string().starts_with(kWorkspaceTempPrefix)) << e.path();
  }
}

TEST_F(WorkspaceTest, RemovesStaleTempFolders) {
  Workspace ws(ws_root_);
  fs::create_directories(ws.root() / ".asbuilt-tmp-old-123-0" / "left");
  EXPECT_EQ(ws.RemoveStaleTemps(), 1);
  EXPECT_FALSE(fs::exists(ws.root() / ".asbuilt-tmp-old-123-0"));
}

}  // namespace
}  // namespace asbuilt::mcp
