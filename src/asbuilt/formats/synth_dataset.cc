#include "asbuilt/formats/synth_dataset.h"

#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

constexpr std::string_view kRecordKind = "asbuilt-synth";

std::string Short(const nlohmann::json& value) {
  std::string text = value.is_null() ? "(absent)" : value.dump();
  return text.size() > 60 ? text.substr(0, 57) + "..." : text;
}

}  // namespace

std::array<std::string, 5> SynthItemRelativeFiles(int index) {
  std::array<std::string, 5> files;
  for (std::size_t k = 0; k < kSynthItemFolders.size(); ++k) {
    const bool meta = k + 1 == kSynthItemFolders.size();
    files[k] = fmt::format("{}/{:06d}.{}", kSynthItemFolders[k], index, meta ? "json" : "png");
  }
  return files;
}

std::array<fs::path, 5> SynthItemFiles(const fs::path& dir, int index) {
  std::array<fs::path, 5> files;
  const std::array<std::string, 5> relative = SynthItemRelativeFiles(index);
  for (std::size_t k = 0; k < files.size(); ++k) files[k] = dir / relative[k];
  return files;
}

bool IsSynthItemComplete(const fs::path& dir, int index) {
  for (const fs::path& file : SynthItemFiles(dir, index)) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) return false;
  }
  return true;
}

fs::path SynthRecordPath(const fs::path& dir) { return dir / "synth.json"; }
fs::path SynthManifestPath(const fs::path& dir) { return dir / "synth_manifest.json"; }

nlohmann::json ReadSynthRecord(const fs::path& dir) {
  const fs::path path = SynthRecordPath(dir);
  if (!fs::exists(path)) {
    throw InputError(path.string(), "", "not found: is this a folder written by `asbuilt dataset synth`?");
  }
  JsonDiagnostics diag(path.string());
  nlohmann::json root = ParseJsonFile(path, diag);
  diag.ThrowIfErrors();
  if (!root.is_object() || root.value("kind", "") != kRecordKind) {
    throw InputError(path.string(), "kind", fmt::format("expected \"{}\"", kRecordKind));
  }
  if (root.value("version", 0) != 1) throw InputError(path.string(), "version", "expected 1");
  if (!root.contains("options") || !root["options"].is_object()) {
    throw InputError(path.string(), "options", "expected an object");
  }
  return root["options"];
}

void ClaimSynthDir(const fs::path& dir, const nlohmann::json& options) {
  if (!fs::exists(SynthRecordPath(dir))) {
    const nlohmann::json record = {{"version", 1}, {"kind", kRecordKind}, {"options", options}};
    WriteFileAtomic(SynthRecordPath(dir), record.dump(1) + "\n");
    return;
  }
  CheckSynthDir(dir, options);
}

void CheckSynthDir(const fs::path& dir, const nlohmann::json& options) {
  if (!fs::exists(SynthRecordPath(dir))) return;
  const nlohmann::json recorded = ReadSynthRecord(dir);
  if (recorded == options) return;
  std::vector<Problem> problems;
  std::vector<std::string> keys;
  for (const auto& [key, value] : recorded.items()) keys.push_back(key);
  for (const auto& [key, value] : options.items()) {
    if (!recorded.contains(key)) keys.push_back(key);
  }
  for (const std::string& key : keys) {
    const nlohmann::json was = recorded.contains(key) ? recorded[key] : nlohmann::json();
    const nlohmann::json now = options.contains(key) ? options[key] : nlohmann::json();
    if (was == now) continue;
    problems.push_back({SynthRecordPath(dir).string(), "options." + key,
                        fmt::format("this folder was made with {}, this run asks for {}: use another folder or the "
                                    "same options (nothing was written)",
                                    Short(was), Short(now))});
  }
  throw InputError(std::move(problems));
}

}  // namespace asbuilt
