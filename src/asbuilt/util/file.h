#ifndef ASBUILT_UTIL_FILE_H_
#define ASBUILT_UTIL_FILE_H_

// Files: whole-file reads with clear errors, and atomic writes (temp file in
// the same folder + rename), so a crash or kill never leaves a half-written
// output under its final name.

#include <chrono>
#include <filesystem>
#include <string>
#include <string_view>

namespace asbuilt {

// Reads a whole file. Throws InputError(file, "", "cannot read: <reason>").
std::string ReadFile(const std::filesystem::path& path);

// Writes `contents` to `path` atomically; creates missing parent folders.
// Throws Error on failure (and leaves no temp file behind).
void WriteFileAtomic(const std::filesystem::path& path, std::string_view contents);

// For writers that need a path of their own (cv::imwrite, cairo): write to
// temp_path(), then Commit() renames it over the final path. If the object is
// destroyed without Commit() (an exception, an early return), the temp file is
// removed. The temp path keeps the final extension, so format-by-extension
// writers work, and starts with '.' so folder listings skip it.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path final_path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::filesystem::path& temp_path() const { return temp_path_; }
  const std::filesystem::path& final_path() const { return final_path_; }
  // Renames the temp file to the final path. Throws Error if the temp file is
  // missing (the writer failed) or the rename fails.
  void Commit();

 private:
  std::filesystem::path final_path_;
  std::filesystem::path temp_path_;
  bool committed_ = false;
};

// True for names AtomicFile uses for its temp files (".name.tmp-…"): tools
// that scan folders (resume, dataset check) skip and clean these.
bool IsAtomicTempName(const std::filesystem::path& path);

// Removes AtomicFile temp files directly in `dir` whose writer process is gone
// (the pid in the name is not alive): what a SIGKILL or power loss in the
// middle of a write leaves behind. The final files they were meant to replace
// are untouched. Returns how many were removed; a missing dir removes none.
// On a folder that processes on other machines write too (a cluster's shared
// filesystem), a pid says nothing: give `min_age`, and only temps untouched
// for that long are removed.
int RemoveDeadAtomicTemps(const std::filesystem::path& dir, std::chrono::seconds min_age = std::chrono::seconds(0));

}  // namespace asbuilt

#endif  // ASBUILT_UTIL_FILE_H_
