// Parts of segmenter.h that need no LibTorch (built with and without it).
#include <fmt/format.h>

#include "asbuilt/geometry/label_class.h"
#include "asbuilt/seg/model_file.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/util/error.h"

namespace asbuilt {

const FieldList<SegmentOptions>& SegmentOptionFields() {
  using O = SegmentOptions;
  static const FieldList<O> kList = {
      BindChoice(&O::mode, {.name = "mode",
                            .description = "whole: the image at the model's scale in one pass; slide: windows of the "
                                           "training crop at a 2/3 stride, logits averaged.",
                            .choices = {"whole", "slide"}}),
      Bind(&O::scale_width_px, {.name = "scale_width_px",
                                .description = "Inference scale the image is fitted to, px (0 = the model's training "
                                               "scale).",
                                .minimum = 0.0}),
      Bind(&O::scale_height_px, {.name = "scale_height_px", .description = "… its height, px.", .minimum = 0.0}),
      Bind(
          &O::batch_size,
          {.name = "batch_size", .description = "Images (whole) or windows (slide) per forward pass.", .minimum = 1.0}),
  };
  return kList;
}

void SegmentOptions::Check() const {
  SegmentOptionFields().CheckValues(*this, "SegmentOptions");
  CheckArgument(
      (scale_width_px == 0) == (scale_height_px == 0),
      fmt::format("SegmentOptions scale {}x{}: give both or neither (0 = model's)", scale_width_px, scale_height_px));
}

std::string SegmenterInfo::ToString() const {
  if (metadata.is_object() && metadata.value("format", "") == "tflite") {
    return fmt::format("TFLite {} ({:.2f}M params, {} ADE20K classes mapped to {}), read at {}x{}",
                       metadata.value("file", "?"), parameters / 1e6, metadata.value("source_classes", 0),
                       config.num_classes, scale_width_px, scale_height_px);
  }
  if (metadata.is_object() && metadata.value("format", "") == "asbuilt-tflite-v1") {
    return fmt::format(
        "TFLite graph fine-tuned by asbuilt ({:.2f}M params, {} ADE20K classes mapped to {}), trained "
        "{} epoch{} at {}x{}",
        parameters / 1e6, metadata["config"].value("source_classes", 0), config.num_classes, epoch,
        epoch == 1 ? "" : "s", scale_width_px, scale_height_px);
  }
  return fmt::format("SegFormer {} ({:.2f}M params, {} classes), trained {} epoch{} at {}x{}", config.arch,
                     parameters / 1e6, config.num_classes, epoch, epoch == 1 ? "" : "s", scale_width_px,
                     scale_height_px);
}

cv::Mat LabelOverlay(const cv::Mat& bgr, const cv::Mat& labels, double alpha) {
  CheckArgument(bgr.type() == CV_8UC3 && labels.type() == CV_8UC1 && bgr.size() == labels.size(),
                "LabelOverlay: needs an 8-bit BGR image and 8-bit labels of the same size");
  static const cv::Vec3b kColours[4] = {{0, 0, 0}, {255, 128, 0}, {0, 200, 0}, {0, 0, 255}};
  cv::Mat out = bgr.clone();
  for (int r = 0; r < out.rows; ++r) {
    cv::Vec3b* o = out.ptr<cv::Vec3b>(r);
    const std::uint8_t* l = labels.ptr<std::uint8_t>(r);
    for (int c = 0; c < out.cols; ++c) {
      if (l[c] == kLabelBackground || l[c] > kLabelWindow) continue;
      for (int k = 0; k < 3; ++k) {
        o[c][k] = static_cast<std::uint8_t>((1 - alpha) * o[c][k] + alpha * kColours[l[c]][k]);
      }
    }
  }
  return out;
}

#ifdef ASBUILT_SEG_NO_TORCH
std::unique_ptr<Segmenter> LoadSegmenter(const std::filesystem::path& path, const SegmentOptions&) {
  throw Error(path.string() + ": this asbuilt was built without LibTorch (ASBUILT_WITH_TORCH=OFF)");
}
SegmenterInfo ReadSegmenterInfo(const std::filesystem::path& path) {
  throw Error(path.string() + ": this asbuilt was built without LibTorch (ASBUILT_WITH_TORCH=OFF)");
}
bool SegmenterAvailable() { return false; }
SegmenterInfo ExportModel(const std::filesystem::path& checkpoint, const std::filesystem::path&) {
  throw Error(checkpoint.string() + ": this asbuilt was built without LibTorch (ASBUILT_WITH_TORCH=OFF)");
}
SegmenterInfo ImportModel(const std::filesystem::path& in, const std::filesystem::path&) {
  throw Error(in.string() + ": this asbuilt was built without LibTorch (ASBUILT_WITH_TORCH=OFF)");
}
#endif

}  // namespace asbuilt
