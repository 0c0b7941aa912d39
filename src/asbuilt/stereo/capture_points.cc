#include "asbuilt/stereo/capture_points.h"

#include <algorithm>
#include <chrono>

#include <fmt/format.h>

#include "asbuilt/stereo/cue_choice.h"
#include "asbuilt/stereo/rectify.h"
#include "asbuilt/util/error.h"

namespace asbuilt {

std::string CapturePointsResult::BriefReport() const {
  int by_class[4] = {0, 0, 0, 0}, by_source[6] = {0, 0, 0, 0, 0, 0};
  for (const ClassPoint& p : points) {
    ++by_class[static_cast<int>(p.label) & 3];
    ++by_source[std::min(5, static_cast<int>(p.source))];
  }
  int carried = 0;
  for (const FrameCues& f : frames) carried += f.CarriedBy() != "none";
  return fmt::format(
      "{} frames ({} with points), {} points (wall {}, door {}, "
      "window {}; corner {}, edge {}, dense {}, boundary {}, "
      "contact {}){}, {:.1f} s",
      frames.size(), carried, points.size(), by_class[1], by_class[2], by_class[3], by_source[0], by_source[2],
      by_source[1], by_source[4], by_source[5],
      ceiling ? fmt::format(", ceiling {:.3f} ± {:.3f} m", ceiling->height_m, ceiling->sigma_m) : "", seconds);
}

CapturePointsResult ComputeCapturePoints(const Capture& capture, const LabelProvider& labels,
                                         const FramePointsOptions& options, const ProgressCallback& progress) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  std::optional<StereoRectifier> rectifier;
  if (!capture.rectified) {
    if (!capture.calibration) throw InputError("capture.json", "calibration", "needed when rectified is false");
    rectifier = MakeStereoRectifier(LoadCalibration(capture.Resolve(*capture.calibration)), {});
  }
  CapturePointsResult result;
  CapturePoints gathered(options);
  int done = 0;
  for (const CaptureFrame& frame : capture.frames) {
    ReportProgress(progress, {"points", done, static_cast<std::int64_t>(capture.frames.size()), ""});
    const StereoFrame stereo = LoadStereoFrame(capture, frame, labels, rectifier ? &*rectifier : nullptr);
    FramePointsResult r = ComputeFramePoints(stereo, options);
    gathered.Add(r);
    ++done;
  }
  CapturePoints::Result finished = gathered.Finish();
  result.frames = std::move(finished.frames);
  result.points = std::move(finished.points);
  result.ceiling = finished.contacts.ceiling;
  result.wall_cue = finished.decision;
  ReportProgress(progress, {"points", done, static_cast<std::int64_t>(capture.frames.size()), ""});
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace asbuilt
