#ifndef ASBUILT_SEG_EXPERIMENT_H_
#define ASBUILT_SEG_EXPERIMENT_H_

// The paper's ratio experiment (PAPER.md §5): for each real/synthetic mix
// (R100, S100, RS5050, RS8020, …) build the mix (dataset/mix.h), train a
// segmenter on it and evaluate it on the same held-out real test set; write
// the table (mIoU, mFscore, mPrecision, mRecall per config) and a plot.
// Does not include LibTorch.
//
// OUT_DIR/<CONFIG>/manifest.json, OUT_DIR/<CONFIG>/run/ (train.h layout),
// OUT_DIR/<CONFIG>/test_metrics.json, OUT_DIR/results.md (the table),
// results.json ({"rows": [{"config", "mIoU", "mFscore", "mPrecision",
// "mRecall", …}], "extra": […], "options": …}), plot.png (grouped bars).
// Re-running resumes: finished trainings are not repeated.

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
  // Further labelled dataset folders (asbuilt label ids) every config's best
  // checkpoint is also scored on, reported in a second table: e.g. the few
  // real photos there are when --real is a stand-in from another domain.
  std::vector<std::filesystem::path> extra_test_dirs;
  std::vector<std::string> configs = {"R100", "S100", "RS5050", "RS8020"};
  std::int64_t total = 0;         // Train + val pairs per config; 0 = as many as the ratio allows.
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
  int real_train_val = 0, synthetic_train_val = 0;  // Pairs of each source in train + val.
  SegmentationMetrics test;                         // On the real test set, best checkpoint.
  double best_val_miou = 0;                         // NaN without a val set.
  int best_epoch = 0;
  double train_wall_s = 0;  // Training time of this config (across resumes).
  // One per RatioExperimentOptions::extra_test_dirs, same order.
  std::vector<SegmentationMetrics> extra;
};

struct RatioExperimentSummary {
  std::vector<RatioExperimentRow> rows;
  std::vector<std::string> extra_names;  // Folder names of the extra test sets.
  double wall_s = 0;
  // The paper's table (config, pairs, mIoU, mFscore, mPrecision, mRecall),
  // then one table per extra test set.
  std::string ToMarkdown() const;
  std::string BriefReport() const;
};

RatioExperimentSummary RunRatioExperiment(const RatioExperimentOptions& options, const ProgressCallback& progress = {},
                                          std::stop_token stop = {});

}  // namespace asbuilt

#endif  // ASBUILT_SEG_EXPERIMENT_H_
