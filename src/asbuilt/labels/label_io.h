#ifndef ASBUILT_LABELS_LABEL_IO_H_
#define ASBUILT_LABELS_LABEL_IO_H_

// Reading and writing label maps and colour images with errors that name the
// file. Label maps are single-channel 8-bit PNGs of label ids (DESIGN.md).

#include <filesystem>

#include <opencv2/core.hpp>

#include "asbuilt/imageio/image_io.h"

namespace asbuilt {

// A label map as stored: CV_8UC1. Throws InputError naming the file if it
// cannot be decoded or is not single-channel 8-bit ("expected a
// single-channel 8-bit label PNG, got 3 channels, 8-bit").
cv::Mat ReadLabelImage(const std::filesystem::path& path);

// A colour image as CV_8UC3 in OpenCV's BGR order (grey images are expanded,
// alpha dropped). Throws InputError naming the file if it cannot be decoded
// or is 16-bit.
cv::Mat ReadColourImage(const std::filesystem::path& path);

// Writes a CV_8UC1 map as PNG, atomically; creates parent folders. Throws
// InvalidArgument for another type, Error if writing fails.
void WriteLabelImage(const std::filesystem::path& path, const cv::Mat& labels);

}  // namespace asbuilt

#endif  // ASBUILT_LABELS_LABEL_IO_H_
