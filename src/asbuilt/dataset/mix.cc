#include "asbuilt/dataset/mix.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <random>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "asbuilt/dataset/checksum.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

// Fisher–Yates with an explicit unbiased draw, so a seed gives the same
// order with any standard library (std::shuffle's is unspecified).
template <typename T>
void Shuffle(std::vector<T>& v, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  for (std::size_t i = v.size(); i > 1; --i) {
    const std::uint64_t n = i;
    const std::uint64_t limit = UINT64_MAX - UINT64_MAX % n;
    std::uint64_t r;
    do {
      r = rng();
    } while (r >= limit);
    std::swap(v[i - 1], v[r % n]);
  }
}

// Independent streams from one seed.
constexpr std::uint64_t kTestStream = 0x7465737400000000ULL;  // "test"

// The room a pair shows: the folder part of its name ("kitchen/review/
// training/003" → "kitchen/review/training"); a pair named without one is
// a room of its own (a folder of single photos).
std::string RoomOf(const ImagePair& p) {
  const std::size_t slash = p.name.rfind('/');
  return slash == std::string::npos ? p.name : p.name.substr(0, slash);
}
constexpr std::uint64_t kRealStream = 0x7265616c00000000ULL;   // "real"
constexpr std::uint64_t kSynthStream = 0x73796e7400000000ULL;  // "synt"
constexpr std::uint64_t kOrderStream = 0x6f72646500000000ULL;  // "orde"

std::vector<ImagePair> Sorted(std::vector<ImagePair> pairs) {
  std::sort(pairs.begin(), pairs.end(), [](const ImagePair& a, const ImagePair& b) {
    return a.image != b.image ? a.image < b.image : a.label < b.label;
  });
  return pairs;
}

}  // namespace

std::optional<MixConfig> MixConfig::Parse(std::string_view name) {
  std::string n(name);
  for (char& c : n) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  auto digits = [](std::string_view s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  if (n == "R100") return MixConfig{100, 0};
  if (n == "S100") return MixConfig{0, 100};
  if (n.size() == 6 && n.rfind("RS", 0) == 0 && digits(std::string_view(n).substr(2))) {
    MixConfig c{std::stoi(n.substr(2, 2)), std::stoi(n.substr(4, 2))};
    // RS0100 does not fit four digits; R100 and S100 are the pure forms.
    if (c.real_percent + c.synthetic_percent == 100) return c;
  }
  return std::nullopt;
}

std::string MixConfig::Name() const {
  if (synthetic_percent == 0) return "R100";
  if (real_percent == 0) return "S100";
  return fmt::format("RS{:02d}{:02d}", real_percent, synthetic_percent);
}

std::string MixConfig::ToString() const {
  return fmt::format("{} ({} % real, {} % synthetic)", Name(), real_percent, synthetic_percent);
}

void MixOptions::Check() const {
  CheckArgument(MixConfig::Parse(config).has_value(),
                fmt::format("MixOptions.config = \"{}\", expected R100, S100 or RSxxyy with xx + yy = 100 "
                            "(RS5050, RS8020, RS2080, …)",
                            config));
  CheckArgument(total >= 0, fmt::format("MixOptions.total = {}, must be >= 0 (0 = as many as possible)", total));
  CheckArgument(split > 0 && split <= 1, fmt::format("MixOptions.split = {}, must be in (0, 1]", split));
  CheckArgument(test_fraction >= 0 && test_fraction < 1,
                fmt::format("MixOptions.test_fraction = {}, must be in [0, 1)", test_fraction));
  CheckArgument(num_threads >= 0, fmt::format("MixOptions.num_threads = {}, must be >= 0", num_threads));
}

std::string MixSummary::BriefReport() const {
  return fmt::format("{} seed {}: {} train + {} val ({} real of {}, {} synthetic of {}), {} real test in {:.2f} s",
                     manifest.config, manifest.seed, manifest.train.size(), manifest.val.size(), real_used,
                     real_available, synthetic_used, synthetic_available, manifest.test.size(), seconds);
}

MixSummary BuildMix(const MixOptions& options, const MixSources& sources, const fs::path& manifest_dir,
                    const ProgressCallback& progress) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  const MixConfig config = *MixConfig::Parse(options.config);

  // Hold out the test pairs first, from the real pairs and the seed only.
  std::vector<ImagePair> real = Sorted(sources.real), test;
  if (!sources.real_test.empty()) {
    test = Sorted(sources.real_test);
    std::map<std::string, std::string> test_files;
    for (const ImagePair& p : test) test_files[fs::weakly_canonical(p.image).string()] = p.name;
    std::erase_if(real, [&](const ImagePair& p) {
      bool dup = test_files.count(fs::weakly_canonical(p.image).string()) > 0;
      if (dup) spdlog::warn("mix: {} is in the test set; left out of the real training pool", p.image.string());
      return dup;
    });
  } else if (!real.empty() && options.test_fraction > 0) {
    // Whole rooms are held out, never single views of one (RoomOf).
    std::map<std::string, std::vector<ImagePair>> by_room;
    for (ImagePair& p : real) by_room[RoomOf(p)].push_back(std::move(p));
    std::vector<std::string> rooms;
    for (const auto& [room, pairs] : by_room) rooms.push_back(room);
    if (rooms.size() < 2) {
      throw Error(fmt::format(
          "the real pairs are all of one room ({}): a test room must be another one, never views of the same room; "
          "give the reviews of more rooms, or --test-fraction 0 (and --test DIR)",
          rooms.front()));
    }
    Shuffle(rooms, options.seed ^ kTestStream);
    const std::size_t wanted = static_cast<std::size_t>(std::ceil(options.test_fraction * real.size()));
    real.clear();
    for (std::size_t i = 0; i < rooms.size(); ++i) {
      std::vector<ImagePair>& pairs = by_room[rooms[i]];
      // Test until it holds `wanted` pairs, but never the last room.
      const bool to_test = test.size() < wanted && i + 1 < rooms.size();
      std::vector<ImagePair>& into = to_test ? test : real;
      into.insert(into.end(), pairs.begin(), pairs.end());
    }
    test = Sorted(std::move(test));
    real = Sorted(std::move(real));
  }
  std::vector<ImagePair> synthetic = Sorted(sources.synthetic);

  // How many of each.
  const std::int64_t have_real = real.size(), have_synth = synthetic.size();
  std::int64_t total = options.total;
  if (total == 0) {
    if (config.synthetic_percent == 0) {
      total = have_real;
    } else if (config.real_percent == 0) {
      total = have_synth;
    } else {
      total = std::min(have_real * 100 / config.real_percent, have_synth * 100 / config.synthetic_percent);
    }
  }
  const std::int64_t n_real = static_cast<std::int64_t>(std::llround(total * config.real_percent / 100.0));
  const std::int64_t n_synth = total - n_real;
  if (n_real > have_real || n_synth > have_synth || total == 0) {
    throw Error(fmt::format(
        "{} with total {} needs {} real pair{} (after holding out {} for test) and {} synthetic, have {} and {}",
        config.Name(), total, n_real, n_real == 1 ? "" : "s", test.size(), n_synth, have_real, have_synth));
  }

  // Pick, then split each source 9:1 so val has the mix's ratio too.
  Shuffle(real, options.seed ^ kRealStream);
  Shuffle(synthetic, options.seed ^ kSynthStream);
  MixSummary summary;
  Manifest& m = summary.manifest;
  m.config = config.Name();
  m.seed = options.seed;
  m.base_dir = manifest_dir;
  // Source files by manifest path, for the checksums (the manifest folder
  // may not exist yet, so its relative paths cannot be opened).
  std::map<std::string, fs::path> files;
  auto entry = [&](const ImagePair& p, PairSource source) {
    ManifestEntry e{RelativePathForManifest(p.image, manifest_dir), RelativePathForManifest(p.label, manifest_dir),
                    source, "", ""};
    files[e.image] = p.image;
    files[e.label] = p.label;
    return e;
  };
  // Val: round(total · (1 − split)) pairs, shared between the sources in
  // proportion (so small mixes still get a val pair).
  const std::int64_t n_val = static_cast<std::int64_t>(std::llround(total * (1.0 - options.split)));
  const std::int64_t n_val_real =
      std::min(n_real, static_cast<std::int64_t>(std::llround(static_cast<double>(n_val) * n_real / total)));
  const std::int64_t n_val_synth = std::min(n_synth, n_val - n_val_real);
  for (auto [pool, count, count_val, source] : {std::tuple{&real, n_real, n_val_real, PairSource::kReal},
                                                std::tuple{&synthetic, n_synth, n_val_synth, PairSource::kSynthetic}}) {
    for (std::int64_t i = 0; i < count; ++i) {
      (i < count_val ? m.val : m.train).push_back(entry((*pool)[i], source));
    }
  }
  Shuffle(m.train, options.seed ^ kOrderStream);
  Shuffle(m.val, (options.seed ^ kOrderStream) + 1);
  for (const ImagePair& p : test) m.test.push_back(entry(p, PairSource::kReal));
  summary.real_available = have_real;
  summary.synthetic_available = have_synth;
  summary.real_used = n_real;
  summary.synthetic_used = n_synth;

  if (options.checksums) {
    std::vector<ManifestEntry*> all;
    for (auto* list : {&m.train, &m.val, &m.test}) {
      for (ManifestEntry& e : *list) all.push_back(&e);
    }
    std::mutex mutex;
    std::int64_t done = 0;
    tbb::task_arena arena(options.num_threads > 0 ? options.num_threads : tbb::task_arena::automatic);
    arena.execute([&] {
      tbb::parallel_for(std::size_t{0}, all.size(), [&](std::size_t i) {
        all[i]->sha256 = Sha256OfFile(files.at(all[i]->image));
        all[i]->label_sha256 = Sha256OfFile(files.at(all[i]->label));
        std::lock_guard lock(mutex);
        ReportProgress(progress, {"checksum", ++done, static_cast<std::int64_t>(all.size()), all[i]->image});
      });
    });
    // A test photo must not also be a training photo under another name.
    std::map<std::string, const ManifestEntry*> trained;
    for (auto* list : {&m.train, &m.val}) {
      for (const ManifestEntry& e : *list) trained.emplace(e.sha256, &e);
    }
    for (const ManifestEntry& e : m.test) {
      if (auto it = trained.find(e.sha256); it != trained.end()) {
        throw Error(fmt::format("test image {} is byte-identical to training image {}: the test set must be held out",
                                e.image, it->second->image));
      }
    }
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

namespace {

fs::path Normal(const fs::path& dir) {
  fs::path p = dir.lexically_normal();
  return p.filename().empty() ? p.parent_path() : p;
}

bool IsReviewTrainingFolder(const fs::path& dir) {
  const fs::path p = Normal(dir);
  return p.filename() == "training" && p.parent_path().filename() == "review";
}

}  // namespace

std::string RoomNameOfFolder(const fs::path& dir) {
  const fs::path p = Normal(dir);
  return IsReviewTrainingFolder(p) ? p.parent_path().parent_path().filename().string() : p.filename().string();
}

MixSummary MixDataset(const MixOptions& options, const std::vector<fs::path>& real_dirs, const fs::path& synthetic_dir,
                      const fs::path& real_test_dir, const fs::path& manifest_path, const ProgressCallback& progress) {
  options.Check();
  MixSources sources;
  auto list = [](const fs::path& dir, const char* what) {
    if (dir.empty()) return std::vector<ImagePair>{};
    PairListing l = ListDatasetPairs(dir);
    for (const fs::path& p : l.images_without_label) spdlog::warn("mix: {} image without label: {}", what, p.string());
    for (const fs::path& p : l.labels_without_image) spdlog::warn("mix: {} label without image: {}", what, p.string());
    return l.pairs;
  };
  for (const fs::path& dir : real_dirs) {
    std::vector<ImagePair> pairs = list(dir, "real");
    // Each folder its own name, so each stays its own room; a review's views
    // are always one room, named by its survey.
    const std::string room = RoomNameOfFolder(dir);
    if (real_dirs.size() > 1 || IsReviewTrainingFolder(dir)) {
      for (ImagePair& p : pairs) p.name = room + "/" + p.name;
    }
    sources.real.insert(sources.real.end(), pairs.begin(), pairs.end());
  }
  sources.synthetic = list(synthetic_dir, "synthetic");
  sources.real_test = list(real_test_dir, "real test");
  fs::path dir = manifest_path.parent_path();
  MixSummary summary = BuildMix(options, sources, dir.empty() ? fs::path(".") : dir, progress);
  if (summary.manifest.test.empty()) spdlog::warn("mix: no real test pairs (no real data given)");
  WriteManifest(summary.manifest, manifest_path);
  return summary;
}

MixSummary MixDataset(const MixOptions& options, const fs::path& real_dir, const fs::path& synthetic_dir,
                      const fs::path& real_test_dir, const fs::path& manifest_path, const ProgressCallback& progress) {
  return MixDataset(options, std::vector<fs::path>{real_dir}, synthetic_dir, real_test_dir, manifest_path, progress);
}

}  // namespace asbuilt
