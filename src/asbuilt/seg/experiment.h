#ifndef ASBUILT_SEG_EXPERIMENT_H_
#define ASBUILT_SEG_EXPERIMENT_H_

// The paper's ratio experiment (PAPER.md §5): for each real/synthetic mix
// (R100, S100, RS5050, RS8020, …) build the mix (dataset/mix.h), train a
// segmenter on it and evaluate it on the same held-out real test set; write
// the table (mIoU, mFscore, mPrecision, mRecall per config) and a plot.
// Does not include LibTorch.
//
// OUT_DIR/<CONFIG>/manifest.json, OUT_DIR/<CONFIG>/run/ (train.h layout),
// OUT_DIR/<CONFIG>/test_metrics.json, OUT_DIR/results.md, results.json,
// plot.png. Re-running resumes: finished trainings are not repeated.

#include <cstdint>
#include <filesystem>
#include <stop_token>
#include <string>
#include <vector>

#include "asbuilt/seg/metrics.h"
#include "asbuilt/seg/train.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

struct RatioExperimentOptions {
  std::filesystem::path real_dir;       // Dataset folder of real pairs.
  std::filesystem::path synthetic_dir;  // Dataset folder of synthetic pairs.
  std::filesystem::path real_test_dir;  // Optional explicit real test set.
  std::vector<std::string> configs = {"R100", "S100", "RS5050", "RS8020"};
  std::int64_t total = 0;  // Train + val pairs per config; 0 = as many as the ratio allows.
  std::filesystem::path out_dir;  // Required.
  // Training settings shared by every config (data paths and out_dir are
  // filled per config).
  TrainOptions train;
  std::uint64_t seed = 1;  // Mix seed (same test set for every config).
  void Check() const;
};

struct RatioExperimentRow {
  std::string config;
  int train_pairs = 0, val_pairs = 0, test_pairs = 0;
  SegmentationMetrics test;  // On the real test set, best checkpoint.
};

struct RatioExperimentSummary {
  std::vector<RatioExperimentRow> rows;
  double wall_s = 0;
  std::string ToMarkdown() const;  // The paper's table.
  std::string BriefReport() const;
};

RatioExperimentSummary RunRatioExperiment(const RatioExperimentOptions& options, const ProgressCallback& progress = {},
                                          std::stop_token stop = {});

}  // namespace asbuilt

#endif  // ASBUILT_SEG_EXPERIMENT_H_
