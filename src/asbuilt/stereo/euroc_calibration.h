#ifndef ASBUILT_STEREO_EUROC_CALIBRATION_H_
#define ASBUILT_STEREO_EUROC_CALIBRATION_H_

// Imports a stereo calibration written in the EuRoC MAV dataset's per-camera
// `sensor.yaml` form (Burri et al., IJRR 2016; Kalibr's camchain.yaml is a
// different layout, not read here) as asbuilt's StereoCalibration, so a real rig
// calibrated elsewhere can be surveyed without a chessboard session:
//
//   intrinsics: [fu, fv, cu, cv]              → K
//   distortion_model: radial-tangential       → OpenCV's plumb-bob D = (k1, k2, p1, p2)
//   distortion_coefficients: [k1, k2, p1, p2]
//   resolution: [width, height]               → image_size
//   T_BS: {rows: 4, cols: 4, data: [...]}     camera → body; then
//                                             x_R = R·x_L + T from T_BS_R⁻¹ · T_BS_L
//
// EuRoC intrinsics use OpenCV's pixel convention (centre of the top-left
// pixel at (0, 0)), so they are taken as they are.

#include <filesystem>

#include "asbuilt/stereo/rectify.h"

namespace asbuilt {

// Reads the left (cam0) and right (cam1) sensor files. Throws InputError
// naming the file and key for a missing or malformed key, a camera model
// other than pinhole, a distortion model other than radial-tangential
// (equidistant/fisheye needs OpenCV's fisheye model, not supported), images
// of different sizes, or a right camera that is not to the right of the left
// one (the files were given in the wrong order). rms_px stays NaN (unknown).
StereoCalibration CalibrationFromEuroc(const std::filesystem::path& left_sensor_yaml,
                                       const std::filesystem::path& right_sensor_yaml);

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_EUROC_CALIBRATION_H_
