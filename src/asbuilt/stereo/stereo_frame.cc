#include "asbuilt/stereo/stereo_frame.h"

#include <string>

#include <fmt/format.h>

#include "asbuilt/imageio/image_io.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace fs = std::filesystem;

LabelProvider LabelsFromDirectory(const fs::path& dir) {
  return [dir](const CaptureFrame& frame, StereoEye eye) -> cv::Mat {
    const std::string name = fmt::format("{:03d}.png", frame.index);
    if (eye == StereoEye::kLeft) {
      const fs::path path = dir / name;
      if (!fs::exists(path)) {
        throw InputError(path.string(), "", fmt::format("no labels for frame {} (expected {})", frame.index, name));
      }
      return ReadLabelImage(path);
    }
    const fs::path path = dir / "right" / name;
    return fs::exists(path) ? ReadLabelImage(path) : cv::Mat();
  };
}

LabelProvider LabelsFromCapture(const Capture& capture) {
  const fs::path base = capture.base_dir;
  return [base](const CaptureFrame& frame, StereoEye eye) -> cv::Mat {
    if (eye != StereoEye::kLeft) return cv::Mat();
    if (!frame.labels) {
      throw InputError("capture.json", fmt::format("frames[index {}].labels", frame.index),
                       "missing (needed with --use-capture-labels)");
    }
    return ReadLabelImage(base / *frame.labels);
  };
}

StereoFrame LoadStereoFrame(const Capture& capture, const CaptureFrame& frame, const LabelProvider& labels,
                            const StereoRectifier* rectifier) {
  StereoFrame out;
  auto read = [&](const std::string& rel, const char* field) {
    const fs::path path = capture.Resolve(rel);
    cv::Mat image = ReadColourImage(path, fmt::format("frames[index {}].{}", frame.index, field));
    CheckImageSize(image, capture.camera.width, capture.camera.height, path, "", "capture.json's camera");
    return image;
  };
  out.left = read(frame.left, "left");
  out.right = read(frame.right, "right");
  out.labels_left = labels(frame, StereoEye::kLeft);
  out.labels_right = labels(frame, StereoEye::kRight);
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
    CheckArgument(rectifier != nullptr, "LoadStereoFrame: an unrectified capture needs a rectifier");
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

}  // namespace asbuilt
