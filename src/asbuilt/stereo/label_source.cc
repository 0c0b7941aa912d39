#include "asbuilt/stereo/label_source.h"

#include <cmath>

#include <fmt/format.h>

#include "asbuilt/imageio/image_io.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace fs = std::filesystem;

double LabelSource::MeanConfidence() const { return NAN; }

std::vector<FrameLabels> DirectoryLabels::Label(const std::vector<FrameImages>& frames) {
  std::vector<FrameLabels> out;
  for (const FrameImages& f : frames) {
    const std::string name = fmt::format("{:03d}.png", f.frame.index);
    const fs::path left = dir_ / name, right = dir_ / "right" / name;
    if (!fs::exists(left)) {
      throw InputError(left.string(), "", fmt::format("no labels for frame {} (expected {})", f.frame.index, name));
    }
    FrameLabels labels{.left = ReadLabelImage(left)};
    if (!f.right.empty() && fs::exists(right)) labels.right = ReadLabelImage(right);
    out.push_back(std::move(labels));
  }
  return out;
}

std::string DirectoryLabels::Describe() const { return fmt::format("label images in {}", dir_.string()); }

std::vector<FrameLabels> CaptureLabels::Label(const std::vector<FrameImages>& frames) {
  std::vector<FrameLabels> out;
  for (const FrameImages& f : frames) {
    if (!f.frame.labels) {
      throw InputError("capture.json", fmt::format("frames[index {}].labels", f.frame.index),
                       "missing (needed with --use-capture-labels)");
    }
    const fs::path path = base_dir_ / *f.frame.labels;
    out.push_back({.left = ReadLabelImage(path)});
  }
  return out;
}

std::string CaptureLabels::Describe() const {
  return "the capture's own exact labels (upper bound, not a real-camera result)";
}

}  // namespace asbuilt
