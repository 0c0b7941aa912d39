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

#include "asbuilt/formats/points_ply.h"
#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/pano/pano_views.h"
#include "asbuilt/pipeline/pano_layout_labels.h"
#include "asbuilt/pipeline/points_plot.h"
#include "asbuilt/pipeline/report.h"
#include "asbuilt/pipeline/review_input.h"
#include "asbuilt/pipeline/segmenter_labels.h"
#include "asbuilt/plan/drawing.h"
#include "asbuilt/plan/fit_plan.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

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
  plan.Check();
  CheckArgument(report_frames >= 0, fmt::format("SurveyOptions.report_frames = {}, must be >= 0", report_frames));
  panorama_views.Check();
  layout.Check();
  level.Check();
  CheckArgument(min_level_tilt_deg >= 0,
                fmt::format("SurveyOptions.min_level_tilt_deg = {}, must be >= 0", min_level_tilt_deg));
  verdict.Check();
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
  CheckArgument(!labels_exact || labels_dir,
                "SurveyOptions.labels_exact: says the labels_dir labels are exact; give labels_dir");
}

namespace {
// A file in models/: $ASBUILT_MODEL_DIR, else the first of <exe>/../models/,
// <exe>/../share/asbuilt/models/ and the source tree's models/ that holds it.
fs::path ShippedFile(const std::string& name) {
  fs::path exe_dir = ExecutableDir();
  std::vector<fs::path> candidates = {exe_dir / ".." / "models" / name,
                                      exe_dir / ".." / "share" / "asbuilt" / "models" / name,
                                      fs::path(ASBUILT_SOURCE_DIR) / "models" / name};
  for (const fs::path& c : candidates) {
    std::error_code ec;
    if (fs::is_regular_file(c, ec)) return fs::weakly_canonical(c, ec);
  }
  return candidates.back();
}
}  // namespace

fs::path DefaultModelPath() {
  if (const char* env = std::getenv("ASBUILT_MODEL"); env != nullptr && *env != '\0') return env;
  return ShippedFile(kShippedModels[0].file);
}

bool IsRendersOnlyModel(const fs::path& model) {
  std::error_code ec;
  return fs::equivalent(model, ModelPathFor("renders"), ec);
}

fs::path ModelPathFor(const std::string& name_or_path) {
  if (name_or_path.empty() || name_or_path == "default") return DefaultModelPath();
  for (const ShippedModel& m : kShippedModels) {
    if (name_or_path == m.name) return ShippedFile(m.file);
  }
  return name_or_path;
}

std::string SurveySummary::BriefReport() const {
  std::string out =
      fmt::format("{} frames, {} points → {} walls, {} openings", frames, points, plan.walls, plan.openings);
  if (plan.area_m2 > 0) out += fmt::format(", {:.2f} m²", plan.area_m2);
  if (score) {
    out += fmt::format("; walls {}/{}", score->walls.matched, score->walls.truth);
    if (auto m = score->wall_length.Median()) {
      out += fmt::format(", length err median {:.1f} % max {:.1f} %", 100 * *m,
                         100 * score->wall_length.Max().value_or(0));
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

// Stage timings, summed per stage in the order the stages first ran.
class StageTimes {
 public:
  void Add(const std::string& stage, double seconds) {
    if (!seconds_.count(stage)) order_.push_back(stage);
    seconds_[stage] += seconds;
  }
  std::vector<StageTiming> Timings() const {
    std::vector<StageTiming> out;
    for (const std::string& s : order_) out.push_back({s, seconds_.at(s)});
    return out;
  }

 private:
  std::map<std::string, double> seconds_;
  std::vector<std::string> order_;
};

// One survey as it passes through the stages of RunSurvey.
struct Survey {
  const fs::path& capture_json;
  const fs::path& out_dir;
  const SurveyOptions& options;
  Clock::time_point start = Clock::now();
  StageTimes times;
  Capture capture;
  std::optional<MonoViews> views;  // A panorama's level views, or a mono capture's levelled ones.
  cv::Mat equirect;                // With pano_layout: the panorama (8-bit BGR) and its views.
  std::vector<PanoView> pano_views;
  std::pair<int, int> pano_size_px{0, 0};  // The panorama's width and height.
  std::string levelled_jpeg;               // The panorama as surveyed, when it was levelled (review/panorama.jpg).
  cv::Mat layout_picture;                  // The panorama with its layout drawn (PanoLayoutLabels).
  std::string layout_brief;                // PanoLayout::BriefReport().
  std::optional<Plan> truth;
  std::unique_ptr<LabelSource> labels;
  std::vector<ClassPoint> points;
  VerdictContext verdict_context;  // What the verdict reads beyond the points.
  PlanInput plan_input;            // What the plan was fitted from (review/ re-fits it).
  struct LabelPng {
    int frame, width_px, height_px;
    std::string png;
  };
  std::vector<LabelPng> label_pngs;  // Each frame's labels, PNG-encoded, for review/labels/.
  std::vector<Vec2> rigs;
  double coverage_deg = 360.0;  // Of the turn around the camera.
  std::vector<ReportFrame> report_frames;
  std::string plan_svg;  // The drawing, for the report (empty: no walls).
  SurveyResult result;

  SurveySummary& summary() { return result.summary; }
  const std::vector<CaptureFrame>& frames() const { return views ? views->frames : capture.frames; }
};

// Report pictures and per-stage timing as the frame loop passes.
class SurveyFrameObserver final : public FrameObserver {
 public:
  explicit SurveyFrameObserver(Survey& survey) : survey_(survey) {}

  void OnStage(const std::string& stage, double seconds) override { survey_.times.Add(stage, seconds); }

  void OnFrame(const CaptureFrame& frame, const cv::Mat& image, const cv::Mat& labels,
               const FramePointsResult& result) override {
    const bool stereo = survey_.capture.kind == CaptureKind::kStereo;
    if (result.cues.CarriedBy() == "none") {
      survey_.summary().notes.push_back(
          stereo ? fmt::format("frame {}: no points (no labelled structure with stereo evidence)", frame.index)
                 : fmt::format("view {}: no floor or ceiling contact of a wall", frame.index));
    }
    if (!labels.empty()) {  // Kept for asbuilt review; written with the other outputs.
      std::vector<uchar> png;
      cv::imencode(".png", labels, png);
      survey_.label_pngs.push_back({frame.index, labels.cols, labels.rows, std::string(png.begin(), png.end())});
    }
    const int wanted = survey_.options.report_frames;
    if (wanted != 0 && static_cast<int>(survey_.report_frames.size()) >= wanted) return;
    const auto t = Clock::now();
    ReportFrame rf{.index = frame.index, .yaw_deg = frame.yaw_deg};
    rf.left_jpeg = EncodeJpeg(image);
    cv::Mat bgr = image;
    if (bgr.channels() == 1) cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
    if (labels.size() == bgr.size()) rf.overlay_jpeg = EncodeJpeg(LabelOverlay(bgr, labels));
    if (stereo && !result.disparity.disparity_px.empty()) {
      rf.disparity_jpeg = EncodeJpeg(ColorizeDisparity(result.disparity.disparity_px));
    }
    survey_.report_frames.push_back(std::move(rf));
    survey_.times.Add("report pictures", Since(t));
  }

 private:
  Survey& survey_;
};

// A panorama read by the segmenter: its tilt from its own lines, and the
// panorama resampled level when it leans enough to matter.
void LevelStage(Survey& s, Image& equirect) {
  const SurveyOptions& o = s.options;
  if (!o.level_panorama || o.labels_dir || o.use_capture_labels) return;
  const auto t = Clock::now();
  SurveySummary& summary = s.summary();
  summary.panorama_tilt = EstimatePanoTilt(equirect, o.level);
  const PanoTilt& tilt = *summary.panorama_tilt;
  if (tilt.found && tilt.tilt_deg >= o.min_level_tilt_deg) {
    equirect = LevelPanorama(equirect, tilt);
    summary.panorama_levelled = true;
    s.levelled_jpeg = EncodeJpeg(AsMat(equirect), equirect.width());
    summary.notes.push_back(
        fmt::format("the panorama was levelled before the survey: {}", tilt.BriefReport(equirect.width())));
  } else if (!tilt.found) {
    summary.notes.push_back(
        fmt::format("the panorama's tilt could not be estimated ({}): surveyed as level", tilt.BriefReport()));
  }
  spdlog::info("survey: panorama {}", tilt.BriefReport(equirect.width()));
  s.times.Add("level", Since(t));
}

// A mono capture read by the segmenter: its turning rig's tilt from the
// lines of all its views, and each view resampled level (kept in memory, as
// a panorama's are) when the rig leans enough to matter.
void LevelMonoStage(Survey& s) {
  const SurveyOptions& o = s.options;
  if (!o.level_panorama || o.labels_dir || o.use_capture_labels) return;
  for (const CaptureFrame& f : s.capture.frames) {
    if (f.pitch_deg != 0) return;  // Refused by the frame loop, which says why.
  }
  const auto t = Clock::now();
  SurveySummary& summary = s.summary();
  const PinholeCamera camera = s.capture.camera.Pinhole();
  std::vector<Image> images;
  std::vector<PanoView> geometry;
  for (std::size_t i = 0; i < s.capture.frames.size(); ++i) {
    const CaptureFrame& f = s.capture.frames[i];
    images.push_back(AsImage(ReadColourImage(s.capture.Resolve(f.left), fmt::format("frames[{}].image", i))));
    geometry.push_back({.camera = camera, .yaw_deg = f.yaw_deg});
  }
  summary.panorama_tilt = EstimateViewsTilt(images, geometry, o.level);
  const PanoTilt& tilt = *summary.panorama_tilt;
  if (tilt.found && tilt.tilt_deg >= o.min_level_tilt_deg) {
    s.views = MonoViews{.kind = summary.capture_kind, .camera = camera, .frames = s.capture.frames};
    for (std::size_t i = 0; i < images.size(); ++i) {
      s.views->images.push_back(AsMat(LevelView(images[i], geometry[i], tilt)));
    }
    summary.panorama_levelled = true;
    summary.notes.push_back(fmt::format("the views were levelled before the survey: the rig {}", tilt.BriefReport()));
  } else if (!tilt.found) {
    summary.notes.push_back(
        fmt::format("the views' tilt could not be estimated ({}): surveyed as level", tilt.BriefReport()));
  }
  spdlog::info("survey: mono rig {}", tilt.BriefReport());
  s.times.Add("level", Since(t));
}

// capture.json, the truth plan, and a panorama's level views (in memory).
void ReadCaptureStage(Survey& s) {
  const auto t = Clock::now();
  s.capture = ReadCapture(s.capture_json);
  s.summary().capture_kind = CaptureKindName(s.capture.kind);
  s.truth = ReadTruth(s.options, s.capture_json);
  if (s.capture.kind == CaptureKind::kPanorama) {
    const CapturePanorama& pano = *s.capture.panorama;
    Image equirect = ReadEquirect(s.capture.Resolve(pano.image));
    s.pano_size_px = {equirect.width(), equirect.height()};
    LevelStage(s, equirect);
    const std::vector<PanoView> views = TurnInPlaceViews(s.options.panorama_views);
    if (s.options.pano_layout && !s.options.labels_dir && !s.options.use_capture_labels) {
      s.equirect = AsMat(equirect).clone();  // Only the layout reads it again.
      s.pano_views = views;
    }
    s.views = MonoViews{.kind = s.summary().capture_kind, .camera = views.front().camera};
    for (std::size_t i = 0; i < views.size(); ++i) {
      s.views->frames.push_back({.index = static_cast<int>(i),
                                 .left = fmt::format("{}#view{:03d}", pano.image, i),
                                 .yaw_deg = pano.yaw_deg + views[i].yaw_deg,
                                 .position_m = pano.position_m});
      s.views->images.push_back(AsMat(RenderPanoView(equirect, views[i])));
    }
  } else if (s.capture.kind == CaptureKind::kMono) {
    LevelMonoStage(s);
  }
  s.summary().frames = static_cast<int>(s.frames().size());
  s.times.Add("read capture", Since(t));
}

// Given label images, the capture's own, or the segmenter.
void LabelSourceStage(Survey& s) {
  const SurveyOptions& options = s.options;
  if (options.labels_dir) {
    s.labels = std::make_unique<DirectoryLabels>(*options.labels_dir);
  } else if (options.use_capture_labels) {
    if (s.views)
      throw InvalidArgument("a panorama capture has no labels of its own: give --labels DIR (NNN.png per view)");
    s.labels = std::make_unique<CaptureLabels>(s.capture);
  } else {
    const auto t = Clock::now();
    const cv::Size image = s.views ? cv::Size(s.views->camera.width_px, s.views->camera.height_px)
                                   : cv::Size(s.capture.camera.width, s.capture.camera.height);
    std::optional<PinholeCamera> wide;
    if (options.segment_wide_views && (s.views || s.capture.kind == CaptureKind::kMono)) {
      wide = s.views ? s.views->camera : s.capture.camera.Pinhole();
    }
    const fs::path model = options.model_path.empty() ? DefaultModelPath() : options.model_path;
    s.labels = std::make_unique<SegmenterLabels>(model, options.segment_scale_px, image, wide);
    s.times.Add("load model", Since(t));
    if (s.views && IsRendersOnlyModel(model)) {
      s.summary().notes.push_back(
          "the segmentation model has seen rendered rooms only; for a photo of a real room `--model real` reads it "
          "far better (models/MODEL_CARD.md)");
    }
    if (s.capture.panorama && options.pano_layout) {
      auto layout = std::make_unique<PanoLayoutLabels>(std::move(s.labels), s.equirect, s.pano_views, s.views->images,
                                                       s.capture.panorama->position_m.z(), options.layout);
      s.times.Add("segment + layout", layout->seconds());
      s.layout_picture = layout->picture();
      s.layout_brief = layout->layout().BriefReport();
      s.summary().notes.push_back(fmt::format("panorama {}", s.layout_brief));
      s.labels = std::move(layout);
    }
  }
  s.summary().labels_source = s.labels->Describe();
}

// Every frame's points (the one frame loop), the wall cue and the ceiling.
void PointsStage(Survey& s, const ProgressCallback& progress) {
  FramePointsOptions options = s.options.points;
  options.ResolveSnaps(s.options.ExactLabels());
  SurveyFrameObserver observer(s);
  CapturePointsResult gathered = s.views ? ComputeCapturePoints(*s.views, *s.labels, options, &observer, progress)
                                         : ComputeCapturePoints(s.capture, *s.labels, options, &observer, progress);
  SurveySummary& summary = s.summary();
  for (const CaptureFrame& f : s.frames()) s.rigs.push_back(f.position_m.head<2>());
  s.coverage_deg = YawCoverageDeg(s.frames(), gathered.camera);
  s.points = std::move(gathered.points);
  summary.points = static_cast<int>(s.points.size());
  summary.wall_cue = gathered.wall_cue;
  if (!summary.wall_cue.empty()) spdlog::info("survey: {}", summary.wall_cue);
  summary.frame_cues = std::move(gathered.frames);
  for (std::size_t i = 0; i < s.report_frames.size(); ++i)
    s.report_frames[i].cues = summary.frame_cues[i].BriefReport();
  if (!gathered.contacts_used) return;
  const ResolvedContacts& contacts = gathered.contacts;
  s.verdict_context.ceiling_samples = contacts.ceiling_samples;
  spdlog::info("survey: ceiling height {} ({}); {} floor contact(s) rejected as tops of things before a wall{}",
               contacts.ceiling
                   ? fmt::format("{:.3f} ± {:.3f} m", contacts.ceiling->height_m, contacts.ceiling->sigma_m)
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
    summary.notes.push_back(fmt::format("the ceiling's height could not be measured: {} wall–ceiling contacts unused",
                                        contacts.ceiling_unused));
  }
}

// Which cue placed each wall, and where the room is larger than the capture
// saw (a wall seen along little of its length, or inferred).
void DescribeWallEvidence(Survey& s) {
  SurveySummary& summary = s.summary();
  const Plan& plan = s.result.plan;
  const std::vector<WallEvidence> evidence = EvidencePerWall(plan, s.points);
  std::vector<std::string> unseen;
  for (std::size_t w = 0; w < evidence.size(); ++w) {
    const WallEvidence& e = evidence[w];
    const double length = (plan.walls[w].end - plan.walls[w].start).norm();
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
    if (e.seen_fraction < s.options.min_seen_fraction) {
      ++summary.walls_unseen;
      unseen.push_back(fmt::format("wall {} ({:.2f} m, seen along {:.0f} %)", w, length, 100 * e.seen_fraction));
    }
  }
  if (unseen.empty()) return;
  std::string list;
  for (std::size_t k = 0; k < unseen.size(); ++k) list += (k ? ", " : "") + unseen[k];
  summary.notes.push_back(fmt::format(
      "the room is larger than what this capture sees: {} {} mostly or wholly unseen, so {} length{} and "
      "the room's area rest on walls inferred across what was not seen — survey from another spot to measure them",
      list, unseen.size() == 1 ? "is" : "are", unseen.size() == 1 ? "its" : "their", unseen.size() == 1 ? "" : "s"));
}

// What the plan stage needs to know of this survey (plan/fit_plan.h decides
// the plan settings from it): the points, where each frame's camera stood,
// the capture's kind, the labels' origin and the ceiling.
PlanInput SurveyPlanInput(const Survey& s) {
  PlanInput input{.points = s.points,
                  .source = s.capture_json.string(),
                  .one_camera = s.capture.kind != CaptureKind::kStereo,
                  .exact_labels = s.options.ExactLabels(),
                  .ceiling_height_m = s.result.summary.ceiling_height_m,
                  .ceiling_height_sigma_m = s.result.summary.ceiling_height_sigma_m,
                  .camera_height_sigma_m = s.options.points.camera_height_sigma_m};
  const bool stereo = s.capture.kind == CaptureKind::kStereo;
  for (const CaptureFrame& f : s.frames()) {
    const RigPose pose{.position_m = f.position_m, .yaw_rad = DegToRad(f.yaw_deg)};
    input.frames.push_back(
        {.index = f.index,
         .position_m = f.position_m,
         .camera_m = stereo ? EyeCentre(pose, s.capture.camera.baseline_m, StereoEye::kLeft) : f.position_m});
  }
  return input;
}

// The plan from the points, and what it rests on.
void PlanStage(Survey& s) {
  const auto t = Clock::now();
  SurveySummary& summary = s.summary();
  Plan& plan = s.result.plan;
  s.plan_input = SurveyPlanInput(s);
  if (s.labels) s.verdict_context.label_confidence = s.labels->MeanConfidence();
  try {
    PlanResult reconstructed = FitPlan(s.plan_input, s.options.plan);
    if (summary.panorama_tilt && summary.panorama_tilt->found) {
      s.verdict_context.photo_tilt_deg = summary.panorama_tilt->tilt_deg;
      s.verdict_context.photo_tilt_sigma_deg = summary.panorama_tilt->sigma_deg;
    }
    summary.verdict = JudgePlan(s.plan_input, reconstructed, s.options.verdict, s.verdict_context);
    plan = std::move(reconstructed.plan);
    MarkPlan(summary.verdict, plan);
    summary.plan = reconstructed.summary;
    if (!reconstructed.summary.closed && !plan.walls.empty()) {
      summary.notes.push_back("the walls found do not close into a room: the area is not measured");
    }
  } catch (const InputError& e) {
    summary.notes.push_back(fmt::format("no plan: {}", e.what()));
  } catch (const InvalidArgument& e) {
    summary.notes.push_back(fmt::format("no plan: {}", e.what()));
  }
  if (plan.walls.empty()) {
    summary.notes.push_back("no walls could be measured from this capture");
    summary.verdict = JudgePlan(s.plan_input, {}, s.options.verdict, s.verdict_context);
    MarkPlan(summary.verdict, plan);  // An empty plan.json says why it is empty.
  }
  // Views that do not go round the room cannot close it (a real capture of
  // one direction, e.g. EuRoC): say what the closed polygon rests on.
  if (s.coverage_deg < 359.5 && !plan.walls.empty()) {
    std::string note = fmt::format(
        "the views cover {:.0f}° of the turn around the rig: walls outside them are not measured", s.coverage_deg);
    if (summary.plan.closed) {
      note += fmt::format(
          "; the room polygon closes through {} inferred wall(s), so its area ({:.2f} m²) is not a measurement",
          summary.plan.inferred_walls, summary.plan.area_m2);
    }
    summary.notes.push_back(note);
  }
  DescribeWallEvidence(s);
  s.times.Add("plan", Since(t));
}

void ScoreStage(Survey& s) {
  if (!s.truth) return;
  s.summary().score = ScorePlan(s.result.plan, *s.truth);
  s.summary().room_overlap = RoomPolygonOverlap(s.result.plan, *s.truth);
}

// What `asbuilt review` needs to re-fit this survey's plan (pipeline/review_input.h).
ReviewInput SurveyReviewInput(const Survey& s) {
  ReviewInput in{.kind = s.result.summary.capture_kind,
                 .capture_json = s.capture_json,
                 .plan_input = s.plan_input,
                 .plan_options = s.options.plan,
                 .labels_source = s.result.summary.labels_source};
  // Each frame's labels (the segmenter's, or those given) beside the cameras they belong to.
  const PinholeCamera frame_camera = s.views ? s.views->camera : s.capture.camera.Pinhole();
  for (const Survey::LabelPng& l : s.label_pngs) {
    const fs::path file = s.out_dir / "review" / "labels" / fmt::format("{:03d}.png", l.frame);
    fs::create_directories(file.parent_path());
    WriteFileAtomic(file, l.png);
    const auto frame =
        std::find_if(s.frames().begin(), s.frames().end(), [&](const CaptureFrame& f) { return f.index == l.frame; });
    const auto planned = std::find_if(s.plan_input.frames.begin(), s.plan_input.frames.end(),
                                      [&](const PlanFrame& f) { return f.index == l.frame; });
    if (frame == s.frames().end() || planned == s.plan_input.frames.end()) continue;
    in.labels.push_back({.frame = l.frame,
                         .image = file,
                         .width_px = l.width_px,
                         .height_px = l.height_px,
                         .camera = frame_camera,
                         .yaw_deg = frame->yaw_deg,
                         .camera_m = planned->camera_m});
  }
  if (s.capture.panorama) {
    const CapturePanorama& pano = *s.capture.panorama;
    fs::path image = s.capture.Resolve(pano.image);
    if (!s.levelled_jpeg.empty()) {  // The review draws on the panorama as surveyed.
      image = s.out_dir / "review" / "panorama.jpg";
      fs::create_directories(image.parent_path());
      WriteFileAtomic(image, s.levelled_jpeg);
    }
    in.images.push_back({.frame = -1,
                         .image = image,
                         .width_px = s.pano_size_px.first,
                         .height_px = s.pano_size_px.second,
                         .yaw_deg = pano.yaw_deg,
                         .camera_m = pano.position_m});
    return in;
  }
  const PinholeCamera camera = s.capture.camera.Pinhole();
  for (std::size_t i = 0; i < s.capture.frames.size(); ++i) {
    const CaptureFrame& f = s.capture.frames[i];
    fs::path image = s.capture.Resolve(f.left);
    if (s.views) {  // Levelled: the review draws on the views as surveyed.
      image = s.out_dir / "review" / "views" / fmt::format("{:03d}.jpg", f.index);
      fs::create_directories(image.parent_path());
      WriteFileAtomic(image, EncodeJpeg(s.views->images[i], camera.width_px));
    }
    in.images.push_back({.frame = f.index,
                         .image = image,
                         .width_px = camera.width_px,
                         .height_px = camera.height_px,
                         .camera = camera,
                         .yaw_deg = f.yaw_deg,
                         .camera_m = i < s.plan_input.frames.size() ? s.plan_input.frames[i].camera_m : f.position_m});
  }
  return in;
}

// plan.json and, with walls, its drawings (each once); the points; the score.
void WriteOutputsStage(Survey& s) {
  const auto t = Clock::now();
  const Plan& plan = s.result.plan;
  fs::create_directories(s.out_dir);
  if (plan.walls.empty()) {
    WritePlan(plan, s.out_dir / "plan.json");
  } else {
    WritePlanFiles(plan, s.out_dir);  // .json, .svg, .dxf, .pdf, .png, .ifc
  }
  WritePoints(s.points, s.out_dir / "points.txt");
  if (!s.layout_picture.empty()) WriteImageAtomic(s.out_dir / "layout.png", s.layout_picture);
  WritePointsPly(s.points, s.out_dir / "points.ply");
  if (s.summary().score) {
    WriteFileAtomic(s.out_dir / "score.json", PlanScoreToJson(*s.summary().score).dump(2) + "\n");
  }
  WriteReviewInput(s.out_dir, SurveyReviewInput(s));
  s.times.Add("write outputs", Since(t));
}

// report.html from the survey in memory (its own time is in its table only).
void ReportStage(Survey& s) {
  if (!s.options.write_report) return;
  const auto t = Clock::now();
  const Plan& plan = s.result.plan;
  SurveyReport report{.title = fmt::format("Survey of {}", s.capture_json.filename().string()),
                      .capture_path = s.capture_json,
                      .summary = s.summary(),
                      .plan = plan,
                      .truth = s.truth,
                      .frames = std::move(s.report_frames),
                      .points_plot_png = PointsPlotPng(s.points, plan, s.truth, s.rigs),
                      .layout_jpeg = EncodeJpeg(s.layout_picture, 1600),
                      .layout_caption = s.layout_brief,
                      .plan_svg = plan.walls.empty() ? std::string() : PlanToSvg(plan)};
  report.summary.stages.push_back({"report", Since(t)});
  WriteSurveyReport(report, s.out_dir / "report.html");
}

// The figures behind the verdict, plan-wide and per wall (null: not measured).
nlohmann::json VerdictEvidenceJson(const PlanVerdict& v) {
  auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  nlohmann::json js = {{"agreement", number(v.agreement)},
                       {"coverage", number(v.coverage)},
                       {"floor_ceiling", number(v.floor_ceiling)},
                       {"label_confidence", number(v.label_confidence)},
                       {"short_walls", v.short_walls},
                       {"odd_corners", v.odd_corners},
                       {"walls", nlohmann::json::array()}};
  if (std::isfinite(v.tilt.tilt_deg)) {
    js["tilt_from_edges"] = {{"tilt_deg", v.tilt.tilt_deg},         {"sigma_deg", v.tilt.sigma_deg},
                             {"toward_deg", v.tilt.toward_deg},     {"samples", v.tilt.samples},
                             {"inlier_share", v.tilt.inlier_share}, {"scatter_m", v.tilt.scatter_m}};
  }
  for (const WallVerdict& w : v.walls) {
    js["walls"].push_back({{"verdict", VerdictName(w.verdict)},
                           {"confidence", w.confidence},
                           {"reasons", w.reasons},
                           {"seen", w.evidence.seen},
                           {"agreement", number(w.evidence.agreement)},
                           {"floor_ceiling", number(w.evidence.floor_ceiling)},
                           {"median_error", number(w.evidence.median_error)},
                           {"hidden_floor", w.evidence.hidden_floor},
                           {"offset_sigma_m", number(w.evidence.offset_sigma_m)},
                           {"run_on_m", w.evidence.run_on_m},
                           {"doubtful_reach_m", w.evidence.doubtful_reach_m}});
  }
  return js;
}

void WriteSummaryStage(const SurveySummary& summary, const fs::path& out_dir) {
  nlohmann::json js = {{"brief", summary.BriefReport()},
                       {"capture_kind", summary.capture_kind},
                       {"frames", summary.frames},
                       {"points", summary.points},
                       {"labels_source", summary.labels_source},
                       {"plan", summary.plan.BriefReport()},
                       {"notes", summary.notes},
                       {"seconds", summary.seconds}};
  if (!summary.wall_cue.empty()) js["wall_cue"] = summary.wall_cue;
  js["wall_cues"] = summary.wall_cues;
  js["walls_unseen"] = summary.walls_unseen;
  for (const StageTiming& s : summary.stages) js["stages"][s.stage] = s.seconds;
  if (summary.panorama_tilt) {
    const PanoTilt& t = *summary.panorama_tilt;
    js["panorama_tilt"] = {{"found", t.found},
                           {"tilt_deg", t.tilt_deg},
                           {"toward_yaw_deg", t.toward_yaw_deg},
                           {"sigma_deg", std::isfinite(t.sigma_deg) ? nlohmann::json(t.sigma_deg) : nlohmann::json()},
                           {"lines", t.lines_used},
                           {"levelled", summary.panorama_levelled}};
  }
  if (std::isfinite(summary.ceiling_height_m)) {
    js["ceiling_height_m"] = summary.ceiling_height_m;
    js["ceiling_height_sigma_m"] = summary.ceiling_height_sigma_m;
  }
  js["verdict"] = VerdictName(summary.verdict.verdict);
  js["confidence"] = summary.verdict.confidence;
  js["verdict_reasons"] = summary.verdict.reasons;
  js["verdict_evidence"] = VerdictEvidenceJson(summary.verdict);
  if (summary.score) js["score"] = PlanScoreToJson(*summary.score);
  if (summary.room_overlap) {
    js["room_iou"] = summary.room_overlap->Iou();
    js["room_intersection_m2"] = summary.room_overlap->intersection_m2;
    js["room_union_m2"] = summary.room_overlap->union_m2;
  }
  WriteFileAtomic(out_dir / "summary.json", js.dump(2) + "\n");
}

}  // namespace

SurveyResult RunSurvey(const fs::path& capture_json, const fs::path& out_dir, const SurveyOptions& options,
                       const ProgressCallback& progress) {
  options.Check();
  Survey s{.capture_json = capture_json, .out_dir = out_dir, .options = options};
  s.summary().out_dir = out_dir;
  ReadCaptureStage(s);
  LabelSourceStage(s);
  PointsStage(s, progress);
  PlanStage(s);
  ScoreStage(s);
  WriteOutputsStage(s);
  s.summary().seconds = Since(s.start);
  s.summary().stages = s.times.Timings();
  ReportStage(s);
  WriteSummaryStage(s.summary(), out_dir);
  return std::move(s.result);
}

}  // namespace asbuilt
