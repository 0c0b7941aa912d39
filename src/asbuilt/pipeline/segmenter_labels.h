#ifndef ASBUILT_PIPELINE_SEGMENTER_LABELS_H_
#define ASBUILT_PIPELINE_SEGMENTER_LABELS_H_

// The segmenter (seg/) as a frame loop's LabelSource (stereo/label_source.h):
// it labels the images the loop has already decoded, both views of a stereo
// frame, several frames in one batched forward pass.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/geometry/rig.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/stereo/label_source.h"

namespace asbuilt {

class SegmenterLabels final : public LabelSource {
 public:
  // Loads the model at `model` to segment at `scale_px` (width, height;
  // {0, 0}: its training scale), or, unset, at the images' own size
  // `image_size` up to twice the model's training scale. Throws Error when
  // this build has no segmenter, InputError for a bad model file.
  //
  // With `camera` (the images' pinhole camera) and a vertical field of view
  // wider than kWideViewFovDeg (a panorama's tall turn-in-place views), each
  // image is segmented through three level-width views turned about the
  // camera's x axis (pitch −40°, 0°, +40°, 90° × 90°), warped from it by the
  // rotation's homography, and their probabilities are warped back and
  // blended by how near each pixel's ray lies to each view's axis: the
  // segmenters were trained on ordinary photos, and read the stretched floor
  // and ceiling at a tall view's ends as wall.
  SegmenterLabels(const std::filesystem::path& model, std::optional<std::pair<int, int>> scale_px, cv::Size image_size,
                  std::optional<PinholeCamera> camera = std::nullopt);

  static constexpr double kWideViewFovDeg = 100.0;

  // Four images a pass (two stereo frames): per image the fastest batch of
  // the shipped model on CPU (docs/survey.md "Structure").
  int BatchImages() const override { return 4; }
  std::vector<FrameLabels> Label(const std::vector<FrameImages>& frames) override;
  std::string Describe() const override { return description_; }
  std::string StageName() const override { return "segment"; }
  double MeanConfidence() const override;

 private:
  // One turned view: the homography from the wide image to it, and each wide
  // pixel's blending weight for it (they depend on the camera only).
  struct TurnedView {
    cv::Mat image_to_turned;
    int side_px = 0;
    cv::Mat weight;  // CV_32F, the wide image's size.
  };
  static std::vector<TurnedView> TurnedViews(const PinholeCamera& camera);
  // Labels of one wide image through the turned views, and the mean over
  // its pixels of the blended probability of the class chosen.
  cv::Mat SegmentWide(const cv::Mat& bgr, double& confidence) const;

  std::unique_ptr<Segmenter> segmenter_;
  std::optional<PinholeCamera> wide_camera_;  // Set when the images are wide views.
  std::vector<TurnedView> turned_;
  std::string description_;
  double confidence_sum_ = 0.0;  // Of each image labelled, its mean confidence.
  int images_labelled_ = 0;
};

}  // namespace asbuilt

#endif  // ASBUILT_PIPELINE_SEGMENTER_LABELS_H_
