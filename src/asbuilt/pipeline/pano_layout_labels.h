#ifndef ASBUILT_PIPELINE_PANO_LAYOUT_LABELS_H_
#define ASBUILT_PIPELINE_PANO_LAYOUT_LABELS_H_

// A panorama survey's labels redrawn on the room's layout (pano/pano_layout.h):
// another LabelSource (the segmenter) labels every view once, its labels are
// gathered into the panorama, the layout is estimated from the panorama's
// edges with them as a guide, and each view's labels become the layout's
// wall band (its floor and ceiling edges) with the segmenter's doors and
// windows inside it.

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/pano/pano_layout.h"
#include "asbuilt/stereo/label_source.h"

namespace asbuilt {

class PanoLayoutLabels final : public LabelSource {
 public:
  // Labels `images` (view i seen by views[i]; frames indexed 0..n−1) with
  // `inner` and builds the layout of `equirect_bgr` from camera_height_m.
  // Throws what `inner` or EstimatePanoLayout throws.
  PanoLayoutLabels(std::unique_ptr<LabelSource> inner, const cv::Mat& equirect_bgr, const std::vector<PanoView>& views,
                   const std::vector<cv::Mat>& images, double camera_height_m, const PanoLayoutOptions& options);

  std::vector<FrameLabels> Label(const std::vector<FrameImages>& frames) override;
  std::string Describe() const override;
  std::string StageName() const override { return "layout labels"; }
  double MeanConfidence() const override { return inner_confidence_; }  // The segmenter's, on the views.

  const PanoLayout& layout() const { return layout_; }
  const cv::Mat& picture() const { return picture_; }  // The panorama with the layout drawn (DrawPanoLayout).
  double seconds() const { return seconds_; }          // Segmenting and layout, in the constructor.

 private:
  std::string inner_description_;
  double inner_confidence_ = NAN;
  PanoLayout layout_;
  std::vector<cv::Mat> labels_;  // Per view.
  cv::Mat picture_;
  double seconds_ = 0.0;
};

}  // namespace asbuilt

#endif  // ASBUILT_PIPELINE_PANO_LAYOUT_LABELS_H_
