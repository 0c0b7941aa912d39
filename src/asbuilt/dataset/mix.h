#ifndef ASBUILT_DATASET_MIX_H_
#define ASBUILT_DATASET_MIX_H_

// Real/synthetic training mixes (PAPER.md §4.2, §5): a named ratio of real
// (R) and synthetic (S) pairs — R100, S100, RS5050, RS8020, RS2080, any
// RSxxyy with xx + yy = 100 — split 9:1 into train and val, plus a held-out
// test list of real pairs that never enters train or val.
//
// Reproducible and comparable across configs: the test pairs depend only on
// the real pairs and the seed (not on the config), so R100, RS5050 and S100
// built with one seed are evaluated on the same real photos.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "asbuilt/dataset/manifest.h"
#include "asbuilt/dataset/pairs.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

struct MixConfig {
  int real_percent = 50;
  int synthetic_percent = 50;

  // "R100", "S100", "RS5050", "RS8020", … (case-insensitive). nullopt for
  // anything else, or percentages not summing to 100.
  static std::optional<MixConfig> Parse(std::string_view name);
  std::string Name() const;      // Canonical: "R100", "S100", "RS5050".
  std::string ToString() const;  // "RS8020 (80 % real, 20 % synthetic)"
};

struct MixOptions {
  std::string config = "RS5050";
  // Train + val pairs; 0 = as many as the sources allow at the ratio.
  std::int64_t total = 0;
  // Fraction of the mix in train (the rest is val, shared between real and
  // synthetic in the mix's ratio); 0.9 = the paper's 9:1.
  double split = 0.9;
  // Fraction of the real pairs held out as the test list (ignored when an
  // explicit test set is given). Whole rooms are held out, never single views
  // of one: a room is the folder part of a pair's name ("kitchen/review/
  // training/003"), a pair named without one a room of its own. Rooms are
  // drawn until the list holds this fraction (rounded up), the last room
  // always left for training.
  double test_fraction = 0.1;
  std::uint64_t seed = 1;
  // Record SHA-256 of every image and label (reads every file once).
  bool checksums = true;
  int num_threads = 0;  // For checksums; 0 = all cores.

  void Check() const;  // Includes the config name.
};

struct MixSources {
  std::vector<ImagePair> real;       // May be empty for S100.
  std::vector<ImagePair> synthetic;  // May be empty for R100.
  // Explicit held-out real test pairs; empty: hold out
  // options.test_fraction of `real`.
  std::vector<ImagePair> real_test;
};

struct MixSummary {
  Manifest manifest;
  std::int64_t real_available = 0;  // Real pairs left after the test hold-out.
  std::int64_t synthetic_available = 0;
  std::int64_t real_used = 0;  // In train + val.
  std::int64_t synthetic_used = 0;
  double seconds = 0.0;

  // "RS5050 seed 1: 900 train + 100 val (500 real, 500 synthetic), 56 real test; wrote manifest.json"
  std::string BriefReport() const;
};

// Builds the mix; entry paths are relative to `manifest_dir`. Throws
// InvalidArgument for bad options, Error when the sources are too small
// for the requested total ("RS5050 with --total 1000 needs 500 real pairs
// (after holding out 56 for test), have 444"), or when a test image is
// byte-identical to a training or val image (checksums on).
MixSummary BuildMix(const MixOptions& options, const MixSources& sources, const std::filesystem::path& manifest_dir,
                    const ProgressCallback& progress = {});

// The room a real folder shows: its name, or for a review's training folder
// (OUT/review/training) its survey OUT's.
std::string RoomNameOfFolder(const std::filesystem::path& dir);

// Lists the dataset folders (ListDatasetPairs; empty paths are skipped),
// builds the mix and writes the manifest atomically. Several real folders
// (say, survey folders whose reviews were saved: OUT/review/training/) are
// listed each under its own name ("kitchen/…"), so each stays its own room.
MixSummary MixDataset(const MixOptions& options, const std::vector<std::filesystem::path>& real_dirs,
                      const std::filesystem::path& synthetic_dir, const std::filesystem::path& real_test_dir,
                      const std::filesystem::path& manifest_path, const ProgressCallback& progress = {});
MixSummary MixDataset(const MixOptions& options, const std::filesystem::path& real_dir,
                      const std::filesystem::path& synthetic_dir, const std::filesystem::path& real_test_dir,
                      const std::filesystem::path& manifest_path, const ProgressCallback& progress = {});

}  // namespace asbuilt

#endif  // ASBUILT_DATASET_MIX_H_
