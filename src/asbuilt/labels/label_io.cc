#include "asbuilt/labels/label_io.h"

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

cv::Mat Decode(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(path.string(), "", "cannot read: no such file");
  cv::Mat image;
  try {
    image = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw InputError(path.string(), "", fmt::format("cannot decode image: {}", e.what()));
  }
  if (image.empty()) throw InputError(path.string(), "", "cannot decode image (not a PNG/JPEG/… or corrupt)");
  return image;
}

const char* DepthName(int depth) {
  switch (depth) {
    case CV_8U: return "8-bit";
    case CV_16U: return "16-bit";
    case CV_32F: return "32-bit float";
    default: return "unusual depth";
  }
}

}  // namespace

cv::Mat ReadLabelImage(const fs::path& path) {
  cv::Mat image = Decode(path);
  if (image.type() != CV_8UC1) {
    throw InputError(path.string(), "",
                     fmt::format("expected a single-channel 8-bit label PNG, got {} channel{}, {}",
                                 image.channels(), image.channels() == 1 ? "" : "s", DepthName(image.depth())));
  }
  return image;
}

cv::Mat ReadColourImage(const fs::path& path) {
  cv::Mat image = Decode(path);
  if (image.depth() != CV_8U) {
    throw InputError(path.string(), "",
                     fmt::format("expected an 8-bit colour image, got {}", DepthName(image.depth())));
  }
  if (image.channels() == 3) return image;
  cv::Mat bgr;
  if (image.channels() == 1) {
    cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  } else if (image.channels() == 4) {
    cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
  } else {
    throw InputError(path.string(), "", fmt::format("unsupported channel count {}", image.channels()));
  }
  return bgr;
}

void WriteLabelImage(const fs::path& path, const cv::Mat& labels) {
  CheckArgument(labels.type() == CV_8UC1, "WriteLabelImage: labels must be CV_8UC1");
  WriteImageAtomic(path, labels);
}

}  // namespace asbuilt
