#ifndef ASBUILT_SEG_LEARN_H_
#define ASBUILT_SEG_LEARN_H_

// Learning from corrections (issue 38, `asbuilt learn`): each survey a
// surveyor corrected and saved in `asbuilt review` holds a labelled real room
// (OUT/review/training/: the survey's views and labels drawn from the
// corrected plan). One call cuts a panorama's tall views into level views
// (dataset/level_views.h), mixes those rooms with renders (split by room,
// never by view), fine-tunes the current model on the mix (train.h
// FinetuneOptions), scores the old and the new model on the held-out rooms
// and keeps the new one only when it is better there. Does not include
// LibTorch.
//
// OUT_DIR after a run:
//   views/NAME/   each room's views as level views (test/views/NAME: a --hold-out room)
//   mix.json      the mix (dataset/manifest.h); its test list is the held-out rooms
//   train/        the fine-tuning run (train.h layout; re-running resumes it)
//   report.md     old vs new per class on the held-out rooms, and the decision
//   report.json   the same as data
//   model.pt      the new model, only when it is better on the held-out rooms

#include <cstdint>
#include <filesystem>
#include <stop_token>
#include <string>
#include <vector>

#include "asbuilt/seg/metrics.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

struct LearnOptions {
  // Survey folders whose review was saved, their review/training folders, or
  // folders holding such survey folders.
  std::vector<std::filesystem::path> reviews;
  std::filesystem::path model;          // The model to improve (required).
  std::filesystem::path synthetic_dir;  // Renders to mix in (dataset synth); empty: real rooms only (R100).
  std::string config = "RS5050";        // The mix (dataset/mix.h); R100 without renders.
  double test_fraction = 0.25;          // Share of the real rooms held out to judge on.
  // A review (as in `reviews`) to judge on instead, kept out of training even
  // when `reviews` lists it: leave-one-room-out runs name each room in turn.
  std::filesystem::path hold_out;
  std::uint64_t seed = 1;         // Which rooms are held out; the training order.
  std::filesystem::path out_dir;  // Required.
  int epochs = 0;                 // 0: FinetuneOptions' schedule.
  int steps_per_epoch = 0;
  int threads = 0;  // LibTorch threads; 0 = every core.
  void Check() const;
};

struct LearnSummary {
  std::vector<std::filesystem::path> examples;  // The review/training folders used.
  std::int64_t train_pairs = 0, val_pairs = 0, test_pairs = 0;
  SegmentationMetrics before, after;  // On the held-out rooms' views.
  bool improved = false;              // after.miou > before.miou: OUT/model.pt written.
  double train_s = 0, wall_s = 0;
  std::string ToMarkdown() const;   // The per-class table and the decision.
  std::string BriefReport() const;  // One line.
};

// The review/training folders `paths` name (as LearnOptions::reviews), in
// order. Throws InputError naming a path that is missing or holds no saved
// review (with what to run to make one).
std::vector<std::filesystem::path> FindReviewExamples(const std::vector<std::filesystem::path>& paths);

LearnSummary LearnFromReviews(const LearnOptions& options, const ProgressCallback& progress = {},
                              std::stop_token stop = {});

}  // namespace asbuilt

#endif  // ASBUILT_SEG_LEARN_H_
