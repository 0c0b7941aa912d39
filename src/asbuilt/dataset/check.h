#ifndef ASBUILT_DATASET_CHECK_H_
#define ASBUILT_DATASET_CHECK_H_

// `asbuilt dataset check DIR|manifest.json`: validates every (image, label)
// pair — both decodable, the label single-channel 8-bit, same size, ids in
// {0, 1, 2, 3, 255} — and counts class pixels. A bad pair is reported by
// name and the others go on; nothing is written.

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "asbuilt/util/error.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

struct DatasetCheckOptions {
  int num_threads = 0;  // 0 = all cores.

  void Check() const;
};

// Pixel and image counts per class: index 0..3 = background, wall, door,
// window; 4 = ignore (255).
struct ClassHistogram {
  std::int64_t pairs = 0;
  std::array<std::int64_t, 5> pixels{};
  std::array<std::int64_t, 5> images_with{};  // Pairs whose label has the class.

  void Add(const ClassHistogram& other);
  std::string ToString() const;  // "24 pairs: background 61.2 %, wall 30.1 %, …"
};

struct DatasetCheckSummary {
  std::int64_t pairs = 0;  // Pairs checked.
  std::int64_t bad_pairs = 0;
  // Every problem: a bad pair (file = the bad file, message names the pair),
  // a manifest error, an image without label.
  std::vector<Problem> problems;
  // Histograms of the good pairs: by group ("all"; for a manifest also
  // "train", "val", "test", "real", "synthetic").
  std::map<std::string, ClassHistogram> histograms;
  double seconds = 0.0;

  bool ok() const { return problems.empty(); }
  // "checked 24 pairs in 0.31 s: 23 ok, 1 bad, 2 problems"
  std::string BriefReport() const;
  // A fixed-width table: group, pairs, then per class % of pixels and images.
  std::string HistogramTable() const;
};

// `path` is a dataset folder (see ListDatasetPairs) or a manifest file.
// Throws InputError only if `path` is neither (not found, not a dataset).
DatasetCheckSummary CheckDataset(const DatasetCheckOptions& options, const std::filesystem::path& path,
                                 const ProgressCallback& progress = {});

}  // namespace asbuilt

#endif  // ASBUILT_DATASET_CHECK_H_
