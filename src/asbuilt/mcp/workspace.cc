#include "asbuilt/mcp/workspace.h"

#include <unistd.h>

#include <atomic>
#include <system_error>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/util/error.h"

namespace asbuilt::mcp {
namespace fs = std::filesystem;
namespace {

std::atomic<unsigned> temp_counter{0};

// True if `path` equals `root` or lies under it (both canonical/absolute).
bool IsInside(const fs::path& root, const fs::path& path) {
  auto r = root.begin(), p = path.begin();
  for (; r != root.end(); ++r, ++p) {
    if (p == path.end() || *r != *p) return false;
  }
  return true;
}

}  // namespace

Workspace::Workspace(const fs::path& root) {
  std::error_code ec;
  fs::create_directories(root, ec);
  if (!fs::is_directory(root, ec)) {
    throw Error(fmt::format("workspace {}: not a folder and cannot be created{}", root.string(),
                            ec ? ": " + ec.message() : ""));
  }
  root_ = fs::canonical(root, ec);
  if (ec) throw Error(fmt::format("workspace {}: {}", root.string(), ec.message()));
}

fs::path Workspace::Resolve(std::string_view relative, std::string_view argument) const {
  std::string shown(relative.substr(0, 80));
  if (relative.size() > 80) shown += "...";
  auto refuse = [&](std::string_view why) {
    throw InvalidArgument(
        fmt::format("{}: \"{}\" {}; give a relative path inside the workspace, such as \"scenes/room.json\"", argument,
                    shown, why));
  };
  if (relative.empty()) refuse("is empty");
  for (char c : relative) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) refuse("contains a control character");
  }
  fs::path rel(relative);
  if (rel.is_absolute() || rel.has_root_name() || rel.has_root_directory()) {
    refuse("is an absolute path; only paths relative to the workspace are allowed");
  }
  for (const fs::path& part : rel) {
    if (part == "..") refuse("contains \"..\"; paths may not leave the workspace");
    if (part.string().starts_with(kWorkspaceTempPrefix)) refuse("names a temporary folder");
  }
  fs::path joined = (root_ / rel).lexically_normal();
  if (!joined.has_filename()) joined = joined.parent_path();  // "dir/" → "dir"
  std::error_code ec;
  fs::path resolved = fs::weakly_canonical(joined, ec);
  if (ec) refuse(fmt::format("cannot be resolved ({})", ec.message()));
  if (!IsInside(root_, resolved)) {
    refuse("leads outside the workspace (through a symbolic link)");
  }
  // weakly_canonical leaves a dangling symlink unresolved; refuse it rather
  // than let a later open follow it.
  if (fs::is_symlink(fs::symlink_status(resolved, ec))) {
    refuse("is a symbolic link that points nowhere");
  }
  if (resolved == root_) refuse("names the workspace itself; give a file or folder name");
  return resolved;
}

std::string Workspace::Display(const fs::path& absolute) const {
  return absolute.lexically_relative(root_).generic_string();
}

int Workspace::RemoveStaleTemps() const {
  int removed = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(root_, ec)) {
    if (entry.path().filename().string().starts_with(kWorkspaceTempPrefix)) {
      std::error_code rm_ec;
      fs::remove_all(entry.path(), rm_ec);
      if (!rm_ec) ++removed;
    }
  }
  return removed;
}

TempOutputDir::TempOutputDir(const Workspace& workspace, const fs::path& final_path) : final_(final_path) {
  temp_ = workspace.root() / fmt::format("{}{}-{}-{}", kWorkspaceTempPrefix, final_path.filename().string(), ::getpid(),
                                         temp_counter.fetch_add(1));
  std::error_code ec;
  fs::create_directories(temp_, ec);
  if (ec) throw Error(fmt::format("cannot create a temp folder in the workspace: {}", ec.message()));
}

TempOutputDir::~TempOutputDir() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(temp_, ec);
  if (ec) spdlog::warn("mcp: cannot remove temp folder {}: {}", temp_.string(), ec.message());
}

void TempOutputDir::Commit(bool replace) {
  std::error_code ec;
  fs::create_directories(final_.parent_path(), ec);
  fs::path aside;
  if (fs::exists(fs::symlink_status(final_, ec))) {
    if (!replace) {
      throw InvalidArgument(fmt::format("{} already exists; choose another output name or pass overwrite: true",
                                        final_.filename().string()));
    }
    aside = temp_.string() + "-old";
    fs::rename(final_, aside, ec);
    if (ec) throw Error(fmt::format("cannot replace {}: {}", final_.string(), ec.message()));
  }
  fs::rename(temp_, final_, ec);
  if (ec) {
    if (!aside.empty()) fs::rename(aside, final_, ec);
    throw Error(fmt::format("cannot move the finished output into place: {}", ec.message()));
  }
  committed_ = true;
  if (!aside.empty()) fs::remove_all(aside, ec);
}

}  // namespace asbuilt::mcp
