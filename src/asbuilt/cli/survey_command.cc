// `asbuilt survey capture.json -o out/` — the main job: a stereo, mono or
// panorama capture in, a dimensioned floor plan and a report out
// (pipeline/survey.h).

#include <string>
#include <utility>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/cli/field_flags.h"
#include "asbuilt/formats/home_file.h"
#include "asbuilt/pipeline/home_survey.h"
#include "asbuilt/pipeline/survey.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {
namespace {

// Every PlanOptions field as --plan.NAME and every FramePointsOptions field
// as --points.NAME (nested: --points.disparity.block-size-px).
const FieldList<SurveyOptions>& SurveyPlanFields() {
  static const FieldList<SurveyOptions> kList =
      FieldList<SurveyOptions>().Nest("plan", &SurveyOptions::plan, PlanOptionFields());
  return kList;
}
const FieldList<SurveyOptions>& SurveyPointsFields() {
  static const FieldList<SurveyOptions> kList =
      FieldList<SurveyOptions>().Nest("points", &SurveyOptions::points, FramePointsOptionFields());
  return kList;
}

// The panorama's level views as --pano.NAME (TurnInPlaceOptionFields).
const FieldList<SurveyOptions>& SurveyPanoViewFields() {
  static const FieldList<SurveyOptions> kList =
      FieldList<SurveyOptions>().Nest("pano", &SurveyOptions::panorama_views, TurnInPlaceOptionFields());
  return kList;
}

const FieldList<SurveyOptions>& SurveyLayoutFields() {
  static const FieldList<SurveyOptions> kList =
      FieldList<SurveyOptions>().Nest("layout", &SurveyOptions::layout, PanoLayoutOptionFields());
  return kList;
}

// A home.json: every room surveyed with `options`, placed, one plan.
int RunHomeSurveyCommand(const std::string& home_json, const std::string& out_dir, const SurveyOptions& options,
                         int jobs) {
  HomeSurveyOptions home;
  home.survey = options;
  home.jobs = jobs;
  fmt::print(stderr, "surveying the rooms of {}\n", home_json);
  const HomeSurveyResult result =
      RunHomeSurvey(home_json, out_dir, home, [](const std::string& line) { fmt::print(stderr, "  {}\n", line); });
  fmt::print("{}\n", result.placement.best.ToString(result.inputs));
  fmt::print("{} → {}/report.html\n", result.BriefReport(), out_dir);
  if (result.plan.verdict) {
    fmt::print("verdict: {}\n", result.plan.verdict->verdict);
    for (const std::string& why : result.plan.verdict->reasons) fmt::print("  {}\n", why);
  }
  return 0;
}

}  // namespace

int RunSurveyCommand(int argc, char** argv) {
  CLI::App app(
      "Survey a room: segment both views of every stereo frame, match and triangulate wall, door\n"
      "and window points, fit the floor plan and write plan.json/.svg/.dxf/.pdf/.png/.ifc, points.txt,\n"
      "points.ply and report.html. A capture with `rectified: false` is rectified first with its\n"
      "calibration. Scores against --truth, or truth.json beside the capture when present.\n"
      "A synthetic capture's own labels are never used unless --labels or --capture-labels says so.\n"
      "A mono capture (level views of one camera) or a panorama capture (one 2:1 equirectangular\n"
      "photo, resampled into --pano-views level views) places the walls from their floor and\n"
      "ceiling edges and the camera height in position_m (docs/survey.md).\n"
      "A home.json (kind \"home\": one capture per room) surveys every room into OUT/rooms/NAME/, places\n"
      "the rooms from the doors they share and writes one plan of the home (docs/home.md).\n"
      "Every PlanOptions field is a flag --plan.NAME, every FramePointsOptions field --points.NAME.",
      "asbuilt survey");
  AddCommonFlags(app);
  std::string capture, out_dir, model, labels_dir, truth;
  SurveyOptions options;
  bool no_report = false;
  app.add_option("capture", capture, "capture.json, or home.json for a whole home")->required();
  int jobs = 0;
  app.add_option("--jobs", jobs, "home.json: rooms surveyed at once (0: one per two hardware threads)")
      ->capture_default_str();
  app.add_option("-o,--out", out_dir, "output folder")->required();
  app.add_option("--model", model,
                 "segmentation model: a shipped model's name (default, renders, real), a checkpoint or a .tflite file");
  std::string seg_scale = "auto";
  app.add_option("--seg-scale", seg_scale,
                 "scale the segmenter sees: auto (the images' own size, up to twice the model's training "
                 "scale), model (its training scale) or WxH")
      ->capture_default_str();
  app.add_option("--labels", labels_dir, "use these label images (NNN.png per frame) instead of segmenting");
  app.add_flag("--labels-exact", options.labels_exact,
               "the --labels images are exact (a renderer's label pass): snapping and ± as for --capture-labels");
  app.add_flag("--capture-labels", options.use_capture_labels,
               "use the capture's own exact labels (synthetic captures; the method's upper bound)");
  app.add_option("--truth", truth, "truth plan to score against (default: truth.json beside the capture)");
  app.add_option("--report-frames", options.report_frames, "frames pictured in the report (0 = all)")
      ->capture_default_str();
  app.add_flag("--no-report", no_report, "skip report.html");
  app.add_flag("--pano-layout", options.pano_layout,
               "panorama captures: redraw the segmenter's labels on the room's layout found from the panorama's "
               "edges (writes layout.png; docs/survey.md)");
  app.add_flag("--level,!--no-level", options.level_panorama,
               "panorama and mono captures read by the segmenter: estimate the photo's (or the turning rig's) tilt "
               "from its lines and level it before the survey (default on; docs/survey.md \"Levelling a panorama\")")
      ->capture_default_str();
  app.add_flag("--segment-turned", options.segment_wide_views,
               "panorama captures: segment each tall view through three square views turned 40° up, level and "
               "down (docs/seg.md)");
  // The short spellings are older flags that scripts use.
  FieldFlags plan_flags(app, SurveyPlanFields().Fields(options), {{"plan.epsilon_m", "--epsilon-m"}},
                        "Plan options (PlanOptions, docs/plan.md)");
  FieldFlags points_flags(app, SurveyPointsFields().Fields(options),
                          {{"points.dense_stride_px", "--dense-stride"},
                           {"points.contacts", "--contacts"},
                           {"points.contact_snap_px", "--snap-contacts-px"}},
                          "Points options (FramePointsOptions, docs/stereo.md)");
  FieldFlags pano_flags(
      app, SurveyPanoViewFields().Fields(options),
      {{"pano.fx", "--pano-fx"}, {"pano.views", "--pano-views"}, {"pano.yaw_step_deg", "--pano-yaw-step"}},
      "Panorama captures: the level views it is resampled into (TurnInPlaceOptions, docs/survey.md)");
  pano_flags.AddSize("pano.width_px", "pano.height_px", "--pano-size", "view size");
  FieldFlags layout_flags(app, SurveyLayoutFields().Fields(options), {},
                          "Panorama layout options (PanoLayoutOptions, docs/survey.md)");
  Parse(app, argc, argv);
  pano_flags.ReadGiven(SurveyPanoViewFields(), options);
  layout_flags.Read(SurveyLayoutFields(), options);
  plan_flags.Read(SurveyPlanFields(), options);
  points_flags.Read(SurveyPointsFields(), options);
  if (!model.empty()) options.model_path = ModelPathFor(model);
  if (seg_scale == "model") {
    options.segment_scale_px = std::pair{0, 0};
  } else if (seg_scale != "auto") {
    int w = 0, h = 0;
    ParseSizeFlag(seg_scale, "--seg-scale", w, h);
    options.segment_scale_px = std::pair{w, h};
  }
  if (!labels_dir.empty()) options.labels_dir = labels_dir;
  if (!truth.empty()) options.truth_path = truth;
  options.write_report = !no_report;
  options.Check();

  if (IsHomeFile(capture)) return RunHomeSurveyCommand(capture, out_dir, options, jobs);

  ProgressPrinter printer;
  SurveyResult result = RunSurvey(capture, out_dir, options, printer.Callback());
  printer.Finish();
  for (const StageTiming& s : result.summary.stages) {
    fmt::print(stderr, "  {:<18} {:7.2f} s\n", s.stage, s.seconds);
  }
  for (const std::string& n : result.summary.notes) fmt::print(stderr, "note: {}\n", n);
  if (result.summary.score) fmt::print("{}", result.summary.score->Table());
  fmt::print("{}\n", result.summary.BriefReport());
  fmt::print("verdict: {}\n", result.summary.verdict.BriefReport());
  for (std::size_t w = 0; w < result.summary.verdict.walls.size(); ++w) {
    const WallVerdict& v = result.summary.verdict.walls[w];
    if (v.verdict == Verdict::kGood) continue;
    fmt::print("  wall {}: {} — {}\n", w, VerdictName(v.verdict), v.Why());
  }
  return 0;
}

}  // namespace asbuilt::cli
