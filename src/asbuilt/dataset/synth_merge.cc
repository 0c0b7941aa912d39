#include "asbuilt/dataset/synth_merge.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "asbuilt/dataset/checksum.h"
#include "asbuilt/formats/synth_dataset.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"
#include "asbuilt/util/shard.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

constexpr const char* kManifestKind = "asbuilt-synth-manifest";

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

template <typename Body>
void ParallelItems(int count, int num_threads, const Body& body) {
  tbb::task_arena arena(num_threads > 0 ? num_threads : tbb::task_arena::automatic);
  arena.execute([&] { tbb::parallel_for(0, count, [&](int i) { body(i); }); });
}

// Why a complete item's file is not whole, or nothing. Reads a PNG's first
// and last bytes only; atomic writes make truncation rare, so this catches
// damage done after the fact (a copy cut short, a disk error).
std::optional<std::string> DamageOf(const fs::path& file, int index) {
  if (file.extension() == ".json") {
    JsonDiagnostics diag(file.string());
    const nlohmann::json meta = ParseJsonFile(file, diag);
    if (!diag.ok()) return "not JSON: " + diag.errors().front().message;
    if (!meta.is_object() || meta.value("index", -1) != index) return fmt::format("does not name index {}", index);
    return std::nullopt;
  }
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  static constexpr unsigned char kEnd[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
  std::ifstream in(file, std::ios::binary);
  unsigned char head[8] = {}, tail[12] = {};
  in.read(reinterpret_cast<char*>(head), 8);
  if (!in || !std::equal(head, head + 8, kSignature)) return std::string("not a PNG");
  in.seekg(-12, std::ios::end);
  in.read(reinterpret_cast<char*>(tail), 12);
  if (!in || !std::equal(tail, tail + 12, kEnd)) return std::string("a PNG cut short (no IEND at its end)");
  return std::nullopt;
}

// "12", "12-40".
std::string RangeText(int first, int last) {
  return first == last ? fmt::format("{}", first) : fmt::format("{}-{}", first, last);
}

// One problem per shard (or one in all) listing the missing items as ranges.
std::vector<Problem> MissingProblems(const fs::path& dir, const std::vector<int>& missing, int count, int shard_count) {
  std::map<int, std::vector<int>> by_shard;  // Shard (or 0) → items.
  for (int i : missing) {
    int shard = 0;
    for (int k = 0; k < shard_count; ++k) {
      auto [b, e] = ShardRange(count, k, shard_count);
      if (i >= b && i < e) shard = k;
    }
    by_shard[shard].push_back(i);
  }
  std::vector<Problem> problems;
  for (const auto& [shard, items] : by_shard) {
    std::string ranges;
    int shown = 0;
    for (std::size_t a = 0; a < items.size();) {
      std::size_t b = a;
      while (b + 1 < items.size() && items[b + 1] == items[b] + 1) ++b;
      if (shown++ < 8) ranges += (ranges.empty() ? "" : ", ") + RangeText(items[a], items[b]);
      a = b + 1;
    }
    if (shown > 8) ranges += fmt::format(", … ({} ranges)", shown);
    std::string what = fmt::format("{} of {} items missing or incomplete: {}", items.size(), count, ranges);
    if (shard_count > 0) {
      auto [b, e] = ShardRange(count, shard, shard_count);
      what = fmt::format(
          "shard {}/{} (items {}): {} of its {} items missing or incomplete: {}; re-run it with "
          "--resume",
          shard, shard_count, RangeText(b, e - 1), items.size(), e - b, ranges);
    }
    problems.push_back({dir.string(), "", what});
  }
  return problems;
}

}  // namespace

void SynthMergeOptions::Check() const {
  CheckArgument(shard_count >= 0, fmt::format("SynthMergeOptions.shard_count = {}, must be >= 0", shard_count));
  CheckArgument(num_threads >= 0, fmt::format("SynthMergeOptions.num_threads = {}, must be >= 0", num_threads));
}

std::string SynthMergeSummary::BriefReport() const {
  return fmt::format("merged {} items ({} files, {:.1f} MB) in {:.1f} s → {}{}", items, files, bytes / 1e6, seconds,
                     manifest.string(),
                     temps_removed > 0 ? fmt::format(" (removed {} temp files of killed writers)", temps_removed) : "");
}

std::string SynthVerifySummary::BriefReport() const {
  return fmt::format("verified {} items ({} files) in {:.1f} s: {}", items, files, seconds,
                     ok() ? std::string("all match") : fmt::format("{} problems", problems.size()));
}

SynthMergeSummary MergeSynthDataset(const fs::path& dir, const SynthMergeOptions& options,
                                    const ProgressCallback& progress) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  const nlohmann::json record = ReadSynthRecord(dir);
  if (!record.contains("count") || !record["count"].is_number_integer() || record["count"].get<int>() < 1) {
    throw InputError(SynthRecordPath(dir).string(), "options.count", "expected a whole number >= 1");
  }
  const int count = record["count"].get<int>();
  if (options.shard_count > count) CheckShardCount(options.shard_count, count);

  // Every item is checked first (existence, then the cheap damage checks);
  // the files are hashed only when the manifest will be written.
  std::vector<int> missing;
  for (int i = 0; i < count; ++i) {
    if (!IsSynthItemComplete(dir, i)) missing.push_back(i);
  }
  std::vector<Problem> problems = MissingProblems(dir, missing, count, options.shard_count);
  std::vector<char> complete(count, 1);
  for (int i : missing) complete[i] = 0;
  std::mutex mutex;
  std::vector<Problem> damaged;
  ParallelItems(count, options.num_threads, [&](int i) {
    if (!complete[i]) return;
    const std::array<fs::path, 5> files = SynthItemFiles(dir, i);
    for (const fs::path& file : files) {
      if (std::optional<std::string> damage = DamageOf(file, i)) {
        std::lock_guard lock(mutex);
        damaged.push_back({file.string(), "",
                           fmt::format("damaged ({}): delete {} and re-run its shard with --resume", *damage,
                                       files.back().string())});
      }
    }
  });
  std::sort(damaged.begin(), damaged.end(), [](const Problem& a, const Problem& b) { return a.file < b.file; });
  problems.insert(problems.end(), damaged.begin(), damaged.end());
  if (!problems.empty()) throw InputError(std::move(problems));

  std::vector<std::array<std::string, 5>> hashes(count);
  std::vector<std::int64_t> bytes(count, 0);
  std::atomic<int> done = 0;
  ParallelItems(count, options.num_threads, [&](int i) {
    const std::array<fs::path, 5> files = SynthItemFiles(dir, i);
    for (std::size_t k = 0; k < files.size(); ++k) {
      hashes[i][k] = Sha256OfFile(files[k]);
      bytes[i] += static_cast<std::int64_t>(fs::file_size(files[k]));
    }
    const int n = ++done;
    if (n % 64 == 0 || n == count) ReportProgress(progress, {"merge", n, count, ""});
  });

  // One item per line: a diff of two manifests reads item by item.
  std::string text = fmt::format("{{\"version\": 1, \"kind\": \"{}\", \"count\": {}, \"options\": {},\n \"items\": [\n",
                                 kManifestKind, count, record.dump());
  SynthMergeSummary summary;
  for (int i = 0; i < count; ++i) {
    nlohmann::json files = nlohmann::json::object();
    const std::array<std::string, 5> relative = SynthItemRelativeFiles(i);
    for (std::size_t k = 0; k < relative.size(); ++k) files[relative[k]] = hashes[i][k];
    text += fmt::format("  {{\"index\": {}, \"files\": {}}}{}\n", i, files.dump(), i + 1 < count ? "," : "");
    summary.files += static_cast<std::int64_t>(relative.size());
    summary.bytes += bytes[i];
  }
  text += " ]}\n";
  summary.manifest = SynthManifestPath(dir);
  WriteFileAtomic(summary.manifest, text);
  // Every item is whole, so no writer is left: a temp file is what a killed one left.
  for (const char* folder : kSynthItemFolders) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir / folder, ec)) {
      if (IsAtomicTempName(entry.path()) && fs::remove(entry.path(), ec)) ++summary.temps_removed;
    }
  }
  summary.items = count;
  summary.seconds = SecondsSince(start);
  return summary;
}

SynthVerifySummary VerifySynthDataset(const fs::path& dir, int num_threads, const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path path = SynthManifestPath(dir);
  if (!fs::exists(path)) {
    throw InputError(path.string(), "", "not found: run `asbuilt dataset merge` on the folder first");
  }
  JsonDiagnostics diag(path.string());
  const nlohmann::json manifest = ParseJsonFile(path, diag);
  diag.ThrowIfErrors();
  if (!manifest.is_object() || manifest.value("kind", "") != kManifestKind || !manifest.contains("items") ||
      !manifest["items"].is_array()) {
    throw InputError(path.string(), "kind", fmt::format("expected a \"{}\" with an items array", kManifestKind));
  }
  const nlohmann::json& items = manifest["items"];
  SynthVerifySummary summary;
  summary.items = static_cast<int>(items.size());
  std::mutex mutex;
  std::atomic<int> done = 0;
  std::atomic<std::int64_t> files = 0;
  ParallelItems(summary.items, num_threads, [&](int i) {
    const nlohmann::json& item = items[static_cast<std::size_t>(i)];
    if (!item.is_object() || !item.contains("files") || !item["files"].is_object()) {
      std::lock_guard lock(mutex);
      summary.problems.push_back({path.string(), fmt::format("items[{}].files", i), "expected an object"});
      return;
    }
    for (const auto& [relative, sha] : item["files"].items()) {
      ++files;
      const fs::path file = dir / relative;
      std::string why;
      if (!fs::is_regular_file(file)) {
        why = "missing";
      } else if (!sha.is_string() || Sha256OfFile(file) != sha.get<std::string>()) {
        why = "changed since the merge (its SHA-256 differs from the manifest's)";
      }
      if (!why.empty()) {
        std::lock_guard lock(mutex);
        summary.problems.push_back({file.string(), "", why});
      }
    }
    const int n = ++done;
    if (n % 64 == 0 || n == summary.items) ReportProgress(progress, {"verify", n, summary.items, ""});
  });
  std::sort(summary.problems.begin(), summary.problems.end(),
            [](const Problem& a, const Problem& b) { return a.file < b.file; });
  summary.files = files;
  summary.seconds = SecondsSince(start);
  return summary;
}

}  // namespace asbuilt
