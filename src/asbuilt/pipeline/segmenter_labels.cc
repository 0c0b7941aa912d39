#include "asbuilt/pipeline/segmenter_labels.h"

#include <cmath>
#include <tuple>

#include <fmt/format.h>

#include <opencv2/imgproc.hpp>

#include "asbuilt/seg/seg_data.h"
#include "asbuilt/util/error.h"

namespace asbuilt {

namespace {

constexpr double kTurnedPitchDeg = 40.0;

// K of a pinhole camera.
cv::Matx33d Intrinsics(double fx, double fy, double cx, double cy) { return {fx, 0, cx, 0, fy, cy, 0, 0, 1}; }

// Rotation taking a ray in the image camera's frame (x right, y down, z
// forward) to the frame of a camera pitched up by `pitch_rad` about x.
cv::Matx33d PitchUp(double pitch_rad) {
  const double c = std::cos(pitch_rad), s = std::sin(pitch_rad);
  return {1, 0, 0, 0, c, s, 0, -s, c};
}

}  // namespace

SegmenterLabels::SegmenterLabels(const std::filesystem::path& model, std::optional<std::pair<int, int>> scale_px,
                                 cv::Size image_size, std::optional<PinholeCamera> camera) {
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
  if (camera && 2 * std::atan2(camera->height_px / 2.0, camera->fy) * 180 / CV_PI > kWideViewFovDeg) {
    wide_camera_ = camera;
    turned_ = TurnedViews(*camera);
    // The turned views are as wide as the image and square: segment them at
    // the scale a square of that width gets.
    if (!scale_px) {
      const SegmenterInfo info = ReadSegmenterInfo(model);
      const cv::Size square(image_size.width, image_size.width);
      const cv::Size twice = FitSize(square, 2 * info.scale_width_px, 2 * info.scale_height_px);
      const cv::Size scale = twice.width < square.width ? twice : square;
      segment.scale_width_px = scale.width;
      segment.scale_height_px = scale.height;
    }
  }
  segmenter_ = LoadSegmenter(model, segment);
  description_ =
      fmt::format("segmenter {} ({}) at {}", model.filename().string(), segmenter_->info().ToString(),
                  segment.scale_width_px > 0 ? fmt::format("{}x{}", segment.scale_width_px, segment.scale_height_px)
                                             : std::string("its training scale"));
  if (wide_camera_) {
    description_ += fmt::format(", each view read as three {:.0f}°-turned square views", kTurnedPitchDeg);
  }
}

std::vector<SegmenterLabels::TurnedView> SegmenterLabels::TurnedViews(const PinholeCamera& cam) {
  const cv::Matx33d k_image = Intrinsics(cam.fx, cam.fy, cam.cx, cam.cy);
  const int side = cam.width_px;
  const double f_turned = side / 2.0;  // 90° across.
  const cv::Matx33d k_turned = Intrinsics(f_turned, f_turned, (side - 1) / 2.0, (side - 1) / 2.0);
  std::vector<TurnedView> views;
  for (double pitch_deg : {-kTurnedPitchDeg, 0.0, kTurnedPitchDeg}) {
    const cv::Matx33d rotation = PitchUp(pitch_deg * CV_PI / 180);
    TurnedView view{.image_to_turned = cv::Mat(k_turned * rotation * k_image.inv()), .side_px = side};
    // Each image pixel's weight: how near its ray is to this view's axis,
    // zero where the ray leaves the turned view.
    view.weight.create(cam.height_px, cam.width_px, CV_32F);
    const cv::Matx33d to_turned = rotation * k_image.inv();
    for (int v = 0; v < cam.height_px; ++v) {
      auto* w = view.weight.ptr<float>(v);
      for (int u = 0; u < cam.width_px; ++u) {
        const cv::Vec3d d = to_turned * cv::Vec3d(u, v, 1);
        const double z = d[2] / cv::norm(d);
        const bool inside = d[2] > 0 && std::abs(d[0] / d[2]) <= 1 && std::abs(d[1] / d[2]) <= 1;
        w[u] = inside ? static_cast<float>(std::pow(z, 8.0)) : 0.f;
      }
    }
    views.push_back(std::move(view));
  }
  return views;
}

cv::Mat SegmenterLabels::SegmentWide(const cv::Mat& bgr, double& confidence) const {
  CheckArgument(bgr.cols == wide_camera_->width_px && bgr.rows == wide_camera_->height_px,
                "SegmenterLabels: a wide view is not the size of its camera");
  std::vector<cv::Mat> sum;  // Per class, weighted probabilities.
  for (const TurnedView& view : turned_) {
    cv::Mat turned;
    cv::warpPerspective(bgr, turned, view.image_to_turned, cv::Size(view.side_px, view.side_px), cv::INTER_LINEAR,
                        cv::BORDER_REPLICATE);
    std::vector<cv::Mat> p = segmenter_->Probabilities(turned);
    if (sum.empty()) sum.assign(p.size(), cv::Mat());
    for (std::size_t c = 0; c < p.size(); ++c) {
      cv::Mat back;
      cv::warpPerspective(p[c], back, view.image_to_turned, bgr.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                          cv::BORDER_CONSTANT, cv::Scalar(0));
      back = back.mul(view.weight);
      if (sum[c].empty())
        sum[c] = back;
      else
        sum[c] += back;
    }
  }
  // argmax of the blended probabilities; the chosen class's share of the
  // pixel's total weight is its blended probability.
  cv::Mat labels(bgr.size(), CV_8U, cv::Scalar(0));
  double top_sum = 0.0;
  for (int v = 0; v < bgr.rows; ++v) {
    auto* out = labels.ptr<uchar>(v);
    for (int u = 0; u < bgr.cols; ++u) {
      float best = -1, total = 0;
      for (std::size_t c = 0; c < sum.size(); ++c) {
        const float value = sum[c].at<float>(v, u);
        total += value;
        if (value > best) best = value, out[u] = static_cast<uchar>(c);
      }
      if (total > 0) top_sum += best / total;
    }
  }
  confidence = top_sum / static_cast<double>(labels.total());
  return labels;
}

std::vector<FrameLabels> SegmenterLabels::Label(const std::vector<FrameImages>& frames) {
  // Every image of the frames in one batch: left, right, left, right, … .
  std::vector<cv::Mat> images;
  for (const FrameImages& f : frames) {
    images.push_back(f.left);
    if (!f.right.empty()) images.push_back(f.right);
  }
  std::vector<cv::Mat> segmented;
  std::vector<double> confidence(images.size(), 0.0);
  if (wide_camera_) {
    for (std::size_t i = 0; i < images.size(); ++i) segmented.push_back(SegmentWide(images[i], confidence[i]));
  } else {
    segmented = segmenter_->SegmentBatch(images, &confidence);
  }
  for (double c : confidence) confidence_sum_ += c;
  images_labelled_ += static_cast<int>(images.size());
  std::vector<FrameLabels> out;
  std::size_t next = 0;
  for (const FrameImages& f : frames) {
    FrameLabels labels{.left = std::move(segmented.at(next++))};
    if (!f.right.empty()) labels.right = std::move(segmented.at(next++));
    out.push_back(std::move(labels));
  }
  return out;
}

double SegmenterLabels::MeanConfidence() const {
  return images_labelled_ > 0 ? confidence_sum_ / images_labelled_ : NAN;
}

}  // namespace asbuilt
