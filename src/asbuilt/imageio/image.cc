#include "asbuilt/imageio/image.h"

#include <cstring>
#include <utility>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {

const char* PixelTypeName(PixelType type) {
  switch (type) {
    case PixelType::kU8:
      return "8-bit";
    case PixelType::kU16:
      return "16-bit";
    case PixelType::kF32:
      return "32-bit float";
  }
  return "?";
}

std::size_t PixelTypeBytes(PixelType type) {
  switch (type) {
    case PixelType::kU8:
      return 1;
    case PixelType::kU16:
      return 2;
    case PixelType::kF32:
      return 4;
  }
  return 1;
}

Image::Image(int width_px, int height_px, int channels, PixelType type)
    : width_px_(width_px), height_px_(height_px), channels_(channels), type_(type) {
  CheckArgument(width_px >= 0 && height_px >= 0, fmt::format("Image: size {}x{}, must be >= 0", width_px, height_px));
  CheckArgument(channels >= 1 && channels <= 4, fmt::format("Image: {} channels, must be 1–4", channels));
  row_stride_bytes_ = row_bytes();
  pixels_ = std::make_shared<std::uint8_t[]>(row_stride_bytes_ * static_cast<std::size_t>(height_px));
}

Image::Image(int width_px, int height_px, int channels, PixelType type, std::shared_ptr<std::uint8_t[]> pixels,
             std::size_t row_stride_bytes)
    : width_px_(width_px),
      height_px_(height_px),
      channels_(channels),
      type_(type),
      pixels_(std::move(pixels)),
      row_stride_bytes_(row_stride_bytes) {
  CheckArgument(width_px >= 0 && height_px >= 0, fmt::format("Image: size {}x{}, must be >= 0", width_px, height_px));
  CheckArgument(channels >= 1 && channels <= 4, fmt::format("Image: {} channels, must be 1–4", channels));
  CheckArgument(empty() || (pixels_ != nullptr && row_stride_bytes >= row_bytes()),
                fmt::format("Image: {}x{} pixels need a buffer with rows >= {} bytes apart, got {}", width_px,
                            height_px, row_bytes(), pixels_ == nullptr ? 0 : row_stride_bytes));
}

Image Image::Clone() const {
  Image copy(width_px_, height_px_, channels_, type_);
  for (int y = 0; y < height_px_; ++y) std::memcpy(copy.Row<std::uint8_t>(y), Row<std::uint8_t>(y), row_bytes());
  return copy;
}

bool Image::SamePixels(const Image& other) const {
  if (width_px_ != other.width_px_ || height_px_ != other.height_px_ || channels_ != other.channels_ ||
      type_ != other.type_) {
    return false;
  }
  for (int y = 0; y < height_px_; ++y) {
    if (std::memcmp(Row<std::uint8_t>(y), other.Row<std::uint8_t>(y), row_bytes()) != 0) return false;
  }
  return true;
}

std::string Image::ToString() const {
  if (empty()) return "Image(empty)";
  return fmt::format("Image({}x{}, {} × {})", width_px_, height_px_, channels_, PixelTypeName(type_));
}

}  // namespace asbuilt
