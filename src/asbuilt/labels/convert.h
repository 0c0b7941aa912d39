#ifndef ASBUILT_LABELS_CONVERT_H_
#define ASBUILT_LABELS_CONVERT_H_

// ID map → label map (PAPER.md §3.4): each pixel takes the label id of the
// nearest palette colour by Euclidean distance in RGB; a pixel farther than
// the threshold from every palette colour becomes background (0).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/labels/palette.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

struct ConvertOptions {
  // Largest RGB distance (0..255 units, up to 441.7 across the cube) at which
  // a pixel still takes its nearest colour's class; beyond → background.
  // Smaller rejects more lighting drift, larger accepts more stray colours.
  double threshold = 100.0;
  // Worker threads for batches; 0 = all cores.
  int num_threads = 0;

  void Check() const;
};

// Converts one ID map (CV_8UC3, BGR as ReadColourImage gives) to a CV_8UC1 label
// map. Throws InvalidArgument for an empty palette or a wrong image type.
// Optionally counts the pixels sent to background by the threshold.
cv::Mat ConvertIdMap(const cv::Mat& idmap_bgr, const Palette& palette, double threshold,
                     std::int64_t* beyond_threshold = nullptr);

struct ConvertSummary {
  int converted = 0;
  std::vector<Problem> failed;  // One per input that could not be converted.
  std::int64_t pixels = 0;
  std::int64_t beyond_threshold = 0;  // Pixels sent to background by the threshold.
  double seconds = 0.0;

  // "converted 24 ID maps (7.4 Mpx, 0.31 % beyond threshold) in 0.52 s; 1 failed"
  std::string BriefReport() const;
};

// Converts every input file into output_dir/<stem>.png (the same file name
// for PNG inputs), in parallel, each written atomically. A file that cannot
// be read is recorded in `failed` and the others go on.
ConvertSummary ConvertIdMapFiles(const ConvertOptions& options, const Palette& palette,
                                 const std::vector<std::filesystem::path>& idmaps,
                                 const std::filesystem::path& output_dir, const ProgressCallback& progress = {});

// The image files (png, jpg, …) directly inside `dir`, sorted, hidden and
// AtomicFile temp files skipped. Throws InputError if `dir` is not a folder.
std::vector<std::filesystem::path> ListImageFiles(const std::filesystem::path& dir);

}  // namespace asbuilt

#endif  // ASBUILT_LABELS_CONVERT_H_
