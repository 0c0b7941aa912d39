#ifndef ASBUILT_IMAGEIO_IMAGE_CV_H_
#define ASBUILT_IMAGEIO_IMAGE_CV_H_

// Image ↔ cv::Mat without copying, for the modules that work in OpenCV
// (stereo, labels, seg, imageio) and inside render/pano .cc files. Both
// directions share the pixels: a write through one shows in the other.

#include <opencv2/core.hpp>

#include "asbuilt/imageio/image.h"

namespace asbuilt {

// A cv::Mat over the image's pixels (CV_8U/CV_16U/CV_32F with its channel
// count; an empty Mat for an empty image) that keeps them alive like the
// Image does, so it may outlive `image`.
cv::Mat AsMat(const Image& image);

// An Image sharing `mat`'s pixels and keeping them alive (it holds a copy
// of the Mat header, hence its reference count). `mat` must be 8-bit, 16-bit
// unsigned or 32-bit float with 1–4 channels (InvalidArgument else); an
// empty Mat gives an empty Image.
Image AsImage(const cv::Mat& mat);

}  // namespace asbuilt

#endif  // ASBUILT_IMAGEIO_IMAGE_CV_H_
