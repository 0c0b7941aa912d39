#ifndef ASBUILT_LABELS_LABEL_IO_H_
#define ASBUILT_LABELS_LABEL_IO_H_

// Writing label maps (single-channel 8-bit PNGs of label ids, DESIGN.md);
// reading them is imageio's ReadLabelImage.

#include <filesystem>

#include <opencv2/core.hpp>

#include "asbuilt/imageio/image_io.h"

namespace asbuilt {

// Writes a CV_8UC1 map as PNG, atomically; creates parent folders. Throws
// InvalidArgument for another type, Error if writing fails.
void WriteLabelImage(const std::filesystem::path& path, const cv::Mat& labels);

}  // namespace asbuilt

#endif  // ASBUILT_LABELS_LABEL_IO_H_
