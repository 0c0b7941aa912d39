#ifndef ASBUILT_STEREO_STEREO_FRAME_H_
#define ASBUILT_STEREO_STEREO_FRAME_H_

// A capture's frames as the points pass takes them: rectified images with
// their labels, the camera and the rig pose; and how they are loaded (each
// image decoded once, labelled, rectified).

#include <opencv2/core.hpp>

#include "asbuilt/formats/capture.h"
#include "asbuilt/geometry/rig.h"
#include "asbuilt/stereo/label_source.h"
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

// Reads a frame's images, each once: left and right of a stereo capture,
// the one image (`left`) of a mono capture, each checked to be the size of
// capture.json's camera. Throws InputError naming the file.
FrameImages ReadFrameImages(const Capture& capture, const CaptureFrame& frame);

// A stereo frame from its decoded images and labels, rectified when the
// capture is not (`rectifier` must then be given; images with linear,
// labels with nearest-neighbour lookup). Throws InputError when the left
// labels are missing or not of the images' size.
StereoFrame MakeStereoFrame(const Capture& capture, FrameImages images, FrameLabels labels,
                            const StereoRectifier* rectifier);

// ReadFrameImages → labels → MakeStereoFrame for one frame: for tests and
// tools that take frames one by one (ComputeCapturePoints batches them).
StereoFrame LoadStereoFrame(const Capture& capture, const CaptureFrame& frame, LabelSource& labels,
                            const StereoRectifier* rectifier);

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_STEREO_FRAME_H_
