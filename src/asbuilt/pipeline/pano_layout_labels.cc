#include "asbuilt/pipeline/pano_layout_labels.h"

#include <chrono>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/util/error.h"

namespace asbuilt {

PanoLayoutLabels::PanoLayoutLabels(std::unique_ptr<LabelSource> inner, const cv::Mat& equirect_bgr,
                                   const std::vector<PanoView>& views, const std::vector<cv::Mat>& images,
                                   double camera_height_m, const PanoLayoutOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  CheckArgument(inner != nullptr, "PanoLayoutLabels: no label source");
  CheckArgument(views.size() == images.size(),
                fmt::format("PanoLayoutLabels: {} views but {} images", views.size(), images.size()));
  inner_description_ = inner->Describe();
  // The inner labels of every view, a batch at a time.
  std::vector<cv::Mat> inner_labels;
  const std::size_t batch = static_cast<std::size_t>(std::max(1, inner->BatchImages()));
  for (std::size_t first = 0; first < images.size(); first += batch) {
    std::vector<FrameImages> frames;
    for (std::size_t i = first; i < std::min(images.size(), first + batch); ++i) {
      frames.push_back({.frame = {.index = static_cast<int>(i)}, .left = images[i]});
    }
    for (FrameLabels& l : inner->Label(frames)) inner_labels.push_back(std::move(l.left));
  }
  inner_confidence_ = inner->MeanConfidence();
  const cv::Mat gathered = EquirectFromViewLabels(views, inner_labels, options.width_px);
  layout_ = EstimatePanoLayout(equirect_bgr, camera_height_m, gathered, options);
  spdlog::info("survey: {}", layout_.BriefReport());
  for (std::size_t i = 0; i < views.size(); ++i)
    labels_.push_back(LayoutViewLabels(layout_, views[i], options.openings_from_labels ? inner_labels[i] : cv::Mat()));
  picture_ = DrawPanoLayout(equirect_bgr, layout_);
  seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<FrameLabels> PanoLayoutLabels::Label(const std::vector<FrameImages>& frames) {
  std::vector<FrameLabels> out;
  for (const FrameImages& f : frames) {
    CheckArgument(f.frame.index >= 0 && f.frame.index < static_cast<int>(labels_.size()),
                  fmt::format("PanoLayoutLabels: no view {}", f.frame.index));
    out.push_back({.left = labels_[f.frame.index].clone()});
  }
  return out;
}

std::string PanoLayoutLabels::Describe() const {
  return fmt::format("{}, redrawn on the panorama's layout (its edges and these labels; ceiling {:.2f} m)",
                     inner_description_, layout_.ceiling_height_m);
}

}  // namespace asbuilt
