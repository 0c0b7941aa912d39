#include "asbuilt/imageio/image_io.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/text.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

const char* DepthName(int depth) {
  switch (depth) {
    case CV_8U:
      return "8-bit";
    case CV_16U:
      return "16-bit";
    case CV_32F:
      return "32-bit float";
    default:
      return "unusual depth";
  }
}

cv::Mat Decode(const fs::path& path, const std::string& field, int flags) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(path.string(), field, "cannot read image: no such file");
  cv::Mat image;
  try {
    image = cv::imread(path.string(), flags);
  } catch (const cv::Exception& e) {
    throw InputError(path.string(), field, fmt::format("cannot decode image: {}", e.what()));
  }
  if (image.empty()) throw InputError(path.string(), field, "cannot decode image (not a PNG/JPEG/… or corrupt)");
  return image;
}

}  // namespace

cv::Mat ToneMapToSrgb8(const cv::Mat& linear_bgr) {
  CV_Assert(linear_bgr.type() == CV_32FC3);
  // The white point: the 98th percentile of the mean channel.
  std::vector<float> level;
  level.reserve(linear_bgr.total());
  for (int y = 0; y < linear_bgr.rows; ++y) {
    const auto* row = linear_bgr.ptr<cv::Vec3f>(y);
    for (int x = 0; x < linear_bgr.cols; ++x) level.push_back((row[x][0] + row[x][1] + row[x][2]) / 3.f);
  }
  auto nth = level.begin() + static_cast<std::ptrdiff_t>(0.98 * (level.size() - 1));
  std::nth_element(level.begin(), nth, level.end());
  const float white = *nth > 0 ? *nth : 1.f;
  cv::Mat out(linear_bgr.size(), CV_8UC3);
  for (int y = 0; y < linear_bgr.rows; ++y) {
    const auto* in = linear_bgr.ptr<cv::Vec3f>(y);
    auto* o = out.ptr<cv::Vec3b>(y);
    for (int x = 0; x < linear_bgr.cols; ++x) {
      for (int c = 0; c < 3; ++c) {
        const float v = std::clamp(in[x][c] / white, 0.f, 1.f);
        const float srgb = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.f / 2.4f) - 0.055f;
        o[x][c] = static_cast<uchar>(std::lround(255.f * srgb));
      }
    }
  }
  return out;
}

// The decoder expands grey, drops alpha and applies EXIF orientation
// (IMREAD_COLOR) while keeping the stored depth (IMREAD_ANYDEPTH).
cv::Mat ReadColourImage(const fs::path& path, const std::string& field) {
  cv::Mat image = Decode(path, field, cv::IMREAD_COLOR | cv::IMREAD_ANYDEPTH);
  if (image.depth() == CV_32F) return ToneMapToSrgb8(image);  // A linear HDR photo.
  if (image.depth() != CV_8U) {
    throw InputError(path.string(), field,
                     fmt::format("expected an 8-bit colour image, got {}", DepthName(image.depth())));
  }
  return image;
}

bool IsImageExtension(const fs::path& path) {
  static const char* kExt[] = {".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".webp"};
  const std::string ext = AsciiLower(path.extension().string());
  return std::any_of(std::begin(kExt), std::end(kExt), [&](const char* e) { return ext == e; });
}

void AllowOpenExr() { setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 0); }

cv::Mat ReadColourImageAnyDepth(const fs::path& path, const std::string& field) {
  cv::Mat image = Decode(path, field, cv::IMREAD_COLOR | cv::IMREAD_ANYDEPTH);
  if (image.depth() != CV_8U && image.depth() != CV_16U && image.depth() != CV_32F) {
    throw InputError(
        path.string(), field,
        fmt::format("expected an 8-bit, 16-bit or 32-bit float colour image, got {}", DepthName(image.depth())));
  }
  return image;
}

cv::Mat ReadGrayImage(const fs::path& path, const std::string& field) {
  return Decode(path, field, cv::IMREAD_GRAYSCALE);
}

cv::Mat ReadLabelImage(const fs::path& path, const std::string& field) {
  cv::Mat image = Decode(path, field, cv::IMREAD_UNCHANGED);
  if (image.type() != CV_8UC1) {
    throw InputError(path.string(), field,
                     fmt::format("expected a single-channel 8-bit label PNG, got {} channel{}, {}", image.channels(),
                                 image.channels() == 1 ? "" : "s", DepthName(image.depth())));
  }
  return image;
}

cv::Mat ReadDepthImage(const fs::path& path, const std::string& field) {
  cv::Mat image = Decode(path, field, cv::IMREAD_ANYDEPTH);
  if (image.type() != CV_16UC1 && image.type() != CV_32FC1) {
    throw InputError(path.string(), field,
                     fmt::format("expected a single-channel 16-bit (mm) or 32-bit float (m) depth image, got {} "
                                 "channel{}, {}",
                                 image.channels(), image.channels() == 1 ? "" : "s", DepthName(image.depth())));
  }
  return image;
}

cv::Mat ReadImageAsStored(const fs::path& path, const std::string& field) {
  return Decode(path, field, cv::IMREAD_UNCHANGED);
}

void CheckImageSize(const cv::Mat& image, int width_px, int height_px, const fs::path& path, const std::string& field,
                    const std::string& what) {
  if (image.cols == width_px && image.rows == height_px) return;
  throw InputError(path.string(), field,
                   fmt::format("image is {}x{}, {} is {}x{}", image.cols, image.rows, what, width_px, height_px));
}

void WriteImageToTemp(const AtomicFile& file, const cv::Mat& image) {
  const fs::path& path = file.final_path();
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  bool ok = false;
  try {
    ok = cv::imwrite(file.temp_path().string(), image, {cv::IMWRITE_PNG_COMPRESSION, 1});
  } catch (const cv::Exception& e) {
    throw Error(fmt::format("{}: cannot write image: {}", path.string(), e.what()));
  }
  if (!ok) throw Error(fmt::format("{}: cannot write image", path.string()));
}

void WriteImageAtomic(const std::filesystem::path& path, const cv::Mat& image) {
  AtomicFile file(path);
  WriteImageToTemp(file, image);
  file.Commit();
}

void WriteImageAtomic(const fs::path& path, const Image& image) { WriteImageAtomic(path, AsMat(image)); }

}  // namespace asbuilt
