#ifndef ASBUILT_SEG_SEGMENTER_H_
#define ASBUILT_SEG_SEGMENTER_H_

// Inference with a trained SegFormer: the public face of seg/ for the rest
// of asbuilt (survey, pipeline, MCP). Does not include LibTorch.
//
//   auto seg = LoadSegmenter("models/segformer_b0_asbuilt.pt");
//   cv::Mat labels = seg->Segment(bgr);   // CV_8U, 0 bg, 1 wall, 2 door, 3 window

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "asbuilt/seg/segformer_config.h"
#include "asbuilt/util/fields.h"

namespace asbuilt {

struct SegmentOptions {
  // "whole": the image resized to the model's scale in one pass; "slide":
  // windows of the model's crop size at 2/3 overlap stride, logits averaged
  // (mmseg's slide inference), better for scales far above training.
  std::string mode = "whole";
  // Scale the input is resized to (aspect kept) before inference; 0 = the
  // scale the model was trained at (stored in the checkpoint).
  int scale_width_px = 0;
  int scale_height_px = 0;
  int batch_size = 4;  // Images (whole) or windows (slide) per forward pass.
  void Check() const;
};

// The field list (util/fields.h).
const FieldList<SegmentOptions>& SegmentOptionFields();

// What a checkpoint says about its model.
struct SegmenterInfo {
  SegformerConfig config;
  int scale_width_px = 0, scale_height_px = 0;  // Training base scale.
  int crop_width_px = 0, crop_height_px = 0;
  int epoch = 0;                 // Epochs trained.
  std::int64_t parameters = 0;   // Trainable parameter count.
  nlohmann::json metadata;       // Everything stored in the checkpoint.
  std::string ToString() const;  // "SegFormer b0 (3.7M params), trained 12 epochs at 256x192".
};

class Segmenter {
 public:
  virtual ~Segmenter() = default;
  // Labels (CV_8U, same size as `bgr`, ids 0..classes-1). `bgr` is CV_8UC3.
  virtual cv::Mat Segment(const cv::Mat& bgr) = 0;
  // Several images at once (batched forward passes where sizes allow).
  std::vector<cv::Mat> SegmentBatch(const std::vector<cv::Mat>& bgr) { return SegmentBatch(bgr, nullptr); }
  // The same, and per image how sure the model was: the mean over its
  // pixels of the probability of the class chosen there (0–1), into
  // `mean_confidence` when it is given.
  virtual std::vector<cv::Mat> SegmentBatch(const std::vector<cv::Mat>& bgr, std::vector<double>* mean_confidence) = 0;
  // Per-class probabilities (CV_32F, one Mat per class) at the image size.
  virtual std::vector<cv::Mat> Probabilities(const cv::Mat& bgr) = 0;
  virtual const SegmenterInfo& info() const = 0;
};

// Loads a checkpoint written by TrainSegmenter (or the shipped model).
// Throws InputError naming the file when it is missing, not a checkpoint or
// inconsistent; InvalidArgument for bad options.
std::unique_ptr<Segmenter> LoadSegmenter(const std::filesystem::path& path, const SegmentOptions& options = {});

// Reads only the metadata of a checkpoint.
SegmenterInfo ReadSegmenterInfo(const std::filesystem::path& path);

// Colour overlay of labels on an image (wall blue, door green, window red,
// background unchanged), for `asbuilt segment --overlay` and reports.
cv::Mat LabelOverlay(const cv::Mat& bgr, const cv::Mat& labels, double alpha = 0.5);

// True when this build has LibTorch (ASBUILT_WITH_TORCH).
bool SegmenterAvailable();

}  // namespace asbuilt

#endif  // ASBUILT_SEG_SEGMENTER_H_
