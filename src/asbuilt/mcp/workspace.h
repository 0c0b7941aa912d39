#ifndef ASBUILT_MCP_WORKSPACE_H_
#define ASBUILT_MCP_WORKSPACE_H_

// The MCP server's workspace: the one folder its tools may read and write.
// Every path a client names is relative to it and is resolved here, which
// refuses absolute paths, `..`, and symbolic links that lead outside
// (resolved with weakly_canonical, then checked against the workspace's own
// canonical path). Multi-file outputs (captures) are built in a hidden temp
// folder inside the workspace and renamed into place only when complete.
//
// Limit: the check and the later open are not atomic; a process that can
// create symlinks inside the workspace between the two could race it. The
// server's own tools create no symlinks.

#include <filesystem>
#include <string>
#include <string_view>

namespace asbuilt::mcp {

class Workspace {
 public:
  // Creates `root` if missing; throws Error if it cannot be created or is not
  // a folder.
  explicit Workspace(const std::filesystem::path& root);

  const std::filesystem::path& root() const { return root_; }

  // The absolute path of `relative` inside the workspace. Throws
  // InvalidArgument naming `argument` (e.g. "arguments.path") with what is
  // allowed: empty, absolute, containing `..`, a hidden temp name, a control
  // character, or resolving (through symlinks) outside the workspace.
  std::filesystem::path Resolve(std::string_view relative, std::string_view argument) const;

  // Path relative to the root, for messages ("plans/a.json").
  std::string Display(const std::filesystem::path& absolute) const;

  // Removes temp folders left by a killed server (`.asbuilt-tmp-*`).
  // Returns how many were removed.
  int RemoveStaleTemps() const;

 private:
  std::filesystem::path root_;  // Canonical.
};

// A temp folder inside the workspace for an output folder that must appear
// complete or not at all. Destroyed without Commit() (an error, a cancel, a
// client gone), it removes itself and everything in it.
class TempOutputDir {
 public:
  TempOutputDir(const Workspace& workspace, const std::filesystem::path& final_path);
  ~TempOutputDir();
  TempOutputDir(const TempOutputDir&) = delete;
  TempOutputDir& operator=(const TempOutputDir&) = delete;

  const std::filesystem::path& path() const { return temp_; }
  // Renames the temp folder to the final path. With `replace`, an existing
  // final folder is moved aside and removed after the rename; otherwise an
  // existing one is an error (InvalidArgument).
  void Commit(bool replace);

 private:
  std::filesystem::path final_;
  std::filesystem::path temp_;
  bool committed_ = false;
};

// Prefix of temp folder names in the workspace.
inline constexpr std::string_view kWorkspaceTempPrefix = ".asbuilt-tmp-";

}  // namespace asbuilt::mcp

#endif  // ASBUILT_MCP_WORKSPACE_H_
