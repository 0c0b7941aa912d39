#ifndef ASBUILT_PIPELINE_SURVEY_H_
#define ASBUILT_PIPELINE_SURVEY_H_

// `asbuilt survey`: a capture in, a dimensioned floor plan and a report
// out. Stereo captures: segment both views → (rectify) → disparity →
// corners, edges and dense points → world points → plan → drawings →
// report, and a score when a truth plan is given or lies beside the capture
// (docs/survey.md "Structure": the stages, each image decoded once).
// Mono and panorama captures (formats/capture.h): a panorama is first
// resampled into level perspective views turning in place at its centre
// (`panorama_views`); each view is segmented and its walls' floor and
// ceiling label edges (contacts) place them from the camera height — the
// cue that needs no second view (docs/survey.md "Survey from a 360° photo").
//
// A synthetic capture's per-frame `labels`/`depth` and its truth.json are
// ground truth for scoring only: they are read as input only when asked
// (labels_dir, use_capture_labels), so a score measures what a user with a
// real camera would get.

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/pano/level.h"
#include "asbuilt/pano/pano_layout.h"
#include "asbuilt/pano/perspective.h"
#include "asbuilt/plan/reconstruct.h"
#include "asbuilt/plan/room_iou.h"
#include "asbuilt/plan/score.h"
#include "asbuilt/plan/verdict.h"
#include "asbuilt/stereo/capture_points.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

struct SurveyOptions {
  // Segmentation model; empty: DefaultModelPath().
  std::filesystem::path model_path;
  // Scale the segmenter sees (width, height; aspect kept). Unset: the
  // capture's own image size, up to twice the model's training scale (it
  // trained on views resized 0.5–2×) — on asbuilt's 640×480 rooms the
  // shipped model finds 80 of 80 walls and 37 of 38 openings at 640×480,
  // 78 and 33 at its 320×240 training scale (bench/RESULTS.md). {0, 0}: the
  // training scale.
  std::optional<std::pair<int, int>> segment_scale_px;
  // Panorama and mono captures: segment views taller than 100° through three
  // turned square views (SegmenterLabels; docs/seg.md "Real-photo weights").
  // Off: on the three annotated CC0 rooms it helped one room and hurt two.
  bool segment_wide_views = false;
  // Use these label images (NNN.png per frame index; right view labels in
  // DIR/right/ when present) instead of segmenting.
  std::optional<std::filesystem::path> labels_dir;
  // Those labels are exact (a renderer's label pass, `pano views
  // --labels-pano`): snapping and ± as for a capture's own exact labels.
  bool labels_exact = false;
  // Use the capture's own per-frame `labels` (exact labels of a synthetic
  // capture) instead of segmenting: the upper bound of the method.
  bool use_capture_labels = false;
  // Whether the labels are exact: the capture's own, or given and said to be.
  bool ExactLabels() const { return use_capture_labels || (labels_dir && labels_exact); }
  // Truth plan to score against; empty: truth.json beside capture.json when
  // it exists.
  std::optional<std::filesystem::path> truth_path;
  FramePointsOptions points;
  PlanOptions plan;
  VerdictOptions verdict;
  // Panorama captures: the level views it is resampled into,
  // TurnInPlaceViews(panorama_views); frame i is view i (its labels:
  // DIR/NNN.png with --labels DIR), at world yaw panorama yaw + view yaw. Wide and tall, so one
  // view sees a wall's base and its ceiling edge at once: 90° across, ±63°
  // up and down — a floor edge from 0.72 m and a ceiling edge 0.9 m above
  // the camera from 0.45 m away (640×480 at fx 400 sees ±31°: no floor edge
  // nearer than 2.4 m at a 1.435 m camera height, most of a small room).
  TurnInPlaceOptions panorama_views = {.width_px = 512, .height_px = 1024, .fx = 256.0};
  // Panorama captures labelled by the segmenter: redraw its labels on the
  // room's layout, found from the panorama's own edges with the labels as a
  // guide (pano/pano_layout.h, docs/survey.md "The layout of a panorama").
  // Off by default: on the 13 ZInD rooms it finds more walls (wall recall
  // 62 % against 50 %) but the room IoU median moves only 0.725 → 0.763, the
  // mean 0.60 → 0.59, and some rooms get worse (bench/results/pano_survey.md); ZInD is a test set,
  // so its defaults are not tuned further on it. Label images given with
  // labels_dir are used as they are either way.
  bool pano_layout = false;
  PanoLayoutOptions layout;
  // Panorama and mono captures read by the segmenter: estimate the photo's
  // (or the turning rig's) tilt from its own lines and resample it level
  // first (pano/level.h) when it leans at least min_level_tilt_deg. Label
  // images given (labels_dir) belong to the images as they are, so they are
  // then left as they are.
  bool level_panorama = true;
  double min_level_tilt_deg = 0.1;
  LevelOptions level;
  // Per-wall cues: a wall seen (points within 0.1 m of it) along less than
  // this fraction of its length is reported as partly unseen.
  double min_seen_fraction = 0.5;
  bool write_report = true;
  // Frames shown in the report (thumbnails, overlays, disparity); the rest
  // are summarised in the table. 0 = all.
  int report_frames = 12;

  void Check() const;
};

struct StageTiming {
  std::string stage;
  double seconds = 0.0;
};

struct SurveySummary {
  std::string labels_source;  // "segmenter models/…", "labels DIR", "capture labels".
  int frames = 0;
  int points = 0;
  std::vector<FrameCues> frame_cues;
  std::string capture_kind = "stereo";  // CaptureKindName().
  // Which cue placed the walls, and why (CapturePoints::Result::decision).
  std::string wall_cue;
  // Per plan wall: the points that placed it, by cue, and how much of its
  // length they cover ("wall 2, 3.41 m: floor contacts 210, ceiling
  // contacts 180; seen along 96 %"; "… inferred: no point of it was seen").
  std::vector<std::string> wall_cues;
  // Walls seen along less than SurveyOptions::min_seen_fraction of their
  // length, or inferred: the room is larger than the capture saw there.
  int walls_unseen = 0;
  // From the wall–ceiling/floor contacts (NaN: not measured).
  double ceiling_height_m = NAN;
  double ceiling_height_sigma_m = NAN;
  // A panorama's tilt as estimated from its lines (unset: not estimated),
  // and whether the survey resampled it level.
  std::optional<PanoTilt> panorama_tilt;
  bool panorama_levelled = false;
  PlanSummary plan;
  // Can the plan be used as it is, and where to look (plan/verdict.h).
  PlanVerdict verdict;
  std::optional<PlanScore> score;
  std::optional<RoomOverlap> room_overlap;  // With a truth: the rooms' 2D IoU.
  std::vector<StageTiming> stages;
  double seconds = 0.0;
  std::filesystem::path out_dir;
  std::vector<std::string> notes;  // What could not be measured, and why.

  // "12 frames, 41000 points → 4 walls, 3 openings, 16.18 m²; walls 4/4,
  // length err median 0.8 % max 1.9 %; 9.1 s → out/report.html".
  std::string BriefReport() const;
};

struct SurveyResult {
  Plan plan;
  SurveySummary summary;
};

// Runs the whole survey (any capture kind) and writes into `out_dir`: plan.json, plan.svg,
// plan.dxf, plan.pdf, plan.png, plan.ifc, points.txt, points.ply, score.json (with a
// truth), summary.json, report.html, and what `asbuilt review` re-fits from
// (review/input.json, review/points.bin; pipeline/review_input.h). Every
// file is written atomically.
// Throws InputError for bad captures, images or models (naming the file);
// nothing is written then.
SurveyResult RunSurvey(const std::filesystem::path& capture_json, const std::filesystem::path& out_dir,
                       const SurveyOptions& options = {}, const ProgressCallback& progress = {});

// The segmentation models shipped in models/, by name; the first is the default.
struct ShippedModel {
  const char* name;
  const char* file;
  const char* what;
};
inline constexpr ShippedModel kShippedModels[] = {
    {"renders", "segformer_b0_asbuilt.pt", "SegFormer-B0 trained on asbuilt's renders only"},
    {"real", "deeplabv3_mnv2_asbuilt_real.pt",
     "DeepLabV3-MobileNetV2 from MLCommons' ADE20K weights, fine-tuned by asbuilt on renders and CC0 photos of "
     "real rooms: for photos of real rooms (models/MODEL_CARD.md)"},
};

// The default segmentation model: $ASBUILT_MODEL if set, else the first of
// <exe>/../models/, <exe>/../share/asbuilt/models/ and the source tree's
// models/ that holds kShippedModels[0].
std::filesystem::path DefaultModelPath();

// `--model`'s argument: "default" (or empty), a shipped model's name
// ("renders", …), or a path (a checkpoint or a .tflite file) as given.
std::filesystem::path ModelPathFor(const std::string& name_or_path);

// Whether `model` is the shipped renders-only model (the survey then notes,
// for a panorama, that `--model real` reads real photos better).
bool IsRendersOnlyModel(const std::filesystem::path& model);

}  // namespace asbuilt

#endif  // ASBUILT_PIPELINE_SURVEY_H_
