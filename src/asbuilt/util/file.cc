#include "asbuilt/util/file.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <system_error>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

std::atomic<unsigned> temp_counter{0};

}  // namespace

std::string ReadFile(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    throw InputError(path.string(), "", "cannot read: is a folder, not a file");
  }
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    throw InputError(path.string(), "", fmt::format("cannot read: {}", std::strerror(errno)));
  }
  std::string out;
  char buffer[1 << 16];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) out.append(buffer, n);
  bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) throw InputError(path.string(), "", "cannot read: I/O error");
  return out;
}

AtomicFile::AtomicFile(fs::path final_path) : final_path_(std::move(final_path)) {
  fs::path parent = final_path_.parent_path();
  if (!parent.empty()) {
    std::error_code ec;
    fs::create_directories(parent, ec);
    if (ec) {
      throw Error(fmt::format("{}: cannot create folder: {}", parent.string(), ec.message()));
    }
  }
  std::string name = fmt::format(".{}.tmp-{}-{}{}", final_path_.stem().string(), ::getpid(), temp_counter.fetch_add(1),
                                 final_path_.extension().string());
  temp_path_ = parent / name;
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_path_, ec);
  }
}

void AtomicFile::Commit() {
  std::error_code ec;
  if (!fs::exists(temp_path_, ec)) {
    throw Error(fmt::format("{}: writing failed (no data was written)", final_path_.string()));
  }
  fs::rename(temp_path_, final_path_, ec);
  if (ec) {
    throw Error(fmt::format("{}: cannot write: {}", final_path_.string(), ec.message()));
  }
  committed_ = true;
}

bool IsAtomicTempName(const fs::path& path) {
  std::string name = path.filename().string();
  return name.size() > 1 && name[0] == '.' && name.find(".tmp-") != std::string::npos;
}

int RemoveDeadAtomicTemps(const fs::path& dir, std::chrono::seconds min_age) {
  int removed = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (!IsAtomicTempName(entry.path())) continue;
    // ".stem.tmp-<pid>-<counter>.ext": the writer's pid follows the last ".tmp-".
    const std::size_t at = name.rfind(".tmp-") + 5;
    char* end = nullptr;
    const long pid = std::strtol(name.c_str() + at, &end, 10);
    if (end == name.c_str() + at || *end != '-' || pid <= 0) continue;
    if (pid == ::getpid() || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    if (min_age.count() > 0) {
      std::error_code time_ec;
      const auto written = fs::last_write_time(entry.path(), time_ec);
      if (time_ec || fs::file_time_type::clock::now() - written < min_age) continue;
    }
    std::error_code rm_ec;
    if (fs::remove(entry.path(), rm_ec)) ++removed;
  }
  return removed;
}

void WriteFileAtomic(const fs::path& path, std::string_view contents) {
  AtomicFile file(path);
  {
    std::FILE* f = std::fopen(file.temp_path().c_str(), "wb");
    if (f == nullptr) {
      throw Error(fmt::format("{}: cannot write: {}", path.string(), std::strerror(errno)));
    }
    bool ok = std::fwrite(contents.data(), 1, contents.size(), f) == contents.size();
    ok = (std::fflush(f) == 0) && ok;
    ok = (::fsync(::fileno(f)) == 0) && ok;
    ok = (std::fclose(f) == 0) && ok;
    if (!ok) {
      throw Error(fmt::format("{}: cannot write: {}", path.string(), std::strerror(errno)));
    }
  }
  file.Commit();
}

}  // namespace asbuilt
