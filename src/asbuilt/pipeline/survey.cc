#include "asbuilt/pipeline/survey.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <spdlog/spdlog.h>

#include "asbuilt/pano/pano_views.h"
#include "asbuilt/pipeline/report.h"
#include "asbuilt/formats/points_ply.h"
#include "asbuilt/plan/drawing.h"
#include "asbuilt/seg/seg_data.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/stereo/rectify.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string EncodeJpeg(const cv::Mat& image, int max_width_px = 360) {
  if (image.empty()) return {};
  cv::Mat small = image;
  if (image.cols > max_width_px) {
    double s = double(max_width_px) / image.cols;
    cv::resize(image, small, cv::Size(), s, s, cv::INTER_AREA);
  }
  std::vector<uchar> bytes;
  cv::imencode(".jpg", small, bytes, {cv::IMWRITE_JPEG_QUALITY, 82});
  return std::string(bytes.begin(), bytes.end());
}

cv::Mat ReadColourImage(const fs::path& path) {
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (image.empty()) {
    throw InputError(path.string(), "", fs::exists(path) ? "cannot decode image (corrupt or not an image)"
                                                         : "image not found");
  }
  return image;
}

// Top-down picture of the class points, the measured walls, the truth plan
// (dashed) and the rig positions.
std::string PointsPlotPng(const std::vector<ClassPoint>& points, const Plan& plan,
                          const std::optional<Plan>& truth, const std::vector<Vec2>& rigs) {
  // Bounds: walls and truth, else the central 98 % of the points.
  std::vector<double> xs, ys;
  for (const PlanWall& w : plan.walls) xs.insert(xs.end(), {w.start.x(), w.end.x()}), ys.insert(ys.end(), {w.start.y(), w.end.y()});
  if (truth) for (const PlanWall& w : truth->walls) xs.insert(xs.end(), {w.start.x(), w.end.x()}), ys.insert(ys.end(), {w.start.y(), w.end.y()});
  if (xs.empty()) {
    for (std::size_t i = 0; i < points.size(); i += std::max<std::size_t>(1, points.size() / 5000)) {
      xs.push_back(points[i].position_m.x());
      ys.push_back(points[i].position_m.y());
    }
  }
  for (const Vec2& r : rigs) xs.push_back(r.x()), ys.push_back(r.y());
  if (xs.empty()) return {};
  auto range = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return std::pair(v[v.size() / 100], v[v.size() - 1 - v.size() / 100]);
  };
  auto [x0, x1] = range(xs);
  auto [y0, y1] = range(ys);
  const double margin = 0.6;
  x0 -= margin, y0 -= margin, x1 += margin, y1 += margin;
  const int size_px = 640;
  double scale = size_px / std::max({x1 - x0, y1 - y0, 1.0});
  cv::Mat img(static_cast<int>((y1 - y0) * scale) + 1, static_cast<int>((x1 - x0) * scale) + 1, CV_8UC3,
              cv::Scalar(255, 255, 255));
  auto px = [&](const Vec2& p) {
    return cv::Point(static_cast<int>((p.x() - x0) * scale), static_cast<int>((y1 - p.y()) * scale));
  };
  // 1 m grid.
  for (double gx = std::ceil(x0); gx <= x1; gx += 1) cv::line(img, px({gx, y0}), px({gx, y1}), {235, 235, 235});
  for (double gy = std::ceil(y0); gy <= y1; gy += 1) cv::line(img, px({x0, gy}), px({x1, gy}), {235, 235, 235});
  static const cv::Scalar kColour[4] = {{0, 0, 0}, {150, 150, 150}, {40, 140, 240}, {230, 160, 40}};
  std::size_t step = std::max<std::size_t>(1, points.size() / 40000);
  for (std::size_t i = 0; i < points.size(); i += step) {
    const ClassPoint& p = points[i];
    cv::Point q = px(p.position_m.head<2>());
    if (q.x < 0 || q.y < 0 || q.x >= img.cols || q.y >= img.rows) continue;
    img.at<cv::Vec3b>(q) = cv::Vec3b(kColour[static_cast<int>(p.label) & 3][0], kColour[static_cast<int>(p.label) & 3][1],
                                     kColour[static_cast<int>(p.label) & 3][2]);
  }
  if (truth) {
    for (const PlanWall& w : truth->walls) {
      Vec2 d = w.end - w.start;
      double len = d.norm();
      for (double t = 0; t < len; t += 0.2) {
        cv::line(img, px(w.start + d * (t / len)), px(w.start + d * (std::min(len, t + 0.1) / len)),
                 {60, 170, 60}, 2, cv::LINE_AA);
      }
    }
  }
  for (const PlanWall& w : plan.walls) cv::line(img, px(w.start), px(w.end), {60, 40, 30}, 2, cv::LINE_AA);
  for (const PlanOpening& o : plan.openings) {
    cv::line(img, px(o.start), px(o.end), o.kind == OpeningKind::kDoor ? cv::Scalar(40, 140, 240) : cv::Scalar(230, 160, 40),
             4, cv::LINE_AA);
  }
  for (const Vec2& r : rigs) cv::circle(img, px(r), 5, {40, 40, 220}, -1, cv::LINE_AA);
  // Scale bar: 1 m.
  cv::line(img, {12, img.rows - 14}, {12 + static_cast<int>(scale), img.rows - 14}, {0, 0, 0}, 2);
  cv::putText(img, "1 m", {16, img.rows - 20}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 1, cv::LINE_AA);
  std::vector<uchar> bytes;
  cv::imencode(".png", img, bytes);
  return std::string(bytes.begin(), bytes.end());
}

// Degrees of the full turn about the rig that at least one frame's horizontal
// field of view covers (1° bins).
double YawCoverageDeg(const std::vector<CaptureFrame>& frames, const PinholeCamera& camera) {
  const double half_fov_deg = RadToDeg(std::atan2(0.5 * camera.width_px, camera.fx));
  std::vector<bool> seen(360, false);
  for (const CaptureFrame& f : frames) {
    for (int d = static_cast<int>(std::floor(f.yaw_deg - half_fov_deg));
         d < static_cast<int>(std::ceil(f.yaw_deg + half_fov_deg)); ++d) {
      seen[((d % 360) + 360) % 360] = true;
    }
  }
  return static_cast<double>(std::count(seen.begin(), seen.end(), true));
}

// What every capture kind hands to the common tail (plan → outputs).
struct SurveyState {
  Clock::time_point start;
  std::map<std::string, double> stage_seconds;
  std::vector<std::string> stage_order;
  std::optional<Plan> truth;
  std::vector<ClassPoint> points;
  std::vector<ReportFrame> report_frames;
  std::vector<Vec2> rigs;
  std::optional<Vec3> viewpoint_m;  // Mean camera / rig position.
  double coverage_deg = 360.0;      // Of the turn around the camera.

  void AddStage(const std::string& stage, double seconds) {
    if (!stage_seconds.count(stage)) stage_order.push_back(stage);
    stage_seconds[stage] += seconds;
  }
};

std::optional<Plan> ReadTruth(const SurveyOptions& options, const fs::path& capture_json) {
  if (options.truth_path) return ReadPlan(*options.truth_path);
  if (fs::path beside = capture_json.parent_path() / "truth.json"; fs::exists(beside)) return ReadPlan(beside);
  return std::nullopt;
}

// Per wall of the plan: the points within kNearM of it (projecting inside
// it), by cue, and the fraction of its length they cover in 10 cm bins.
struct WallEvidence {
  int floor_contacts = 0, ceiling_contacts = 0, stereo = 0, vertices = 0, openings = 0;
  double seen_fraction = 0.0;
};
std::vector<WallEvidence> EvidencePerWall(const Plan& plan, const std::vector<ClassPoint>& points) {
  constexpr double kNearM = 0.1, kBinM = 0.1;
  std::vector<WallEvidence> out(plan.walls.size());
  for (std::size_t w = 0; w < plan.walls.size(); ++w) {
    const Vec2 a = plan.walls[w].start, d = plan.walls[w].end - a;
    const double length = d.norm();
    if (length <= 0) continue;
    const Vec2 dir = d / length, normal(-dir.y(), dir.x());
    std::vector<bool> bins(static_cast<std::size_t>(std::ceil(length / kBinM)), false);
    WallEvidence& e = out[w];
    for (const ClassPoint& p : points) {
      const Vec2 q = p.position_m.head<2>() - a;
      const double t = q.dot(dir);
      if (t < 0 || t > length || std::abs(q.dot(normal)) > kNearM) continue;
      bins[std::min(bins.size() - 1, static_cast<std::size_t>(t / kBinM))] = true;
      if (p.label != LabelClass::kWall) {
        ++e.openings;
      } else if (p.source == PointSource::kContact) {
        (p.position_m.z() < 0.01 ? e.floor_contacts : e.ceiling_contacts)++;
      } else if (p.source == PointSource::kVertex) {
        ++e.vertices;
      } else {
        ++e.stereo;
      }
    }
    e.seen_fraction = bins.empty() ? 0.0 : double(std::count(bins.begin(), bins.end(), true)) / bins.size();
  }
  return out;
}

fs::path ExecutableDir() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

}  // namespace

void SurveyOptions::Check() const {
  points.Check();
  CheckArgument(!contact_snap_px || *contact_snap_px >= 0,
                fmt::format("SurveyOptions.contact_snap_px = {}, must be >= 0", contact_snap_px.value_or(0)));
  plan.Check();
  CheckArgument(report_frames >= 0, fmt::format("SurveyOptions.report_frames = {}, must be >= 0", report_frames));
  panorama_views.Check();
  CheckArgument(std::abs(panorama_views.pitch_deg) < 1e-9,
                fmt::format("SurveyOptions.panorama_views.pitch_deg = {}, must be 0: contacts need level views",
                            panorama_views.pitch_deg));
  CheckArgument(min_seen_fraction >= 0 && min_seen_fraction <= 1,
                fmt::format("SurveyOptions.min_seen_fraction = {}, must be in [0, 1]", min_seen_fraction));
  if (segment_scale_px) {
    SegmentOptions{.scale_width_px = segment_scale_px->first, .scale_height_px = segment_scale_px->second}.Check();
  }
  CheckArgument(!(labels_dir && use_capture_labels),
                "SurveyOptions: give either labels_dir or use_capture_labels, not both");
}

fs::path DefaultModelPath() {
  constexpr char kName[] = "segformer_b0_asbuilt.pt";
  if (const char* env = std::getenv("ASBUILT_MODEL"); env != nullptr && *env != '\0') return env;
  fs::path exe_dir = ExecutableDir();
  std::vector<fs::path> candidates = {exe_dir / ".." / "models" / kName,
                                      exe_dir / ".." / "share" / "asbuilt" / "models" / kName,
                                      fs::path(ASBUILT_SOURCE_DIR) / "models" / kName};
  for (const fs::path& c : candidates) {
    std::error_code ec;
    if (fs::is_regular_file(c, ec)) return fs::weakly_canonical(c, ec);
  }
  return candidates.back();
}

std::string SurveySummary::BriefReport() const {
  std::string out = fmt::format("{} frames, {} points → {} walls, {} openings", frames, points, plan.walls,
                                plan.openings);
  if (plan.area_m2 > 0) out += fmt::format(", {:.2f} m²", plan.area_m2);
  if (score) {
    out += fmt::format("; walls {}/{}", score->walls.matched, score->walls.truth);
    if (auto m = score->wall_length.Median()) {
      out += fmt::format(", length err median {:.1f} % max {:.1f} %", 100 * *m, 100 * score->wall_length.Max().value_or(0));
    }
    out += fmt::format(", openings {}/{}", score->doors.matched + score->windows.matched,
                       score->doors.truth + score->windows.truth);
    if (auto m = score->opening_width.Median()) out += fmt::format(", width err median {:.1f} %", 100 * *m);
  }
  if (room_overlap) out += fmt::format(", room IoU {:.3f}", room_overlap->Iou());
  out += fmt::format("; {:.1f} s", seconds);
  if (!out_dir.empty()) out += fmt::format(" → {}", (out_dir / "report.html").string());
  return out;
}

namespace {

// The segmenter a survey uses (SurveyOptions::model_path or the shipped
// model) at SurveyOptions::segment_scale_px, or else at the images' own
// size up to twice the model's training scale; `source` says which.
std::unique_ptr<Segmenter> LoadSurveySegmenter(const SurveyOptions& options, cv::Size image, std::string* source) {
  const fs::path model = options.model_path.empty() ? DefaultModelPath() : options.model_path;
  if (!SegmenterAvailable()) {
    throw Error("this build has no segmenter (built without LibTorch): pass --labels DIR");
  }
  SegmentOptions segment;
  if (options.segment_scale_px) {
    std::tie(segment.scale_width_px, segment.scale_height_px) = *options.segment_scale_px;
  } else {
    const SegmenterInfo info = ReadSegmenterInfo(model);
    const cv::Size twice = FitSize(image, 2 * info.scale_width_px, 2 * info.scale_height_px);
    const cv::Size scale = twice.width < image.width ? twice : image;
    segment.scale_width_px = scale.width;
    segment.scale_height_px = scale.height;
  }
  std::unique_ptr<Segmenter> segmenter = LoadSegmenter(model, segment);
  *source = fmt::format("segmenter {} ({}) at {}", model.filename().string(), segmenter->info().ToString(),
                        segment.scale_width_px > 0
                            ? fmt::format("{}x{}", segment.scale_width_px, segment.scale_height_px)
                            : std::string("its training scale"));
  return segmenter;
}

SurveyResult FinishSurvey(const fs::path& capture_json, const fs::path& out_dir, const SurveyOptions& options,
                          SurveyState& st, CapturePoints::Result gathered_points, SurveyResult result);
SurveyResult RunMonoSurvey(const Capture& capture, const fs::path& capture_json, const fs::path& out_dir,
                           const SurveyOptions& options, const ProgressCallback& progress, SurveyState& st);

}  // namespace

SurveyResult RunSurvey(const fs::path& capture_json, const fs::path& out_dir, const SurveyOptions& options,
                       const ProgressCallback& progress) {
  options.Check();
  SurveyState st{.start = Clock::now()};
  SurveyResult result;
  SurveySummary& summary = result.summary;
  summary.out_dir = out_dir;
  auto add_stage = [&](const std::string& stage, double seconds) { st.AddStage(stage, seconds); };
  auto& stage_seconds = st.stage_seconds;

  // Capture, truth, rectifier.
  Clock::time_point t = Clock::now();
  const Capture capture = ReadCapture(capture_json);
  if (capture.kind != CaptureKind::kStereo) return RunMonoSurvey(capture, capture_json, out_dir, options, progress, st);
  summary.frames = static_cast<int>(capture.frames.size());
  st.truth = ReadTruth(options, capture_json);
  std::optional<StereoRectifier> rectifier;
  if (!capture.rectified) {
    const fs::path calibration_path = capture.Resolve(*capture.calibration);
    StereoCalibration calibration = LoadCalibration(calibration_path);
    if (calibration.image_size != cv::Size(capture.camera.width, capture.camera.height)) {
      throw InputError(calibration_path.string(), "image_width",
                       fmt::format("calibration is for {}x{} images, the capture's camera is {}x{}",
                                   calibration.image_size.width, calibration.image_size.height,
                                   capture.camera.width, capture.camera.height));
    }
    rectifier = MakeStereoRectifier(calibration, {});
  }
  add_stage("read capture", Since(t));

  // Labels: given, the capture's own, or the segmenter.
  LabelProvider labels;
  std::unique_ptr<Segmenter> segmenter;
  std::map<std::pair<int, int>, cv::Mat> segmented;  // (frame, eye) → labels, until the frame is loaded.
  if (options.labels_dir) {
    labels = LabelsFromDirectory(*options.labels_dir);
    summary.labels_source = fmt::format("label images in {}", options.labels_dir->string());
  } else if (options.use_capture_labels) {
    labels = LabelsFromCapture(capture);
    summary.labels_source = "the capture's own exact labels (upper bound, not a real-camera result)";
  } else {
    t = Clock::now();
    segmenter = LoadSurveySegmenter(options, cv::Size(capture.camera.width, capture.camera.height),
                                    &summary.labels_source);
    add_stage("load model", Since(t));
    labels = [&](const CaptureFrame& frame, StereoEye eye) -> cv::Mat {
      auto key = std::pair(frame.index, eye == StereoEye::kLeft ? 0 : 1);
      if (auto it = segmented.find(key); it != segmented.end()) return it->second;
      // Both views of this frame and of the next in one batched forward
      // pass: on 2 cores a batch of 4 at 640×480 takes 0.29 s an image, of
      // 2 0.38 s, of 1 0.46 s (bench/results/survey.md).
      Clock::time_point ts = Clock::now();
      std::vector<const CaptureFrame*> batch = {&frame};
      const auto at = std::find_if(capture.frames.begin(), capture.frames.end(),
                                   [&](const CaptureFrame& f) { return f.index == frame.index; });
      if (at != capture.frames.end() && std::next(at) != capture.frames.end()) batch.push_back(&*std::next(at));
      std::vector<cv::Mat> images;
      for (const CaptureFrame* f : batch) {
        images.push_back(ReadColourImage(capture.Resolve(f->left)));
        images.push_back(ReadColourImage(capture.Resolve(f->right)));
      }
      std::vector<cv::Mat> out = segmenter->SegmentBatch(images);
      add_stage("segment", Since(ts));
      for (size_t k = 0; k < batch.size(); ++k) {
        segmented[{batch[k]->index, 0}] = out[2 * k];
        segmented[{batch[k]->index, 1}] = out[2 * k + 1];
      }
      return segmented.at(key);
    };
  }

  // Per frame: load (rectify), labels, disparity, points.
  std::vector<ReportFrame> report_frames;
  FramePointsOptions point_options = options.points;
  point_options.contact_snap_px =
      FramePointsOptions::ContactSnapPxFor(options.contact_snap_px, options.use_capture_labels);
  CapturePoints gathered(point_options);
  Vec3 rig_sum = Vec3::Zero();
  int done = 0;
  const int total = static_cast<int>(capture.frames.size());
  for (const CaptureFrame& frame : capture.frames) {
    ReportProgress(progress, {.stage = "survey", .done = done, .total = total,
                              .detail = fmt::format("frame {}", frame.index)});
    t = Clock::now();
    StereoFrame stereo = LoadStereoFrame(capture, frame, labels, rectifier ? &*rectifier : nullptr);
    segmented.erase({frame.index, 0});
    segmented.erase({frame.index, 1});
    add_stage("load + rectify", Since(t));  // Segmenting inside it is moved out below.
    t = Clock::now();
    FramePointsResult r = ComputeFramePoints(stereo, point_options);
    double frame_seconds = Since(t);
    add_stage("disparity", r.disparity.seconds);
    add_stage("corners + points", std::max(0.0, frame_seconds - r.disparity.seconds));
    gathered.Add(r);
    rig_sum += frame.position_m;
    if (options.report_frames == 0 || static_cast<int>(report_frames.size()) < options.report_frames) {
      t = Clock::now();
      ReportFrame rf{.index = frame.index, .yaw_deg = frame.yaw_deg};
      rf.left_jpeg = EncodeJpeg(stereo.left);
      cv::Mat left_bgr = stereo.left;
      if (left_bgr.channels() == 1) cv::cvtColor(stereo.left, left_bgr, cv::COLOR_GRAY2BGR);
      if (stereo.labels_left.size() == left_bgr.size()) {
        rf.overlay_jpeg = EncodeJpeg(LabelOverlay(left_bgr, stereo.labels_left));
      }
      if (!r.disparity.disparity_px.empty()) rf.disparity_jpeg = EncodeJpeg(ColorizeDisparity(r.disparity.disparity_px));
      report_frames.push_back(std::move(rf));
      add_stage("report pictures", Since(t));
    }
    if (r.cues.CarriedBy() == "none") {
      summary.notes.push_back(fmt::format("frame {}: no points (no labelled structure with stereo evidence)", frame.index));
    }
    ++done;
  }
  // Move the segment time out of "load + rectify" (the provider runs inside it).
  if (stage_seconds.count("segment")) {
    stage_seconds["load + rectify"] = std::max(0.0, stage_seconds["load + rectify"] - stage_seconds["segment"]);
  }
  ReportProgress(progress, {.stage = "survey", .done = done, .total = total});
  for (const CaptureFrame& frame : capture.frames) st.rigs.push_back(frame.position_m.head<2>());
  if (total > 0) st.viewpoint_m = rig_sum / total;
  st.coverage_deg = YawCoverageDeg(capture.frames, rectifier ? rectifier->camera : capture.camera.Pinhole());
  st.report_frames = std::move(report_frames);
  return FinishSurvey(capture_json, out_dir, options, st, gathered.Finish(), std::move(result));
}

namespace {

SurveyResult FinishSurvey(const fs::path& capture_json, const fs::path& out_dir, const SurveyOptions& options,
                          SurveyState& st, CapturePoints::Result gathered_points, SurveyResult result) {
  SurveySummary& summary = result.summary;
  std::vector<ClassPoint>& points = st.points;
  std::vector<ReportFrame>& report_frames = st.report_frames;
  const std::optional<Plan>& truth = st.truth;
  auto add_stage = [&](const std::string& stage, double seconds) { st.AddStage(stage, seconds); };
  Clock::time_point t;
  // The wall cue for the whole capture (stereo, or floor/ceiling contacts
  // where the walls' stereo disagrees with them); wall–ceiling contacts become
  // points once the ceiling's height is known from the columns that saw both
  // of a wall's edges (all frames together).
  points = std::move(gathered_points.points);
  summary.wall_cue = gathered_points.decision;
  if (!summary.wall_cue.empty()) spdlog::info("survey: {}", summary.wall_cue);
  summary.frame_cues = std::move(gathered_points.frames);
  for (std::size_t i = 0; i < report_frames.size(); ++i) report_frames[i].cues = summary.frame_cues[i].BriefReport();
  if (gathered_points.contacts_used) {
    const ResolvedContacts& contacts = gathered_points.contacts;
    spdlog::info("survey: ceiling height {} ({}); {} floor contact(s) rejected as tops of things before a wall{}",
                 contacts.ceiling ? fmt::format("{:.3f} ± {:.3f} m", contacts.ceiling->height_m, contacts.ceiling->sigma_m)
                                  : "not measured",
                 contacts.how, contacts.floor_rejected,
                 contacts.ceiling_rejected > 0
                     ? fmt::format(", {} ceiling contact(s) where a frame beside saw the wall rise higher",
                                   contacts.ceiling_rejected)
                     : "");
    if (contacts.ceiling) {
      summary.ceiling_height_m = contacts.ceiling->height_m;
      summary.ceiling_height_sigma_m = contacts.ceiling->sigma_m;
    } else if (contacts.ceiling_unused > 0) {
      summary.notes.push_back(fmt::format(
          "the ceiling's height could not be measured: {} wall–ceiling contacts unused", contacts.ceiling_unused));
    }
  }
  summary.points = static_cast<int>(points.size());

  // Plan.
  t = Clock::now();
  PlanOptions plan_options = options.plan;
  if (!plan_options.viewpoint_m) plan_options.viewpoint_m = st.viewpoint_m;
  try {
    PlanResult plan = ReconstructPlan(points, plan_options, capture_json.string());
    result.plan = std::move(plan.plan);
    summary.plan = plan.summary;
    if (!plan.summary.closed && !result.plan.walls.empty()) {
      summary.notes.push_back("the walls found do not close into a room: the area is not measured");
    }
  } catch (const InputError& e) {
    summary.notes.push_back(fmt::format("no plan: {}", e.what()));
  } catch (const InvalidArgument& e) {
    summary.notes.push_back(fmt::format("no plan: {}", e.what()));
  }
  if (result.plan.walls.empty()) summary.notes.push_back("no walls could be measured from this capture");
  // Views that do not go round the room cannot close it (a real capture of
  // one direction, e.g. EuRoC): say what the closed polygon rests on.
  if (const double coverage_deg = st.coverage_deg; coverage_deg < 359.5 && !result.plan.walls.empty()) {
    std::string note = fmt::format("the views cover {:.0f}° of the turn around the rig: walls outside them are not measured",
                                   coverage_deg);
    if (summary.plan.closed) {
      note += fmt::format("; the room polygon closes through {} inferred wall(s), so its area ({:.2f} m²) is not a measurement",
                          summary.plan.inferred_walls, summary.plan.area_m2);
    }
    summary.notes.push_back(note);
  }
  // Which cue placed each wall, and where the room is larger than the
  // capture saw (a wall seen along little of its length, or inferred).
  {
    const std::vector<WallEvidence> evidence = EvidencePerWall(result.plan, points);
    std::vector<std::string> unseen;
    for (std::size_t w = 0; w < evidence.size(); ++w) {
      const WallEvidence& e = evidence[w];
      const double length = (result.plan.walls[w].end - result.plan.walls[w].start).norm();
      std::vector<std::string> cues;
      if (e.floor_contacts > 0) cues.push_back(fmt::format("floor contacts {}", e.floor_contacts));
      if (e.ceiling_contacts > 0) cues.push_back(fmt::format("ceiling contacts {}", e.ceiling_contacts));
      if (e.stereo > 0) cues.push_back(fmt::format("stereo points {}", e.stereo));
      if (e.vertices > 0) cues.push_back(fmt::format("corner columns {}", e.vertices));
      if (e.openings > 0) cues.push_back(fmt::format("door/window points {}", e.openings));
      std::string line = fmt::format("wall {}, {:.2f} m: ", w, length);
      if (cues.empty()) {
        line += "inferred: no point of it was seen (it closes the room between the walls beside it)";
      } else {
        for (std::size_t k = 0; k < cues.size(); ++k) line += (k ? ", " : "") + cues[k];
        line += fmt::format("; seen along {:.0f} % of its length", 100 * e.seen_fraction);
      }
      summary.wall_cues.push_back(line);
      if (e.seen_fraction < options.min_seen_fraction) {
        ++summary.walls_unseen;
        unseen.push_back(fmt::format("wall {} ({:.2f} m, seen along {:.0f} %)", w, length, 100 * e.seen_fraction));
      }
    }
    if (!unseen.empty()) {
      std::string list;
      for (std::size_t k = 0; k < unseen.size(); ++k) list += (k ? ", " : "") + unseen[k];
      summary.notes.push_back(fmt::format(
          "the room is larger than what this capture sees: {} {} mostly or wholly unseen, so {} length{} and "
          "the room's area rest on walls inferred across what was not seen — survey from another spot to measure them",
          list, unseen.size() == 1 ? "is" : "are", unseen.size() == 1 ? "its" : "their", unseen.size() == 1 ? "" : "s"));
    }
  }
  add_stage("plan", Since(t));

  // Score.
  if (truth) {
    summary.score = ScorePlan(result.plan, *truth);
    summary.room_overlap = RoomPolygonOverlap(result.plan, *truth);
  }

  // Outputs.
  t = Clock::now();
  fs::create_directories(out_dir);
  WritePlan(result.plan, out_dir / "plan.json");
  WritePoints(points, out_dir / "points.txt");
  WritePointsPly(points, out_dir / "points.ply");
  std::string plan_svg;
  if (!result.plan.walls.empty()) {
    WritePlanFiles(result.plan, out_dir);  // plan.json again (same), .svg, .dxf, .pdf, .png, .ifc
    plan_svg = ReadFile(out_dir / "plan.svg");
  }
  if (summary.score) WriteFileAtomic(out_dir / "score.json", PlanScoreToJson(*summary.score).dump(2) + "\n");
  add_stage("write outputs", Since(t));

  summary.seconds = Since(st.start);
  for (const std::string& s : st.stage_order) summary.stages.push_back({s, st.stage_seconds[s]});

  if (options.write_report) {
    t = Clock::now();
    SurveyReport report{.title = fmt::format("Survey of {}", capture_json.filename().string()),
                        .capture_path = capture_json,
                        .summary = summary,
                        .plan = result.plan,
                        .truth = truth,
                        .frames = std::move(report_frames),
                        .points_plot_png = PointsPlotPng(points, result.plan, truth, st.rigs),
                        .plan_svg = plan_svg};
    double report_seconds = Since(t);
    report.summary.stages.push_back({"report", report_seconds});
    WriteSurveyReport(report, out_dir / "report.html");
  }
  nlohmann::json js = {{"brief", summary.BriefReport()}, {"capture_kind", summary.capture_kind},
                       {"frames", summary.frames}, {"points", summary.points},
                       {"labels_source", summary.labels_source}, {"plan", summary.plan.BriefReport()},
                       {"notes", summary.notes}, {"seconds", summary.seconds}};
  if (!summary.wall_cue.empty()) js["wall_cue"] = summary.wall_cue;
  js["wall_cues"] = summary.wall_cues;
  js["walls_unseen"] = summary.walls_unseen;
  for (const StageTiming& s : summary.stages) js["stages"][s.stage] = s.seconds;
  if (std::isfinite(summary.ceiling_height_m)) {
    js["ceiling_height_m"] = summary.ceiling_height_m;
    js["ceiling_height_sigma_m"] = summary.ceiling_height_sigma_m;
  }
  if (summary.score) js["score"] = PlanScoreToJson(*summary.score);
  if (summary.room_overlap) {
    js["room_iou"] = summary.room_overlap->Iou();
    js["room_intersection_m2"] = summary.room_overlap->intersection_m2;
    js["room_union_m2"] = summary.room_overlap->union_m2;
  }
  WriteFileAtomic(out_dir / "summary.json", js.dump(2) + "\n");
  return result;
}


// Mono and panorama captures: level views of one camera, walls placed by
// their floor/ceiling contacts (no second view, so no stereo).
SurveyResult RunMonoSurvey(const Capture& capture, const fs::path& capture_json, const fs::path& out_dir,
                           const SurveyOptions& options, const ProgressCallback& progress, SurveyState& st) {
  SurveyResult result;
  SurveySummary& summary = result.summary;
  summary.out_dir = out_dir;
  summary.capture_kind = CaptureKindName(capture.kind);
  Clock::time_point t = Clock::now();
  st.truth = ReadTruth(options, capture_json);

  // The frames: the capture's own views, or the panorama resampled.
  std::vector<CaptureFrame> frames;
  std::vector<cv::Mat> images;  // Panorama views (in memory), by frame.
  PinholeCamera camera;
  if (capture.kind == CaptureKind::kPanorama) {
    const CapturePanorama& pano = *capture.panorama;
    const fs::path pano_path = capture.Resolve(pano.image);
    const cv::Mat equirect = ReadEquirect(pano_path);
    const std::vector<PanoView> views = TurnInPlaceViews(options.panorama_views);
    camera = views.front().camera;
    for (std::size_t i = 0; i < views.size(); ++i) {
      CaptureFrame f{.index = static_cast<int>(i), .left = fmt::format("{}#view{:03d}", pano.image, i),
                     .yaw_deg = pano.yaw_deg + views[i].yaw_deg, .position_m = pano.position_m};
      frames.push_back(std::move(f));
      images.push_back(RenderPanoView(equirect, views[i]));
    }
    if (options.use_capture_labels) {
      throw InvalidArgument("a panorama capture has no labels of its own: give --labels DIR (NNN.png per view)");
    }
  } else {
    camera = capture.camera.Pinhole();
    for (std::size_t i = 0; i < capture.frames.size(); ++i) {
      const CaptureFrame& f = capture.frames[i];
      if (std::abs(f.pitch_deg) > 0.01) {
        throw InputError(capture_json.string(), fmt::format("frames[{}].pitch_deg", i),
                         fmt::format("{}: a mono survey places walls from a level camera (pitch 0)", f.pitch_deg));
      }
    }
    frames = capture.frames;
  }
  summary.frames = static_cast<int>(frames.size());
  st.AddStage("read capture", Since(t));

  auto image_of = [&](std::size_t i) -> cv::Mat {
    cv::Mat image = images.empty() ? ReadColourImage(capture.Resolve(frames[i].left)) : images[i];
    if (image.cols != camera.width_px || image.rows != camera.height_px) {
      throw InputError(capture.Resolve(frames[i].left).string(), "",
                       fmt::format("image is {}x{}, capture.json's camera is {}x{}", image.cols, image.rows,
                                   camera.width_px, camera.height_px));
    }
    return image;
  };

  // Labels: given, the capture's own, or the segmenter (a few views a pass).
  std::function<std::vector<cv::Mat>(std::size_t first, const std::vector<cv::Mat>& batch)> label_batch;
  if (options.labels_dir || options.use_capture_labels) {
    const LabelProvider provider =
        options.labels_dir ? LabelsFromDirectory(*options.labels_dir) : LabelsFromCapture(capture);
    summary.labels_source = options.labels_dir ? fmt::format("label images in {}", options.labels_dir->string())
                                               : "the capture's own labels";
    label_batch = [&, provider](std::size_t first, const std::vector<cv::Mat>& batch) {
      std::vector<cv::Mat> out;
      for (std::size_t k = 0; k < batch.size(); ++k) out.push_back(provider(frames[first + k], StereoEye::kLeft));
      return out;
    };
  } else {
    t = Clock::now();
    auto segmenter = std::shared_ptr<Segmenter>(
        LoadSurveySegmenter(options, cv::Size(camera.width_px, camera.height_px), &summary.labels_source));
    st.AddStage("load model", Since(t));
    label_batch = [segmenter](std::size_t, const std::vector<cv::Mat>& batch) {
      return segmenter->SegmentBatch(batch);
    };
  }

  FramePointsOptions point_options = options.points;
  point_options.contacts = ContactUse::kAlways;
  point_options.contact_snap_px =
      FramePointsOptions::ContactSnapPxFor(options.contact_snap_px, options.use_capture_labels);
  CapturePoints gathered(point_options);
  constexpr std::size_t kBatch = 4;
  Vec3 camera_sum = Vec3::Zero();
  for (std::size_t first = 0; first < frames.size(); first += kBatch) {
    ReportProgress(progress, {.stage = "survey", .done = static_cast<std::int64_t>(first),
                              .total = static_cast<std::int64_t>(frames.size())});
    t = Clock::now();
    std::vector<cv::Mat> batch;
    for (std::size_t i = first; i < std::min(frames.size(), first + kBatch); ++i) batch.push_back(image_of(i));
    st.AddStage("load images", Since(t));
    t = Clock::now();
    std::vector<cv::Mat> labels = label_batch(first, batch);
    st.AddStage(options.labels_dir || options.use_capture_labels ? "load labels" : "segment", Since(t));
    for (std::size_t k = 0; k < batch.size(); ++k) {
      const CaptureFrame& frame = frames[first + k];
      if (labels[k].size() != batch[k].size()) {
        throw InputError(options.labels_dir ? (*options.labels_dir / fmt::format("{:03d}.png", frame.index)).string()
                                            : capture_json.string(),
                         "", fmt::format("labels are {}x{}, the view is {}x{}", labels[k].cols, labels[k].rows,
                                         batch[k].cols, batch[k].rows));
      }
      t = Clock::now();
      MonoFrame mono{.image = batch[k], .labels = labels[k], .camera = camera,
                     .pose = {frame.position_m, DegToRad(frame.yaw_deg)}, .index = frame.index};
      FramePointsResult r = ComputeMonoFramePoints(mono, point_options);
      st.AddStage("contacts", Since(t));
      if (r.cues.CarriedBy() == "none") {
        summary.notes.push_back(fmt::format("view {}: no floor or ceiling contact of a wall", frame.index));
      }
      gathered.Add(r);
      camera_sum += frame.position_m;
      if (options.report_frames == 0 || static_cast<int>(st.report_frames.size()) < options.report_frames) {
        t = Clock::now();
        ReportFrame rf{.index = frame.index, .yaw_deg = frame.yaw_deg};
        rf.left_jpeg = EncodeJpeg(batch[k]);
        rf.overlay_jpeg = EncodeJpeg(LabelOverlay(batch[k], labels[k]));
        st.report_frames.push_back(std::move(rf));
        st.AddStage("report pictures", Since(t));
      }
    }
  }
  ReportProgress(progress, {.stage = "survey", .done = static_cast<std::int64_t>(frames.size()),
                            .total = static_cast<std::int64_t>(frames.size())});
  for (const CaptureFrame& f : frames) st.rigs.push_back(f.position_m.head<2>());
  if (!frames.empty()) st.viewpoint_m = camera_sum / static_cast<double>(frames.size());
  st.coverage_deg = YawCoverageDeg(frames, camera);
  CapturePoints::Result gathered_points = gathered.Finish();
  gathered_points.decision = fmt::format(
      "walls placed by their floor/ceiling contacts from a level camera {:.3f} m above the floor ({} capture: one "
      "camera, no stereo)",
      frames.empty() ? 0.0 : camera_sum.z() / static_cast<double>(frames.size()), summary.capture_kind);
  return FinishSurvey(capture_json, out_dir, options, st, std::move(gathered_points), std::move(result));
}
}  // namespace

}  // namespace asbuilt
