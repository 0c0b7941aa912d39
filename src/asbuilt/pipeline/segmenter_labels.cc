#include "asbuilt/pipeline/segmenter_labels.h"

#include <tuple>

#include <fmt/format.h>

#include "asbuilt/seg/seg_data.h"
#include "asbuilt/util/error.h"

namespace asbuilt {

SegmenterLabels::SegmenterLabels(const std::filesystem::path& model, std::optional<std::pair<int, int>> scale_px,
                                 cv::Size image_size) {
  if (!SegmenterAvailable()) {
    throw Error("this build has no segmenter (built without LibTorch): pass --labels DIR");
  }
  SegmentOptions segment;
  if (scale_px) {
    std::tie(segment.scale_width_px, segment.scale_height_px) = *scale_px;
  } else {
    const SegmenterInfo info = ReadSegmenterInfo(model);
    const cv::Size twice = FitSize(image_size, 2 * info.scale_width_px, 2 * info.scale_height_px);
    const cv::Size scale = twice.width < image_size.width ? twice : image_size;
    segment.scale_width_px = scale.width;
    segment.scale_height_px = scale.height;
  }
  segmenter_ = LoadSegmenter(model, segment);
  description_ = fmt::format("segmenter {} ({}) at {}", model.filename().string(), segmenter_->info().ToString(),
                             segment.scale_width_px > 0
                                 ? fmt::format("{}x{}", segment.scale_width_px, segment.scale_height_px)
                                 : std::string("its training scale"));
}

std::vector<FrameLabels> SegmenterLabels::Label(const std::vector<FrameImages>& frames) {
  // Every image of the frames in one batch: left, right, left, right, … .
  std::vector<cv::Mat> images;
  for (const FrameImages& f : frames) {
    images.push_back(f.left);
    if (!f.right.empty()) images.push_back(f.right);
  }
  std::vector<cv::Mat> segmented = segmenter_->SegmentBatch(images);
  std::vector<FrameLabels> out;
  std::size_t next = 0;
  for (const FrameImages& f : frames) {
    FrameLabels labels{.left = std::move(segmented.at(next++))};
    if (!f.right.empty()) labels.right = std::move(segmented.at(next++));
    out.push_back(std::move(labels));
  }
  return out;
}

}  // namespace asbuilt
