#ifndef ASBUILT_STEREO_CAPTURE_POINTS_H_
#define ASBUILT_STEREO_CAPTURE_POINTS_H_

// The stereo stage's entry point for `asbuilt points` and `asbuilt survey`:
// world points by class from every frame of a capture (frame_points.h per
// frame, cue_choice.h for the whole capture).

#include <optional>
#include <string>
#include <vector>

#include "asbuilt/formats/capture.h"
#include "asbuilt/formats/points_file.h"
#include "asbuilt/stereo/contacts.h"
#include "asbuilt/stereo/frame_points.h"
#include "asbuilt/stereo/frame_points_options.h"
#include "asbuilt/stereo/stereo_frame.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

struct CapturePointsResult {
  std::vector<ClassPoint> points;
  std::vector<FrameCues> frames;
  std::optional<CeilingHeight> ceiling;  // Estimated (or given) ceiling height.
  std::string wall_cue;                  // CapturePoints::Result::decision.
  double seconds = 0.0;

  // "12 frames, 45123 points (wall 40000, door 3000, window 2123; corner 150,
  // edge 3000, dense 41773, boundary 200, contact 900), 3.2 s".
  std::string BriefReport() const;
};

// Every frame of a capture (rectifying first when `rectified` is false,
// with the maps computed once from capture.calibration).
CapturePointsResult ComputeCapturePoints(const Capture& capture, const LabelProvider& labels,
                                         const FramePointsOptions& options, const ProgressCallback& progress = {});

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_CAPTURE_POINTS_H_
