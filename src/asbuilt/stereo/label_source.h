#ifndef ASBUILT_STEREO_LABEL_SOURCE_H_
#define ASBUILT_STEREO_LABEL_SOURCE_H_

// Where a frame's labels come from: label images given beside the capture,
// the capture's own (exact) labels, or a segmenter run on the images the
// frame loop has already decoded (pipeline/segmenter_labels.h). Labels are
// CV_8UC1 label ids (LabelClass, formats/points_file.h) aligned with the images as
// stored, before any rectification.

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/formats/capture.h"

namespace asbuilt {

// One frame's images as stored in the capture, each decoded once (CV_8UC3;
// unrectified when the capture is). `right` is empty for a mono view.
struct FrameImages {
  CaptureFrame frame;
  cv::Mat left, right;
};

// Label ids (CV_8UC1) for a frame's images, of their size. `right` is empty
// when there are none (normal: matches are then not checked against them).
struct FrameLabels {
  cv::Mat left, right;
};

class LabelSource {
 public:
  virtual ~LabelSource() = default;
  // The most images labelled in one call (a segmenter's batch): the frame
  // loop hands Label() that many images' frames at once. At least 1.
  virtual int BatchImages() const { return 1; }
  // The labels of each frame, in order (the frame loop checks their size
  // against the images). Throws InputError naming a missing or unreadable
  // label file.
  virtual std::vector<FrameLabels> Label(const std::vector<FrameImages>& frames) = 0;
  // What the labels are, for reports: "label images in DIR", "the
  // capture's own exact labels …", "segmenter … at 640x480".
  virtual std::string Describe() const = 0;
  // The stage its time is reported under: "load labels" or "segment".
  virtual std::string StageName() const { return "load labels"; }
  // How sure a segmenter was of the images labelled so far: the mean over
  // them of each image's mean probability of the classes chosen (0–1). NaN
  // for labels that come with no such measure (given, exact).
  virtual double MeanConfidence() const;
};

// Left labels from DIR/NNN.png (frame index, three digits); right labels
// from DIR/right/NNN.png when present. Throws InputError if a left file is
// missing.
class DirectoryLabels final : public LabelSource {
 public:
  explicit DirectoryLabels(std::filesystem::path dir) : dir_(std::move(dir)) {}
  std::vector<FrameLabels> Label(const std::vector<FrameImages>& frames) override;
  std::string Describe() const override;

 private:
  std::filesystem::path dir_;
};

// Left labels from each frame's `labels` key of capture.json (the exact
// labels of a synthetic capture: the method's upper bound). Throws
// InputError for a frame without one.
class CaptureLabels final : public LabelSource {
 public:
  explicit CaptureLabels(const Capture& capture) : base_dir_(capture.base_dir) {}
  std::vector<FrameLabels> Label(const std::vector<FrameImages>& frames) override;
  std::string Describe() const override;

 private:
  std::filesystem::path base_dir_;
};

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_LABEL_SOURCE_H_
