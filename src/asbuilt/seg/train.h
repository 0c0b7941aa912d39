#ifndef ASBUILT_SEG_TRAIN_H_
#define ASBUILT_SEG_TRAIN_H_

// Training SegFormer (PAPER.md §5): AdamW, poly schedule with linear warm-up,
// mmseg-style augmentation, validation every epoch, atomic checkpoints and
// resume after a kill. Does not include LibTorch.
//
// OUT_DIR after a run:
//   options.json   the fully resolved options (written before training)
//   last.pt        model + optimizer + history, after every epoch (atomic)
//   best.pt        model only, best validation mIoU so far (atomic)
//   log.csv, log.jsonl   one row per epoch (rewritten atomically from history)
//   plot.png       training loss and validation mIoU per epoch

#include <cstdint>
#include <filesystem>
#include <stop_token>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/seg/distributed.h"
#include "asbuilt/seg/seg_data.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

struct TrainOptions {
  // Data: a manifest (dataset/manifest.h), or image + label folders split
  // 9:1 by `seed` (labels_dir empty: a dataset folder, see SplitFromFolders).
  std::filesystem::path manifest;
  std::filesystem::path images_dir;
  std::filesystem::path labels_dir;
  double val_fraction = 0.1;      // Folders only: share held out for validation.
  std::filesystem::path out_dir;  // Required.

  std::string arch = "b0";  // b0, b1, b2 (published), tiny (b0, decoder 128), or
                            // tflite: the TFLite graph of `init` (a .tflite file
                            // or an asbuilt-tflite checkpoint), fine-tuned
                            // through asbuilt's class groups (tflite_segmenter.h).
  int num_classes = 4;
  int epochs = 50;             // Paper: 50.
  int steps_per_epoch = 0;     // 0 = ceil(train pairs / batch); else a fixed count.
  int batch_size = 2;          // Paper: 2. Global: K ranks read batch_size/K each.
  double lr = 1e-4;            // AdamW learning rate (paper: 1e-4).
  double weight_decay = 1e-3;  // AdamW weight decay (paper: 1e-3).
  double head_lr_mult = 1.0;   // Decoder lr multiplier (mmseg SegFormer: 10).
  int warmup_steps = 0;        // Linear warm-up from warmup_ratio·lr; 0 = none.
  double warmup_ratio = 1e-6;
  double poly_power = 1.0;      // lr = base · (1 − step/total)^power, min 0.
  double drop_path_rate = 0.1;  // Stochastic depth.
  AugmentOptions augment;       // Scale, crop, flip, photometric, blur/noise.
  int val_max_images = 0;       // Validate on at most this many (0 = all).
  std::uint64_t seed = 0;       // Split, sampling order, augmentation, init.
  std::filesystem::path init;   // Load these weights first (non-strict: a
                                // different head or missing tensors are skipped).
  bool resume = true;           // Continue from out_dir/last.pt if present.
  int stop_after_epoch = 0;     // End this run after that epoch (0 = run to
                                // `epochs`); the schedule still spans `epochs`.
  int threads = 0;              // LibTorch intra-op threads; 0 = every core.

  // This process's rank among K training together (world_size 1: alone;
  // docs/seg.md "Distributed training").
  DistributedOptions distributed;

  void Check() const;
  nlohmann::json ToJson() const;
};

// The field list of the options above that are not paths (util/fields.h);
// `augment.*` nests AugmentOptionFields, `dist_timeout_s` is
// distributed.timeout_s.
const FieldList<TrainOptions>& TrainOptionFields();

struct EpochRecord {
  int epoch = 0;
  std::int64_t step = 0;
  double lr = 0;
  double train_loss = 0;  // Mean over the epoch's steps.
  double val_miou = 0, val_mfscore = 0, val_mprecision = 0, val_mrecall = 0, val_aacc = 0;  // NaN: no val set.
  double wall_s = 0;  // Since the run started (across resumes).
  nlohmann::json ToJson() const;
};

struct TrainSummary {
  std::filesystem::path out_dir;
  int epochs_done = 0;
  int resumed_from_epoch = 0;  // 0 = fresh start.
  std::int64_t steps = 0;
  int train_pairs = 0, val_pairs = 0;
  double first_loss = 0, last_loss = 0;  // Mean training loss, first / last epoch.
  double best_miou = 0;                  // NaN when there is no validation set.
  int best_epoch = 0;
  double wall_s = 0;
  bool stopped = false;  // Stop requested: ended after the last checkpoint.
  std::vector<EpochRecord> history;
  std::string BriefReport() const;
};

// The options that continue training the model `info` describes (read from
// `model`, a checkpoint of either kind or a .tflite file) on new data, as
// `asbuilt train --finetune` and `asbuilt learn` do: its architecture, its
// training scale and crop and the same augmentation, a lower rate and a short
// schedule (8 epochs of 50 steps, batch 8; docs/seg.md "Fine-tuning"). The
// caller sets the data and the output folder.
TrainOptions FinetuneOptions(const std::filesystem::path& model, const SegmenterInfo& info);

// Trains (or resumes) and writes OUT_DIR as described above. Throws
// InvalidArgument for bad options, InputError for bad data (naming the file).
//
// Distributed (options.distributed.world_size = K > 1; every rank calls this
// with the same options but its rank): data-parallel over c10d's Gloo process
// group. Rank r reads and augments the r-th K-th of each global batch, the
// loss is the global batch's mean, gradients are summed over the ranks and
// the decoder's batch norm is synchronised, so the run follows a single
// process's up to rounding. Rank 0 writes every file and reports progress;
// validation is split between the ranks. Every rank resumes from
// OUT_DIR/last.pt (a shared folder). Errors name the rank ("rank 1 of 2: …");
// a rank that dies makes the others fail within options.distributed.timeout_s.
TrainSummary TrainSegmenter(const TrainOptions& options, const ProgressCallback& progress = {},
                            std::stop_token stop = {});

}  // namespace asbuilt

#endif  // ASBUILT_SEG_TRAIN_H_
