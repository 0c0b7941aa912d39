#include "asbuilt/stereo/capture_points.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>

#include <fmt/format.h>

#include "asbuilt/imageio/image_io.h"
#include "asbuilt/stereo/cue_choice.h"
#include "asbuilt/stereo/rectify.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Where the loop's frames come from: a capture's files or views in memory.
struct FrameFeed {
  const std::vector<CaptureFrame>* frames = nullptr;
  std::function<FrameImages(std::size_t i)> read;
  bool stereo = true;
  const Capture* capture = nullptr;            // Stereo: MakeStereoFrame.
  const StereoRectifier* rectifier = nullptr;  // Stereo, unrectified.
  PinholeCamera camera;                        // As measured.
  std::string mono_kind;                       // Mono: "mono", "panorama".
};

// The rectifier of an unrectified stereo capture (nullopt when rectified),
// its calibration checked against the capture's image size.
std::optional<StereoRectifier> CaptureRectifier(const Capture& capture) {
  if (capture.rectified) return std::nullopt;
  if (!capture.calibration) throw InputError("capture.json", "calibration", "needed when rectified is false");
  const fs::path path = capture.Resolve(*capture.calibration);
  const StereoCalibration calibration = LoadCalibration(path);
  if (calibration.image_size != cv::Size(capture.camera.width, capture.camera.height)) {
    throw InputError(
        path.string(), "image_width",
        fmt::format("calibration is for {}x{} images, the capture's camera is {}x{}", calibration.image_size.width,
                    calibration.image_size.height, capture.camera.width, capture.camera.height));
  }
  return MakeStereoRectifier(calibration, {});
}

// One frame's points from its decoded images and labels.
FramePointsResult PointsOfFrame(const FrameFeed& feed, FrameImages images, FrameLabels labels,
                                const FramePointsOptions& options, FrameObserver* observer) {
  auto stage = [&](const std::string& name, double seconds) {
    if (observer) observer->OnStage(name, seconds);
  };
  const CaptureFrame frame = images.frame;
  if (!feed.stereo) {
    if (labels.left.size() != images.left.size()) {
      throw InputError(feed.capture ? feed.capture->Resolve(frame.left).string() : frame.left, "labels",
                       fmt::format("frame {}: labels are {}x{}, the image is {}x{}", frame.index, labels.left.cols,
                                   labels.left.rows, images.left.cols, images.left.rows));
    }
    const auto t = Clock::now();
    const MonoFrame mono{.image = images.left,
                         .labels = labels.left,
                         .camera = feed.camera,
                         .pose = {frame.position_m, DegToRad(frame.yaw_deg)},
                         .index = frame.index};
    FramePointsResult r = ComputeMonoFramePoints(mono, options);
    stage("contacts", SecondsSince(t));
    if (observer) observer->OnFrame(frame, mono.image, mono.labels, r);
    return r;
  }
  auto t = Clock::now();
  const StereoFrame stereo = MakeStereoFrame(*feed.capture, std::move(images), std::move(labels), feed.rectifier);
  if (feed.rectifier) stage("rectify", SecondsSince(t));
  t = Clock::now();
  FramePointsResult r = ComputeFramePoints(stereo, options);
  const double seconds = SecondsSince(t);
  stage("disparity", r.disparity.seconds);
  stage("corners + points", std::max(0.0, seconds - r.disparity.seconds));
  if (observer) observer->OnFrame(frame, stereo.left, stereo.labels_left, r);
  return r;
}

// The one loop over a capture's frames (capture_points.h).
CapturePointsResult RunFrameLoop(const FrameFeed& feed, LabelSource& labels, FramePointsOptions options,
                                 FrameObserver* observer, const ProgressCallback& progress) {
  const auto start = Clock::now();
  if (!feed.stereo) options.contacts = ContactUse::kAlways;
  options.Check();
  const std::vector<CaptureFrame>& frames = *feed.frames;
  const auto total = static_cast<std::int64_t>(frames.size());
  // Frames per LabelSource::Label call: as many as its batch of images holds.
  const std::size_t batch = std::max(1, labels.BatchImages() / (feed.stereo ? 2 : 1));
  CapturePoints gathered(options);
  Vec3 camera_sum = Vec3::Zero();
  for (std::size_t first = 0; first < frames.size(); first += batch) {
    auto t = Clock::now();
    std::vector<FrameImages> images;
    for (std::size_t i = first; i < std::min(frames.size(), first + batch); ++i) images.push_back(feed.read(i));
    if (observer) observer->OnStage("read images", SecondsSince(t));
    t = Clock::now();
    std::vector<FrameLabels> labelled = labels.Label(images);
    if (observer) observer->OnStage(labels.StageName(), SecondsSince(t));
    CheckArgument(labelled.size() == images.size(), "LabelSource::Label gave labels for a different number of frames");
    for (std::size_t k = 0; k < images.size(); ++k) {
      const CaptureFrame& frame = frames[first + k];
      ReportProgress(progress, {.stage = "points",
                                .done = static_cast<std::int64_t>(first + k),
                                .total = total,
                                .detail = fmt::format("frame {}", frame.index)});
      FramePointsResult r = PointsOfFrame(feed, std::move(images[k]), std::move(labelled[k]), options, observer);
      gathered.Add(r);
      camera_sum += frame.position_m;
    }
  }
  ReportProgress(progress, {.stage = "points", .done = total, .total = total});
  CapturePoints::Result finished = gathered.Finish();
  if (!feed.stereo) {
    finished.decision = fmt::format(
        "walls placed by their floor/ceiling contacts from a level camera {:.3f} m above the floor ({} capture: one "
        "camera, no stereo)",
        frames.empty() ? 0.0 : camera_sum.z() / static_cast<double>(frames.size()), feed.mono_kind);
  }
  CapturePointsResult result{.points = std::move(finished.points),
                             .frames = std::move(finished.frames),
                             .ceiling = finished.contacts.ceiling,
                             .wall_cue = std::move(finished.decision),
                             .contacts_used = finished.contacts_used,
                             .contacts = std::move(finished.contacts),
                             .camera = feed.camera};
  result.seconds = SecondsSince(start);
  return result;
}

}  // namespace

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

CapturePointsResult ComputeCapturePoints(const Capture& capture, LabelSource& labels, const FramePointsOptions& options,
                                         FrameObserver* observer, const ProgressCallback& progress) {
  CheckArgument(capture.kind != CaptureKind::kPanorama,
                "ComputeCapturePoints: a panorama capture is resampled into MonoViews first");
  FrameFeed feed{.frames = &capture.frames,
                 .read = [&](std::size_t i) { return ReadFrameImages(capture, capture.frames[i]); },
                 .stereo = capture.kind == CaptureKind::kStereo,
                 .capture = &capture,
                 .camera = capture.camera.Pinhole(),
                 .mono_kind = CaptureKindName(capture.kind)};
  std::optional<StereoRectifier> rectifier;
  if (feed.stereo) {
    const auto t = Clock::now();
    rectifier = CaptureRectifier(capture);
    if (rectifier) {
      feed.rectifier = &*rectifier;
      feed.camera = rectifier->camera;
      if (observer) observer->OnStage("rectify", SecondsSince(t));
    }
  } else {
    for (std::size_t i = 0; i < capture.frames.size(); ++i) {
      const CaptureFrame& f = capture.frames[i];
      if (std::abs(f.pitch_deg) > 0.01) {
        throw InputError((capture.base_dir / "capture.json").string(), fmt::format("frames[{}].pitch_deg", i),
                         fmt::format("{}: a mono survey places walls from a level camera (pitch 0)", f.pitch_deg));
      }
    }
  }
  return RunFrameLoop(feed, labels, options, observer, progress);
}

CapturePointsResult ComputeCapturePoints(const MonoViews& views, LabelSource& labels, const FramePointsOptions& options,
                                         FrameObserver* observer, const ProgressCallback& progress) {
  CheckArgument(views.images.size() == views.frames.size(),
                "ComputeCapturePoints: MonoViews needs one image per frame");
  const FrameFeed feed{.frames = &views.frames,
                       .read =
                           [&](std::size_t i) {
                             CheckImageSize(views.images[i], views.camera.width_px, views.camera.height_px,
                                            views.frames[i].left, "", "the views' camera");
                             return FrameImages{.frame = views.frames[i], .left = views.images[i]};
                           },
                       .stereo = false,
                       .camera = views.camera,
                       .mono_kind = views.kind};
  return RunFrameLoop(feed, labels, options, observer, progress);
}

}  // namespace asbuilt
