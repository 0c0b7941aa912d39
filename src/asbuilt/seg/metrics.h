#ifndef ASBUILT_SEG_METRICS_H_
#define ASBUILT_SEG_METRICS_H_

// Segmentation metrics with mmsegmentation's IoUMetric definitions
// (PAPER.md §5: mIoU, mFscore, mPrecision, mRecall). Per class c, over all
// pixels whose label is not ignored:
//   intersect_c = #(pred = c ∧ label = c), pred_c = #(pred = c),
//   label_c = #(label = c), union_c = pred_c + label_c − intersect_c
//   IoU = intersect/union, Precision = intersect/pred, Recall = Acc = intersect/label,
//   Fscore = 2·P·R/(P + R) (β = 1), aAcc = Σ intersect / Σ label.
// A ratio with a zero denominator is NaN (as torch computes it), and means
// skip NaN (numpy nanmean), so a class absent from labels and predictions
// does not count. No LibTorch here.

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

namespace asbuilt {

// counts[label][pred] over non-ignored pixels.
class ConfusionMatrix {
 public:
  explicit ConfusionMatrix(int num_classes = 4);
  int num_classes() const { return num_classes_; }
  // Accumulates one image: `label` and `pred` CV_8U of the same size.
  // Label pixels equal to `ignore_label` or ≥ num_classes are skipped.
  // Throws InvalidArgument on size/type mismatch or a prediction out of range.
  void Add(const cv::Mat& label, const cv::Mat& pred, int ignore_label = 255);
  void Add(int label, int pred, std::int64_t count = 1);
  void Merge(const ConfusionMatrix& other);
  std::int64_t at(int label, int pred) const { return counts_[label * num_classes_ + pred]; }
  std::int64_t total() const;
  std::int64_t ignored_pixels() const { return ignored_; }

 private:
  int num_classes_;
  std::vector<std::int64_t> counts_;
  std::int64_t ignored_ = 0;
};

struct ClassMetrics {
  std::string name;
  std::int64_t intersect = 0, union_ = 0, pred_pixels = 0, label_pixels = 0;
  double iou = 0, fscore = 0, precision = 0, recall = 0;  // NaN when undefined.
};

struct SegmentationMetrics {
  std::vector<ClassMetrics> classes;
  double miou = 0, mfscore = 0, mprecision = 0, mrecall = 0;  // nanmean over classes.
  double aacc = 0;                                            // Pixel accuracy.
  std::int64_t images = 0;
  ConfusionMatrix confusion{4};

  // "mIoU 0.812 mFscore 0.893 mPrecision 0.901 mRecall 0.887 aAcc 0.934 (12 images)".
  std::string BriefReport() const;
  // Per-class table + means + confusion matrix, Markdown (NaN prints as "nan").
  std::string ToMarkdown() const;
  nlohmann::json ToJson() const;
};

// Names for 4 classes: background, wall, door, window.
std::vector<std::string> DefaultClassNames();

// Computes every metric from the matrix. `class_names` may be empty
// (then "class<i>") and must otherwise have num_classes entries.
SegmentationMetrics ComputeMetrics(const ConfusionMatrix& confusion,
                                   const std::vector<std::string>& class_names = DefaultClassNames());

// The metrics a ToJson() wrote, recomputed from its confusion matrix, image
// count and class names. Throws InputError naming `file` and the field.
SegmentationMetrics MetricsFromJson(const nlohmann::json& json, const std::string& file);

// The metrics of several parts of one evaluation (shards of its images): the
// confusion matrices and image counts summed, every metric recomputed, so the
// result is the whole evaluation's, exactly. Throws InvalidArgument when the
// parts' classes differ.
SegmentationMetrics MergeMetrics(const std::vector<SegmentationMetrics>& parts);

}  // namespace asbuilt

#endif  // ASBUILT_SEG_METRICS_H_
