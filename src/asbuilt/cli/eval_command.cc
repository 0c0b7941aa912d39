// `asbuilt eval <what> …` — scores results against the truth. Each kind of
// evaluation is one CLI11 subcommand:
//   eval plan PLAN TRUTH [--json FILE]   floor plan vs truth.json (plan/score.h)
//   eval seg --model M (--manifest F | --images D [--labels D])   segmenter (seg/evaluate.h)
//   eval zind --model M --zind TOUR [-o DIR]   segmenter on real photos (pipeline/zind_eval.h)

#include <string>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/formats/plan_file.h"
#include "asbuilt/formats/zind.h"
#include "asbuilt/pipeline/survey.h"
#include "asbuilt/pipeline/zind_eval.h"
#include "asbuilt/plan/score.h"
#include "asbuilt/seg/evaluate.h"
#include "asbuilt/seg/seg_data.h"
#include "asbuilt/util/progress.h"
#include "asbuilt/util/file.h"

namespace asbuilt::cli {

int RunEvalCommand(int argc, char** argv) {
  CLI::App app("Score results against the truth.", "asbuilt eval");
  AddCommonFlags(app);
  app.require_subcommand(1);

  // eval plan
  CLI::App* plan_cmd =
      app.add_subcommand("plan",
                         "score a floor plan against the truth: wall recall/precision and length error, opening\n"
                         "recall/precision per kind and width error, room area error (table on stdout)");
  std::string plan_path, truth_path, plan_json_out;
  ScoreOptions score_options;
  plan_cmd->add_option("plan", plan_path, "predicted plan.json")->required();
  plan_cmd->add_option("truth", truth_path, "truth.json")->required();
  plan_cmd->add_option("--json", plan_json_out, "also write the scores as JSON to FILE");
  plan_cmd->add_option("--wall-max-angle-deg", score_options.wall_max_angle_deg, "max angle between matched walls")
      ->capture_default_str();
  plan_cmd
      ->add_option("--wall-max-distance-m", score_options.wall_max_distance_m,
                   "max mean endpoint-to-line distance of matched walls")
      ->capture_default_str();
  plan_cmd
      ->add_option("--opening-max-centre-distance-m", score_options.opening_max_centre_distance_m,
                   "max distance between matched opening centres")
      ->capture_default_str();

  // eval seg
  CLI::App* seg_cmd = app.add_subcommand(
      "seg",
      "score a segmenter on labelled images: per-class IoU, F-score, precision, recall, their means\n"
      "(mIoU, mFscore, mPrecision, mRecall) and the confusion matrix (mmseg IoUMetric definitions)");
  std::string seg_model, seg_manifest, seg_images, seg_labels, seg_json, seg_md, seg_split = "test";
  EvaluateOptions seg_options;
  SegmentOptions seg_segment;
  seg_cmd
      ->add_option("--model", seg_model,
                   "a checkpoint, a .tflite file, or a shipped model's name (default, renders, real)")
      ->required();
  seg_cmd->add_option("--manifest", seg_manifest, "dataset manifest (see --split)");
  seg_cmd->add_option("--split", seg_split, "manifest list to score: test, val or train")->capture_default_str();
  seg_cmd->add_option("--images", seg_images, "image folder (or a dataset folder without --labels)");
  seg_cmd->add_option("--labels", seg_labels, "label folder");
  seg_cmd->add_option("--label-map", seg_options.label_map, "label ids: asbuilt, ade20k, nyu40")->capture_default_str();
  seg_cmd->add_option("--max-images", seg_options.max_images, "score at most N images (0 = all)");
  seg_cmd->add_option("--mode", seg_segment.mode, "whole or slide")->capture_default_str();
  seg_cmd->add_option("--json", seg_json, "also write the metrics as JSON to FILE");
  seg_cmd->add_option("--markdown", seg_md, "also write the Markdown table to FILE");

  // eval zind
  CLI::App* zind_cmd = app.add_subcommand(
      "zind",
      "score a segmenter on real photos: each primary panorama of a ZInD tour (taken inside its room)\n"
      "turned into perspective views, labelled from its annotated layout (furniture in front of a wall\n"
      "counts as wall; passages ignored), scored on whole views and on the upper half (above the horizon).\n"
      "Writes DIR/metrics.json, metrics.md, report.html and contact sheets. ZInD is for academic use only:\n"
      "research measurement, never training data (docs/seg.md)");
  std::string zind_model, zind_tour, zind_out = "zind-eval", zind_size, zind_scale, zind_layout = "raw";
  ZindEvalOptions zind_options;
  SegmentOptions zind_segment;
  bool zind_no_sheets = false;
  zind_cmd
      ->add_option("--model", zind_model,
                   "a checkpoint, a .tflite file, or a shipped model's name (default, renders, real)")
      ->required();
  zind_cmd->add_option("--zind", zind_tour, "ZInD tour folder (with zind_data.json and panos/)")->required();
  zind_cmd->add_option("-o,--out", zind_out, "output folder (never commit it: derived from ZInD)")
      ->capture_default_str();
  AddTurnInPlaceFlags(*zind_cmd, &zind_options.turn, &zind_size);
  zind_cmd->add_option("--seg-scale", zind_scale, "scale the segmenter sees, WxH (default: the view size)");
  zind_cmd->add_option("--mode", zind_segment.mode, "whole or slide")->capture_default_str();
  zind_cmd->add_option("--layout", zind_layout, "ZInD layout the labels come from: raw, complete, visible")
      ->check(CLI::IsMember({"raw", "complete", "visible"}))
      ->capture_default_str();
  zind_cmd->add_option("--max-panoramas", zind_options.max_panoramas, "score at most N panoramas (0 = all)")
      ->capture_default_str();
  zind_cmd->add_option("--batch", zind_options.batch_size, "views per forward pass")->capture_default_str();
  zind_cmd->add_flag("--no-sheets", zind_no_sheets, "skip the contact sheets and report.html");

  Parse(app, argc, argv);

  if (zind_cmd->parsed()) {
    ApplyTurnInPlaceSize(zind_size, zind_options.turn);
    zind_options.write_sheets = !zind_no_sheets;
    zind_options.layout = zind_layout == "complete"  ? ZindLayoutKind::kComplete
                          : zind_layout == "visible" ? ZindLayoutKind::kVisible
                                                     : ZindLayoutKind::kRaw;
    zind_options.Check();
    zind_segment.scale_width_px = zind_options.turn.width_px;
    zind_segment.scale_height_px = zind_options.turn.height_px;
    ParseSizeFlag(zind_scale, "--seg-scale", zind_segment.scale_width_px, zind_segment.scale_height_px);
    const ZindTour tour = ReadZindTour(zind_tour);
    auto segmenter = LoadSegmenter(ModelPathFor(zind_model), zind_segment);
    zind_options.segmenter_name = fmt::format(
        "{} ({}, {} inference at {}x{})", std::filesystem::path(zind_model).filename().string(),
        segmenter->info().ToString(), zind_segment.mode, zind_segment.scale_width_px, zind_segment.scale_height_px);
    ProgressPrinter printer;
    ZindEvalSummary s = EvaluateOnZind(*segmenter, tour, zind_out, zind_options, printer.Callback());
    printer.Finish();
    fmt::print("{}\n{}\nreport: {}\n", s.ToMarkdown(), s.BriefReport(),
               (std::filesystem::path(zind_out) / (zind_options.write_sheets ? "report.html" : "metrics.md")).string());
    return 0;
  }

  if (seg_cmd->parsed()) {
    if (seg_manifest.empty() == seg_images.empty()) {
      throw CLI::ValidationError("eval seg", "give --manifest or --images (one of them)");
    }
    std::vector<SegSample> samples;
    if (!seg_manifest.empty()) {
      SegDataSplit split = SplitFromManifest(seg_manifest);
      if (seg_split == "test")
        samples = split.test;
      else if (seg_split == "val")
        samples = split.val;
      else if (seg_split == "train")
        samples = split.train;
      else
        throw CLI::ValidationError("--split", "must be test, val or train, got '" + seg_split + "'");
    } else {
      samples = SplitFromFolders(seg_images, seg_labels, 0.0).train;
    }
    auto segmenter = LoadSegmenter(ModelPathFor(seg_model), seg_segment);
    ProgressPrinter printer;
    SegmentationMetrics m = EvaluateSegmentation(*segmenter, samples, seg_options, printer.Callback());
    printer.Finish();
    if (!seg_json.empty()) WriteFileAtomic(seg_json, m.ToJson().dump(2) + "\n");
    if (!seg_md.empty()) WriteFileAtomic(seg_md, m.ToMarkdown());
    fmt::print("{}\n{}\n", m.ToMarkdown(), m.BriefReport());
    return 0;
  }

  if (plan_cmd->parsed()) {
    Plan predicted = ReadPlan(plan_path);
    Plan truth = ReadPlan(truth_path);
    PlanScore score = ScorePlan(predicted, truth, score_options);
    if (!plan_json_out.empty()) WriteFileAtomic(plan_json_out, PlanScoreToJson(score).dump(1) + "\n");
    fmt::print("{}", score.Table());
    return 0;
  }
  return 0;
}

}  // namespace asbuilt::cli
