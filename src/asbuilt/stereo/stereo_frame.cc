#include "asbuilt/stereo/stereo_frame.h"

#include <string>

#include <fmt/format.h>

#include "asbuilt/imageio/image_io.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace fs = std::filesystem;

FrameImages ReadFrameImages(const Capture& capture, const CaptureFrame& frame) {
  auto read = [&](const std::string& rel, const char* field) {
    const fs::path path = capture.Resolve(rel);
    cv::Mat image = ReadColourImage(path, fmt::format("frames[index {}].{}", frame.index, field));
    CheckImageSize(image, capture.camera.width, capture.camera.height, path, "", "capture.json's camera");
    return image;
  };
  FrameImages out{.frame = frame, .left = read(frame.left, "left")};
  if (capture.kind == CaptureKind::kStereo) out.right = read(frame.right, "right");
  return out;
}

StereoFrame MakeStereoFrame(const Capture& capture, FrameImages images, FrameLabels labels,
                            const StereoRectifier* rectifier) {
  const CaptureFrame& frame = images.frame;
  StereoFrame out{.left = std::move(images.left),
                  .right = std::move(images.right),
                  .labels_left = std::move(labels.left),
                  .labels_right = std::move(labels.right)};
  for (const cv::Mat* l : {&out.labels_left, &out.labels_right}) {
    if (!l->empty() && l->size() != out.left.size()) {
      throw InputError(capture.Resolve(frame.left).string(), "labels",
                       fmt::format("frame {}: labels are {}x{}, images {}x{}", frame.index, l->cols, l->rows,
                                   out.left.cols, out.left.rows));
    }
  }
  if (out.labels_left.empty()) {
    throw InputError(capture.Resolve(frame.left).string(), "labels",
                     fmt::format("frame {}: no left labels", frame.index));
  }
  out.camera = capture.camera.Pinhole();
  out.baseline_m = capture.camera.baseline_m;
  out.pose = frame.Pose();
  out.index = frame.index;
  if (!capture.rectified) {
    CheckArgument(rectifier != nullptr, "MakeStereoFrame: an unrectified capture needs a rectifier");
    out.left = RectifyImage(*rectifier, StereoEye::kLeft, out.left);
    out.right = RectifyImage(*rectifier, StereoEye::kRight, out.right);
    out.labels_left = RectifyImage(*rectifier, StereoEye::kLeft, out.labels_left, Interpolation::kNearest);
    if (!out.labels_right.empty()) {
      out.labels_right = RectifyImage(*rectifier, StereoEye::kRight, out.labels_right, Interpolation::kNearest);
    }
    out.camera = rectifier->camera;
    out.baseline_m = rectifier->baseline_m;
  }
  return out;
}

StereoFrame LoadStereoFrame(const Capture& capture, const CaptureFrame& frame, LabelSource& labels,
                            const StereoRectifier* rectifier) {
  std::vector<FrameImages> images = {ReadFrameImages(capture, frame)};
  std::vector<FrameLabels> labelled = labels.Label(images);
  CheckArgument(labelled.size() == 1, "LoadStereoFrame: the label source gave no labels");
  return MakeStereoFrame(capture, std::move(images.front()), std::move(labelled.front()), rectifier);
}

}  // namespace asbuilt
