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

#include "asbuilt/pipeline/report.h"
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
double YawCoverageDeg(const Capture& capture, const PinholeCamera& camera) {
  const double half_fov_deg = RadToDeg(std::atan2(0.5 * camera.width_px, camera.fx));
  std::vector<bool> seen(360, false);
  for (const CaptureFrame& f : capture.frames) {
    for (int d = static_cast<int>(std::floor(f.yaw_deg - half_fov_deg));
         d < static_cast<int>(std::ceil(f.yaw_deg + half_fov_deg)); ++d) {
      seen[((d % 360) + 360) % 360] = true;
    }
  }
  return static_cast<double>(std::count(seen.begin(), seen.end(), true));
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
  out += fmt::format("; {:.1f} s", seconds);
  if (!out_dir.empty()) out += fmt::format(" → {}", (out_dir / "report.html").string());
  return out;
}

SurveyResult RunSurvey(const fs::path& capture_json, const fs::path& out_dir, const SurveyOptions& options,
                       const ProgressCallback& progress) {
  options.Check();
  const Clock::time_point start = Clock::now();
  SurveyResult result;
  SurveySummary& summary = result.summary;
  summary.out_dir = out_dir;
  std::map<std::string, double> stage_seconds;
  std::vector<std::string> stage_order;
  auto add_stage = [&](const std::string& stage, double seconds) {
    if (!stage_seconds.count(stage)) stage_order.push_back(stage);
    stage_seconds[stage] += seconds;
  };

  // Capture, truth, rectifier.
  Clock::time_point t = Clock::now();
  const Capture capture = ReadCapture(capture_json);
  summary.frames = static_cast<int>(capture.frames.size());
  std::optional<Plan> truth;
  if (options.truth_path) {
    truth = ReadPlan(*options.truth_path);
  } else if (fs::path beside = capture_json.parent_path() / "truth.json"; fs::exists(beside)) {
    truth = ReadPlan(beside);
  }
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
    fs::path model = options.model_path.empty() ? DefaultModelPath() : options.model_path;
    if (!SegmenterAvailable()) {
      throw Error("this build has no segmenter (built without LibTorch): pass --labels DIR");
    }
    SegmentOptions segment;
    if (options.segment_scale_px) {
      std::tie(segment.scale_width_px, segment.scale_height_px) = *options.segment_scale_px;
    } else {
      const SegmenterInfo info = ReadSegmenterInfo(model);
      const cv::Size image(capture.camera.width, capture.camera.height);
      const cv::Size twice = FitSize(image, 2 * info.scale_width_px, 2 * info.scale_height_px);
      const cv::Size scale = twice.width < image.width ? twice : image;
      segment.scale_width_px = scale.width;
      segment.scale_height_px = scale.height;
    }
    segmenter = LoadSegmenter(model, segment);
    summary.labels_source =
        fmt::format("segmenter {} ({}) at {}", model.filename().string(), segmenter->info().ToString(),
                    segment.scale_width_px > 0 ? fmt::format("{}x{}", segment.scale_width_px, segment.scale_height_px)
                                               : std::string("its training scale"));
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
  std::vector<ClassPoint> points;
  std::vector<ReportFrame> report_frames;
  std::vector<Vec2> rigs;
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
    rigs.push_back(frame.position_m.head<2>());
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
  // The wall cue for the whole capture (stereo, or floor/ceiling contacts
  // where the walls' stereo disagrees with them); wall–ceiling contacts become
  // points once the ceiling's height is known from the columns that saw both
  // of a wall's edges (all frames together).
  CapturePoints::Result gathered_points = gathered.Finish();
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
  if (!plan_options.viewpoint_m && total > 0) plan_options.viewpoint_m = rig_sum / total;
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
  if (const double coverage_deg = YawCoverageDeg(capture, rectifier ? rectifier->camera : capture.camera.Pinhole());
      coverage_deg < 359.5 && !result.plan.walls.empty()) {
    std::string note = fmt::format("the views cover {:.0f}° of the turn around the rig: walls outside them are not measured",
                                   coverage_deg);
    if (summary.plan.closed) {
      note += fmt::format("; the room polygon closes through {} inferred wall(s), so its area ({:.2f} m²) is not a measurement",
                          summary.plan.inferred_walls, summary.plan.area_m2);
    }
    summary.notes.push_back(note);
  }
  add_stage("plan", Since(t));

  // Score.
  if (truth) {
    summary.score = ScorePlan(result.plan, *truth);
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

  summary.seconds = Since(start);
  for (const std::string& s : stage_order) summary.stages.push_back({s, stage_seconds[s]});

  if (options.write_report) {
    t = Clock::now();
    SurveyReport report{.title = fmt::format("Survey of {}", capture_json.filename().string()),
                        .capture_path = capture_json,
                        .summary = summary,
                        .plan = result.plan,
                        .truth = truth,
                        .frames = std::move(report_frames),
                        .points_plot_png = PointsPlotPng(points, result.plan, truth, rigs),
                        .plan_svg = plan_svg};
    double report_seconds = Since(t);
    report.summary.stages.push_back({"report", report_seconds});
    WriteSurveyReport(report, out_dir / "report.html");
  }
  nlohmann::json js = {{"brief", summary.BriefReport()}, {"frames", summary.frames}, {"points", summary.points},
                       {"labels_source", summary.labels_source}, {"plan", summary.plan.BriefReport()},
                       {"notes", summary.notes}, {"seconds", summary.seconds}};
  if (!summary.wall_cue.empty()) js["wall_cue"] = summary.wall_cue;
  for (const StageTiming& s : summary.stages) js["stages"][s.stage] = s.seconds;
  if (std::isfinite(summary.ceiling_height_m)) {
    js["ceiling_height_m"] = summary.ceiling_height_m;
    js["ceiling_height_sigma_m"] = summary.ceiling_height_sigma_m;
  }
  if (summary.score) js["score"] = PlanScoreToJson(*summary.score);
  WriteFileAtomic(out_dir / "summary.json", js.dump(2) + "\n");
  return result;
}

}  // namespace asbuilt
