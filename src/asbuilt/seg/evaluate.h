#ifndef ASBUILT_SEG_EVALUATE_H_
#define ASBUILT_SEG_EVALUATE_H_

// Evaluating a segmenter on labelled images (PAPER.md §5 metrics, see
// metrics.h). Does not include LibTorch.

#include <array>
#include <cstdint>
#include <stop_token>
#include <string>
#include <vector>

#include "asbuilt/seg/metrics.h"
#include "asbuilt/seg/seg_data.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

struct EvaluateOptions {
  // How the label files' ids map to asbuilt's 4 classes (255 = ignore):
  //   "asbuilt": identity (0..3, 255)
  //   "ade20k":  SceneParsing-150: 0 → ignore, 1 wall → 1, 15 door and
  //              59 screen door → 2, 9 windowpane → 3, other → 0
  //   "nyu40":   NYU-40: 0 → ignore, 1 wall → 1, 8 door → 2, 9 window → 3,
  //              other → 0
  std::string label_map = "asbuilt";
  int max_images = 0;  // 0 = all.
  void Check() const;
};

// The lookup table of a named label map (throws InvalidArgument if unknown).
std::array<std::uint8_t, 256> LabelMapTable(const std::string& name);

// Segments every sample and accumulates the confusion matrix. Throws
// InputError naming a bad image or label file.
SegmentationMetrics EvaluateSegmentation(Segmenter& segmenter, const std::vector<SegSample>& samples,
                                         const EvaluateOptions& options = {}, const ProgressCallback& progress = {},
                                         std::stop_token stop = {});

}  // namespace asbuilt

#endif  // ASBUILT_SEG_EVALUATE_H_
