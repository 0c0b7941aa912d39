#ifndef ASBUILT_STEREO_STEREO_FRAME_H_
#define ASBUILT_STEREO_STEREO_FRAME_H_

// A capture's frames as the points pass takes them: rectified images with
// their labels, the camera and the rig pose.

#include <filesystem>
#include <functional>

#include <opencv2/core.hpp>

#include "asbuilt/formats/capture.h"
#include "asbuilt/geometry/rig.h"
#include "asbuilt/stereo/rectify.h"

namespace asbuilt {

// One rectified stereo frame with its labels, ready for ComputeFramePoints.
struct StereoFrame {
  cv::Mat left, right;   // Rectified CV_8UC3 (or CV_8UC1).
  cv::Mat labels_left;   // CV_8UC1 label ids, left view (required).
  cv::Mat labels_right;  // Optional; when given, matches must agree with it.
  PinholeCamera camera;  // Rectified intrinsics.
  double baseline_m = 0.12;
  RigPose pose;
  int index = -1;
};

// One level view of a single camera (a mono capture, or a view resampled
// from a panorama): no second image, so no disparity. Its optical centre is
// at pose.position_m (not offset by half a baseline), level (pitch 0).
struct MonoFrame {
  cv::Mat image;   // CV_8UC3 or CV_8UC1 (ceiling contacts snap to its edges).
  cv::Mat labels;  // CV_8UC1 label ids, the image's size.
  PinholeCamera camera;
  RigPose pose;
  int index = -1;
};

// Labels for a frame's view: empty Mat when there are none (for the right
// view, "none" is normal). Images are as the capture's images (unrectified
// when the capture is); they are rectified with nearest-neighbour lookup.
using LabelProvider = std::function<cv::Mat(const CaptureFrame& frame, StereoEye eye)>;
// Left labels from DIR/NNN.png (frame index, three digits); right labels from
// DIR/right/NNN.png when present. Throws InputError if a left file is missing.
LabelProvider LabelsFromDirectory(const std::filesystem::path& dir);
// Left labels from each frame's `labels` key of capture.json.
LabelProvider LabelsFromCapture(const Capture& capture);

// Reads a frame's images and labels, rectifying them when the capture is not
// rectified (`rectifier` must then be given). Throws InputError for missing
// or unreadable images and labels, naming the file.
StereoFrame LoadStereoFrame(const Capture& capture, const CaptureFrame& frame, const LabelProvider& labels,
                            const StereoRectifier* rectifier);

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_STEREO_FRAME_H_
