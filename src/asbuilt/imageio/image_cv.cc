#include "asbuilt/imageio/image_cv.h"

#include <memory>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// Lends an Image's pixels to cv::Mat: the Mat's buffer record (UMatData)
// holds a copy of the Image's shared pointer, released when the last Mat
// sharing the record goes (the pattern of OpenCV's own NumPy allocator).
// Buffers OpenCV allocates anew for such a Mat (create() with another size)
// come from the standard allocator.
class SharedPixelsAllocator : public cv::MatAllocator {
 public:
  cv::UMatData* Lend(const Image& image) const {
    auto* u = new cv::UMatData(this);
    u->data = u->origdata = image.pixels().get();
    u->size = image.row_stride_bytes() * static_cast<std::size_t>(image.height());
    u->userdata = new std::shared_ptr<std::uint8_t[]>(image.pixels());
    return u;
  }

  cv::UMatData* allocate(int dims, const int* sizes, int type, void* data, size_t* step, cv::AccessFlag flags,
                         cv::UMatUsageFlags usage) const override {
    return cv::Mat::getStdAllocator()->allocate(dims, sizes, type, data, step, flags, usage);
  }
  bool allocate(cv::UMatData* u, cv::AccessFlag flags, cv::UMatUsageFlags usage) const override {
    return cv::Mat::getStdAllocator()->allocate(u, flags, usage);
  }
  void deallocate(cv::UMatData* u) const override {
    if (u == nullptr || u->refcount != 0) return;
    delete static_cast<std::shared_ptr<std::uint8_t[]>*>(u->userdata);
    delete u;
  }
};

SharedPixelsAllocator& SharedPixels() {
  static SharedPixelsAllocator* const kAllocator = new SharedPixelsAllocator();  // Outlives every Mat.
  return *kAllocator;
}

}  // namespace

cv::Mat AsMat(const Image& image) {
  if (image.empty()) return cv::Mat();
  int depth = CV_8U;
  switch (image.type()) {
    case PixelType::kU8:
      depth = CV_8U;
      break;
    case PixelType::kU16:
      depth = CV_16U;
      break;
    case PixelType::kF32:
      depth = CV_32F;
      break;
  }
  cv::Mat mat(image.height(), image.width(), CV_MAKETYPE(depth, image.channels()), image.pixels().get(),
              image.row_stride_bytes());
  mat.u = SharedPixels().Lend(image);
  mat.addref();
  mat.allocator = &SharedPixels();
  return mat;
}

Image AsImage(const cv::Mat& mat) {
  if (mat.empty()) return Image();
  CheckArgument(mat.dims == 2, fmt::format("AsImage: a {}-dimensional Mat, needs 2", mat.dims));
  PixelType type = PixelType::kU8;
  switch (mat.depth()) {
    case CV_8U:
      type = PixelType::kU8;
      break;
    case CV_16U:
      type = PixelType::kU16;
      break;
    case CV_32F:
      type = PixelType::kF32;
      break;
    default:
      throw InvalidArgument(
          fmt::format("AsImage: Mat depth {}, needs 8-bit, 16-bit unsigned or 32-bit float", mat.depth()));
  }
  // The buffer's owner is a copy of the Mat header (it holds the Mat's
  // reference count); the aliasing pointer addresses its first pixel.
  const auto owner = std::make_shared<const cv::Mat>(mat);
  std::shared_ptr<std::uint8_t[]> pixels(owner, mat.data);
  return Image(mat.cols, mat.rows, mat.channels(), type, std::move(pixels), mat.step[0]);
}

}  // namespace asbuilt
