#ifndef ASBUILT_DATASET_SYNTH_MERGE_H_
#define ASBUILT_DATASET_SYNTH_MERGE_H_

// `asbuilt dataset merge DIR` and `asbuilt dataset verify DIR`: a synthetic
// dataset made by shards (one process or a cluster's array job) becomes one
// manifest, DIR/synth_manifest.json, with every item's files and their
// SHA-256, once every item is there and whole; verify re-hashes every file
// against it. The manifest holds nothing of how the items were made (no
// shard count, no times), so any split of the work, killed and resumed or
// not, gives the same bytes (docs/formats.md "Synthetic datasets").

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "asbuilt/util/error.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

struct SynthMergeOptions {
  int shard_count = 0;  // The run's N, to name the shard of each missing item; 0: items only.
  int num_threads = 0;  // Hashing threads; 0 = all cores.

  void Check() const;
};

struct SynthMergeSummary {
  int items = 0;
  std::int64_t files = 0;
  std::int64_t bytes = 0;
  double seconds = 0.0;
  std::filesystem::path manifest;
  int temps_removed = 0;  // Temp files a killed writer left in the item folders.

  // "merged 400 items (2000 files, 31.2 MB) in 0.8 s → DIR/synth_manifest.json"
  std::string BriefReport() const;
};

// Checks that every item of DIR/synth.json's count is complete and whole (a
// PNG ends with its IEND chunk, a meta file parses and names its own index),
// hashes every file and writes DIR/synth_manifest.json atomically, then
// removes the temp files killed writers left (none can be writing). Throws
// InputError listing every missing item range (with its shard when
// `shard_count` is given) and every damaged file, and writes nothing then.
SynthMergeSummary MergeSynthDataset(const std::filesystem::path& dir, const SynthMergeOptions& options = {},
                                    const ProgressCallback& progress = {});

struct SynthVerifySummary {
  int items = 0;
  std::int64_t files = 0;
  std::vector<Problem> problems;  // A missing or changed file each (file = its path).
  double seconds = 0.0;

  bool ok() const { return problems.empty(); }
  // "verified 400 items (2000 files) in 0.7 s: all match" or "…: 2 problems".
  std::string BriefReport() const;
};

// Re-hashes every file DIR/synth_manifest.json lists. Throws InputError only
// when the manifest itself is missing or unreadable.
SynthVerifySummary VerifySynthDataset(const std::filesystem::path& dir, int num_threads = 0,
                                      const ProgressCallback& progress = {});

}  // namespace asbuilt

#endif  // ASBUILT_DATASET_SYNTH_MERGE_H_
