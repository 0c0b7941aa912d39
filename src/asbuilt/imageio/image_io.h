#ifndef ASBUILT_IMAGEIO_IMAGE_IO_H_
#define ASBUILT_IMAGEIO_IMAGE_IO_H_

// The image layer: every image file asbuilt reads goes through one of the
// Read* functions (one error wording: the file, then what is wrong with it),
// and every image it writes is written atomically (temp file + rename), so a
// killed run never leaves a broken image under its final name.

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

#include "asbuilt/imageio/image.h"
#include "asbuilt/util/file.h"

namespace asbuilt {

// Reads a colour image as CV_8UC3 in OpenCV's BGR order (grey images are
// expanded, alpha dropped, a JPEG's EXIF orientation applied; linear HDR
// files (Radiance .hdr) tone-mapped by ToneMapToSrgb8; 16-bit files are
// refused). Every reader throws InputError(path, field, …) when the file
// is missing, cannot be decoded or has the wrong type; `field` names where
// the path came from (e.g. "frames[3].left") and may be empty.
cv::Mat ReadColourImage(const std::filesystem::path& path, const std::string& field = "");

// Whether `path` names a photo by its extension, in any case: .png, .jpg,
// .jpeg, .bmp, .tif, .tiff, .webp (what the image readers take from folders).
bool IsImageExtension(const std::filesystem::path& path);

// Lets OpenCV decode OpenEXR files in this process. OpenCV reads them only
// when asked (the format's decoder has a CVE history), and reads the switch
// once, before the first EXR: call this before reading an EXR the user or a
// Debian package gave.
void AllowOpenExr();

// Reads a colour image at the depth it is stored in, as 3-channel BGR:
// CV_8UC3, CV_16UC3 or CV_32FC3 (Radiance .hdr; OpenEXR after
// AllowOpenExr()). For linear high-dynamic-range photos.
cv::Mat ReadColourImageAnyDepth(const std::filesystem::path& path, const std::string& field = "");

// A linear high-dynamic-range BGR image (CV_32FC3) as a photo-like 8-bit sRGB
// one: divided by the 98th percentile of the mean channel, clipped to 1, the
// sRGB transfer curve. The rule ../shared/data/cc0-panoramas made its JPEGs by.
cv::Mat ToneMapToSrgb8(const cv::Mat& linear_bgr);

// Reads an image as 8-bit grey (CV_8UC1); colour files are converted.
cv::Mat ReadGrayImage(const std::filesystem::path& path, const std::string& field = "");

// Reads a label map as stored: single-channel 8-bit label ids (CV_8UC1),
// refused otherwise ("expected a single-channel 8-bit label PNG, got 3
// channels, 8-bit"); palette-coloured masks are the labels module's import.
cv::Mat ReadLabelImage(const std::filesystem::path& path, const std::string& field = "");

// Reads a depth image as stored: 16-bit millimetres (CV_16UC1) or 32-bit float
// metres (CV_32FC1); any other type is refused.
cv::Mat ReadDepthImage(const std::filesystem::path& path, const std::string& field = "");

// Reads an image as stored (any depth, any channel count). For tools that
// inspect or convert images; the pipeline uses the typed readers above.
cv::Mat ReadImageAsStored(const std::filesystem::path& path, const std::string& field = "");

// Throws InputError(path, field, "image is WxH, <what> is W'xH'") unless
// `image` has the size `width_px` × `height_px`.
void CheckImageSize(const cv::Mat& image, int width_px, int height_px, const std::filesystem::path& path,
                    const std::string& field, const std::string& what);

// Writes `image` in the format of the path's extension (.png: 8/16-bit,
// lossless). Creates missing folders. Throws Error on failure.
void WriteImageAtomic(const std::filesystem::path& path, const cv::Mat& image);
void WriteImageAtomic(const std::filesystem::path& path, const Image& image);
// The same into `file`'s temp path, for writers that commit several files
// together (util/file.h AtomicFile).
void WriteImageToTemp(const AtomicFile& file, const cv::Mat& image);

}  // namespace asbuilt

#endif  // ASBUILT_IMAGEIO_IMAGE_IO_H_
