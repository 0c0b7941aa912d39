#ifndef ASBUILT_IMAGEIO_IMAGE_H_
#define ASBUILT_IMAGEIO_IMAGE_H_

// An image as a value in public headers that must not include OpenCV (render,
// pano): size, channel count, element type and a shared pixel buffer, rows
// top to bottom, channels interleaved (colour images in OpenCV's BGR order).
// Copies share the pixels, as cv::Mat's do; Clone() copies them.
// imageio/image_cv.h converts to and from cv::Mat without copying.
//
//   Image labels(640, 480, 1, PixelType::kU8);
//   labels.Row<std::uint8_t>(y)[x] = 1;

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace asbuilt {

// The type of one channel value.
enum class PixelType {
  kU8,   // std::uint8_t: colour, labels, ids.
  kU16,  // std::uint16_t: depth in millimetres, instance ids.
  kF32,  // float: linear radiance.
};
const char* PixelTypeName(PixelType type);   // "8-bit", "16-bit", "32-bit float".
std::size_t PixelTypeBytes(PixelType type);  // 1, 2, 4.

class Image {
 public:
  Image() = default;  // Empty: 0 × 0, no pixels.
  // A new width_px × height_px image of `channels` (1–4) values per pixel,
  // all zero. Throws InvalidArgument for a negative size or a channel count
  // outside 1–4.
  Image(int width_px, int height_px, int channels, PixelType type);
  // Pixels someone else owns, without copying: rows `row_stride_bytes` apart
  // from `pixels` (whose owner the pointer keeps alive). For image_cv.h.
  Image(int width_px, int height_px, int channels, PixelType type, std::shared_ptr<std::uint8_t[]> pixels,
        std::size_t row_stride_bytes);

  int width() const { return width_px_; }
  int height() const { return height_px_; }
  int channels() const { return channels_; }
  PixelType type() const { return type_; }
  bool empty() const { return width_px_ == 0 || height_px_ == 0; }
  std::size_t row_stride_bytes() const { return row_stride_bytes_; }
  // Bytes of pixel data in one row (width × channels × value size).
  std::size_t row_bytes() const { return static_cast<std::size_t>(width_px_) * channels_ * PixelTypeBytes(type_); }
  // The shared buffer (its owner stays alive while a copy of this pointer does).
  const std::shared_ptr<std::uint8_t[]>& pixels() const { return pixels_; }

  // Row y (0 = top) as `channels()` interleaved values per pixel; T must match
  // type() (std::uint8_t, std::uint16_t or float). No bounds checks.
  template <typename T>
  T* Row(int y) {
    return reinterpret_cast<T*>(pixels_.get() + static_cast<std::size_t>(y) * row_stride_bytes_);
  }
  template <typename T>
  const T* Row(int y) const {
    return reinterpret_cast<const T*>(pixels_.get() + static_cast<std::size_t>(y) * row_stride_bytes_);
  }

  Image Clone() const;  // A copy with pixels of its own (rows packed).
  // True when size, channels, type and every pixel value are equal.
  bool SamePixels(const Image& other) const;
  std::string ToString() const;  // "Image(640x480, 3 × 8-bit)", "Image(empty)".

 private:
  int width_px_ = 0;
  int height_px_ = 0;
  int channels_ = 1;
  PixelType type_ = PixelType::kU8;
  std::shared_ptr<std::uint8_t[]> pixels_;
  std::size_t row_stride_bytes_ = 0;
};

}  // namespace asbuilt

#endif  // ASBUILT_IMAGEIO_IMAGE_H_
