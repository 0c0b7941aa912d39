#include "asbuilt/seg/evaluate.h"

#include <fmt/format.h>
#include <opencv2/core.hpp>

#include "asbuilt/imageio/image_io.h"
#include "asbuilt/util/error.h"

namespace asbuilt {

void EvaluateOptions::Check() const {
  LabelMapTable(label_map);
  CheckArgument(max_images >= 0, fmt::format("EvaluateOptions.max_images = {}, must be >= 0", max_images));
}

std::array<std::uint8_t, 256> LabelMapTable(const std::string& name) {
  std::array<std::uint8_t, 256> t{};
  if (name == "asbuilt") {
    for (int i = 0; i < 256; ++i) t[i] = static_cast<std::uint8_t>(i);
  } else if (name == "ade20k") {
    t.fill(0);
    t[0] = 255;
    t[1] = 1;
    t[15] = 2;
    t[59] = 2;
    t[9] = 3;
  } else if (name == "nyu40") {
    t.fill(0);
    t[0] = 255;
    t[1] = 1;
    t[8] = 2;
    t[9] = 3;
  } else {
    throw InvalidArgument(fmt::format("label map '{}' unknown; known: asbuilt, ade20k, nyu40", name));
  }
  return t;
}

SegmentationMetrics EvaluateSegmentation(Segmenter& segmenter, const std::vector<SegSample>& samples,
                                         const EvaluateOptions& options, const ProgressCallback& progress,
                                         std::stop_token stop) {
  options.Check();
  const auto table = LabelMapTable(options.label_map);
  const int n_classes = segmenter.info().config.num_classes;
  ConfusionMatrix cm(n_classes);
  size_t n = samples.size();
  if (options.max_images > 0) n = std::min(n, static_cast<size_t>(options.max_images));
  std::int64_t images = 0;
  for (size_t i = 0; i < n && !stop.stop_requested(); ++i) {
    const cv::Mat bgr = ReadColourImage(samples[i].image);
    const cv::Mat label = ReadLabelImage(samples[i].label);
    CheckImageSize(label, bgr.cols, bgr.rows, samples[i].label, "", "its image " + samples[i].image.string());
    cv::Mat mapped(label.size(), CV_8UC1);
    for (int r = 0; r < label.rows; ++r) {
      const std::uint8_t* s = label.ptr<std::uint8_t>(r);
      std::uint8_t* d = mapped.ptr<std::uint8_t>(r);
      for (int c = 0; c < label.cols; ++c) d[c] = table[s[c]];
    }
    cm.Add(mapped, segmenter.Segment(bgr));
    ++images;
    ReportProgress(progress, {.stage = "evaluate", .done = images, .total = static_cast<std::int64_t>(n)});
  }
  SegmentationMetrics m = ComputeMetrics(cm);
  m.images = images;
  return m;
}

}  // namespace asbuilt
