#ifndef ASBUILT_STEREO_CAPTURE_POINTS_H_
#define ASBUILT_STEREO_CAPTURE_POINTS_H_

// The stereo stage's entry point for `asbuilt points` and `asbuilt survey`:
// the one loop over a capture's frames. Per batch of frames: read each
// image once (stereo_frame.h), label them (label_source.h), then per frame
// rectify and compute its points (frame_points.h); for the whole capture,
// choose the wall cue and resolve the contacts (cue_choice.h). Stereo
// captures give every cue; mono captures and a panorama's views give
// contacts and what rests on them (ComputeMonoFramePoints).

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/formats/capture.h"
#include "asbuilt/formats/points_file.h"
#include "asbuilt/geometry/rig.h"
#include "asbuilt/stereo/contacts.h"
#include "asbuilt/stereo/frame_points.h"
#include "asbuilt/stereo/frame_points_options.h"
#include "asbuilt/stereo/label_source.h"
#include "asbuilt/stereo/stereo_frame.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

// Level views of one camera made in memory (a panorama resampled into
// perspective views, pano/): frame i shows images[i] (CV_8UC3 of the
// camera's size), seen from frames[i]'s position and yaw.
struct MonoViews {
  std::string kind = "panorama";  // What they were made from, for the wall-cue sentence.
  PinholeCamera camera;
  std::vector<CaptureFrame> frames;
  std::vector<cv::Mat> images;
};

// What the frame loop tells its caller as it goes (report pictures, timing).
class FrameObserver {
 public:
  virtual ~FrameObserver() = default;
  // Seconds spent in one of the loop's stages, reported as they pass:
  // "rectify" (unrectified captures), "read images", LabelSource::StageName(),
  // "disparity" and "corners + points" (stereo), "contacts" (mono).
  virtual void OnStage(const std::string& stage, double seconds) = 0;
  // After each frame's points: its left (or only) image and labels as the
  // pass saw them (rectified), and the pass's result (its points, cues and,
  // for stereo, disparity).
  virtual void OnFrame(const CaptureFrame& frame, const cv::Mat& image, const cv::Mat& labels,
                       const FramePointsResult& result) = 0;
};

struct CapturePointsResult {
  std::vector<ClassPoint> points;
  std::vector<FrameCues> frames;         // Of the wall cue chosen.
  std::optional<CeilingHeight> ceiling;  // Estimated (or given) ceiling height.
  std::string wall_cue;                  // CapturePoints::Result::decision.
  // Contacts among the points: the ceiling's provenance and what was
  // rejected (ResolvedContacts; its points are in `points`).
  bool contacts_used = false;
  ResolvedContacts contacts;
  PinholeCamera camera;  // The frames' camera as measured (rectified when the capture is not).
  double seconds = 0.0;

  // "12 frames, 45123 points (wall 40000, door 3000, window 2123; corner 150,
  // edge 3000, dense 41773, boundary 200, contact 900), 3.2 s".
  std::string BriefReport() const;
};

// Every frame of a stereo or mono capture (a panorama: resample it into
// MonoViews first). Unrectified stereo captures are rectified with maps
// computed once from capture.calibration, whose image size must be the
// camera's. Mono frames must be level (pitch 0) and use contacts
// (ContactUse::kAlways whatever `options.contacts` says). Throws
// InputError for bad images, labels or calibration, naming the file.
CapturePointsResult ComputeCapturePoints(const Capture& capture, LabelSource& labels, const FramePointsOptions& options,
                                         FrameObserver* observer = nullptr, const ProgressCallback& progress = {});
// Every view of `views`, as a mono capture's frames.
CapturePointsResult ComputeCapturePoints(const MonoViews& views, LabelSource& labels, const FramePointsOptions& options,
                                         FrameObserver* observer = nullptr, const ProgressCallback& progress = {});

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_CAPTURE_POINTS_H_
