#ifndef ASBUILT_STEREO_RECTIFY_H_
#define ASBUILT_STEREO_RECTIFY_H_

// Stereo calibration files and rectification (PAPER.md §7, "rectify with
// precomputed maps"). A calibration is OpenCV YAML with K1 D1 K2 D2 R T and
// the image size (as `asbuilt calibrate` writes it); a StereoRectifier holds
// the remap tables, computed once per rig and reused for every frame.

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

#include "asbuilt/formats/capture.h"
#include "asbuilt/geometry/rig.h"

namespace asbuilt {

struct StereoCalibration {
  cv::Size image_size;
  cv::Mat K1, D1, K2, D2;          // 3×3 camera matrices, distortion vectors (CV_64F).
  cv::Mat R, T;                    // Right camera from left: x_R = R·x_L + T (T in metres).
  double rms_px = NAN;             // Stereo reprojection RMS, NaN if unknown.
  double epipolar_error_px = NAN;  // Mean distance to the epipolar line, NaN if unknown.

  std::string ToString() const;
};

// Reads an OpenCV FileStorage YAML/XML. Throws InputError naming the file and
// the missing or malformed key ("calibration.yml: K1: expected a 3x3 matrix").
StereoCalibration LoadCalibration(const std::filesystem::path& path);
// Every problem of a calibration file, without throwing (`asbuilt validate
// --kind calibration`).
FileReport CheckCalibrationFile(const std::filesystem::path& path);
// Writes K1 D1 K2 D2 R T, image_width/image_height, rms (and any extra
// scalars) atomically, readable by cv::FileStorage.
void WriteCalibration(const StereoCalibration& calibration, const std::filesystem::path& path);

struct RectifyOptions {
  // 0 crops to pixels valid in both views; 1 keeps every source pixel (black
  // borders). Values between trade field of view for border.
  double alpha = 0.0;

  void Check() const;
};

// Remap tables for one rig, and the rectified pinhole camera and baseline
// that the disparity → depth conversion uses.
struct StereoRectifier {
  cv::Mat left_map_x, left_map_y, right_map_x, right_map_y;  // CV_32F.
  PinholeCamera camera;                                      // Rectified intrinsics (both views).
  double baseline_m = 0;                                     // |T| along the rectified x axis.
  cv::Mat R1;                                                // Rotation rectified-left ← original-left.

  std::string ToString() const;
};

// Computes the maps (cv::stereoRectify + initUndistortRectifyMap). Throws
// InvalidArgument on a calibration without an image size or matrices.
StereoRectifier MakeStereoRectifier(const StereoCalibration& calibration, const RectifyOptions& options);

enum class Interpolation { kLinear, kNearest };  // kNearest for label images.

// Rectifies one image of the pair. Throws InvalidArgument when the image
// size differs from the calibration's.
cv::Mat RectifyImage(const StereoRectifier& rectifier, StereoEye eye, const cv::Mat& image,
                     Interpolation interpolation = Interpolation::kLinear);

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_RECTIFY_H_
