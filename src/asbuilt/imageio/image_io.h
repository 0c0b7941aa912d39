#ifndef ASBUILT_IMAGEIO_IMAGE_IO_H_
#define ASBUILT_IMAGEIO_IMAGE_IO_H_

// Image files written atomically (temp file + rename), so a killed run never
// leaves a broken image under its final name.

#include <filesystem>

#include <opencv2/core.hpp>

namespace asbuilt {

// Writes `image` in the format of the path's extension (.png: 8/16-bit,
// lossless). Creates missing folders. Throws Error on failure.
void WriteImageAtomic(const std::filesystem::path& path, const cv::Mat& image);

}  // namespace asbuilt

#endif  // ASBUILT_IMAGEIO_IMAGE_IO_H_
