// `asbuilt eval <what> …` — scores results against the truth. Each kind of
// evaluation is one CLI11 subcommand:
//   eval plan PLAN TRUTH [--json FILE]   floor plan vs truth.json (plan/score.h)
//   eval seg --model M (--manifest F | --images D [--labels D]) [--shard i/N]   segmenter (seg/evaluate.h)
//   eval merge DIR --shards N            the shards' metrics of `cluster eval` summed (seg/metrics.h)
//   eval zind --model M --zind TOUR [-o DIR]   segmenter on real photos (pipeline/zind_eval.h)

#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/cluster/cluster_job.h"
#include "asbuilt/formats/plan_file.h"
#include "asbuilt/formats/zind.h"
#include "asbuilt/pipeline/survey.h"
#include "asbuilt/pipeline/zind_eval.h"
#include "asbuilt/plan/score.h"
#include "asbuilt/seg/evaluate.h"
#include "asbuilt/seg/seg_data.h"
#include "asbuilt/util/progress.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"
#include "asbuilt/util/shard.h"

namespace asbuilt::cli {

namespace {

// `eval merge DIR --shards N`: DIR/shards/i-of-N.json summed into DIR/metrics.json and metrics.md.
void MergeEvalShards(const std::string& merge_dir, int merge_shards) {
  if (merge_shards < 1) throw CLI::ValidationError("--shards", "must be >= 1");
  std::vector<SegmentationMetrics> parts;
  std::vector<std::string> missing;
  std::optional<std::int64_t> total;
  for (int k = 0; k < merge_shards; ++k) {
    const std::filesystem::path file = EvalShardPath(merge_dir, k, merge_shards);
    if (!std::filesystem::exists(file)) {
      missing.push_back(std::to_string(k));
      continue;
    }
    JsonDiagnostics diag(file.string());
    const nlohmann::json json = ParseJsonFile(file, diag);
    diag.ThrowIfErrors();
    const nlohmann::json shard = json.value("shard", nlohmann::json::object());
    if (shard.value("index", -1) != k || shard.value("count", -1) != merge_shards) {
      throw InputError(file.string(), "shard", fmt::format("expected shard {} of {}", k, merge_shards));
    }
    if (total && shard.value("images_total", -1) != *total) {
      throw InputError(file.string(), "shard.images_total",
                       "differs from the earlier shards': not the same evaluation");
    }
    total = shard.value("images_total", std::int64_t{-1});
    parts.push_back(MetricsFromJson(json, file.string()));
  }
  if (!missing.empty()) {
    throw InputError((std::filesystem::path(merge_dir) / "shards").string(), "",
                     fmt::format("shard(s) {} of {} missing: finish them (asbuilt cluster eval -o {} --resume)",
                                 fmt::join(missing, ", "), merge_shards, merge_dir));
  }
  SegmentationMetrics m = MergeMetrics(parts);
  WriteFileAtomic(std::filesystem::path(merge_dir) / "metrics.json", m.ToJson().dump(2) + "\n");
  WriteFileAtomic(std::filesystem::path(merge_dir) / "metrics.md", m.ToMarkdown());
  fmt::print("{}\n{}\nwrote {}/metrics.json, metrics.md\n", m.ToMarkdown(), m.BriefReport(), merge_dir);
}

}  // namespace

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
  const auto seg_segment_flags = AddSegmentFlags(*seg_cmd, seg_segment);
  seg_cmd->add_option("--json", seg_json, "also write the metrics as JSON to FILE");
  seg_cmd->add_option("--markdown", seg_md, "also write the Markdown table to FILE");
  std::string seg_shard;
  seg_cmd->add_option("--shard", seg_shard,
                      "score only shard i of N of the images (i/N, 0-based); its --json holds the confusion\n"
                      "matrix that `eval merge` sums");

  // eval merge
  CLI::App* merge_cmd = app.add_subcommand(
      "merge",
      "the metrics of a sharded evaluation (asbuilt cluster eval): DIR/shards/i-of-N.json summed into\n"
      "DIR/metrics.json and metrics.md, the metrics one process gives");
  std::string merge_dir;
  int merge_shards = 0;
  merge_cmd->add_option("dir", merge_dir, "the evaluation folder (with shards/)")->required();
  merge_cmd->add_option("--shards", merge_shards, "how many shards the evaluation had")->required();

  // eval zind
  CLI::App* zind_cmd = app.add_subcommand(
      "zind",
      "score a segmenter on real photos: each primary panorama of a ZInD tour (taken inside its room)\n"
      "turned into perspective views, labelled from its annotated layout (furniture in front of a wall\n"
      "counts as wall; passages ignored), scored on whole views and on the upper half (above the horizon).\n"
      "Writes DIR/metrics.json, metrics.md, report.html and contact sheets. ZInD is for academic use only:\n"
      "research measurement, never training data (docs/seg.md)");
  std::string zind_model, zind_tour, zind_out = "zind-eval", zind_layout = "raw";
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
  const auto zind_turn_flags = AddTurnInPlaceFlags(*zind_cmd, zind_options.turn);
  // The segmenter reads the views at their own size unless --seg-scale says otherwise.
  const auto zind_segment_flags = AddSegmentFlags(*zind_cmd, zind_segment, "--seg-scale", false);
  zind_cmd->add_option("--layout", zind_layout, "ZInD layout the labels come from: raw, complete, visible")
      ->check(CLI::IsMember({"raw", "complete", "visible"}))
      ->capture_default_str();
  zind_cmd->add_option("--max-panoramas", zind_options.max_panoramas, "score at most N panoramas (0 = all)")
      ->capture_default_str();
  zind_cmd->add_option("--batch", zind_options.batch_size, "views per forward pass")->capture_default_str();
  zind_cmd->add_flag("--no-sheets", zind_no_sheets, "skip the contact sheets and report.html");

  Parse(app, argc, argv);

  if (zind_cmd->parsed()) {
    zind_turn_flags->ReadGiven(TurnInPlaceOptionFields(), zind_options.turn);
    zind_options.write_sheets = !zind_no_sheets;
    zind_options.layout = zind_layout == "complete"  ? ZindLayoutKind::kComplete
                          : zind_layout == "visible" ? ZindLayoutKind::kVisible
                                                     : ZindLayoutKind::kRaw;
    zind_options.Check();
    zind_segment.scale_width_px = zind_options.turn.width_px;
    zind_segment.scale_height_px = zind_options.turn.height_px;
    zind_segment_flags->ReadGiven(SegmentOptionFields(), zind_segment);
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
    if (seg_options.max_images > 0 && static_cast<int>(samples.size()) > seg_options.max_images) {
      samples.resize(seg_options.max_images);
    }
    const std::size_t total_images = samples.size();
    std::optional<Shard> shard;
    if (!seg_shard.empty()) {
      shard = ParseShard(seg_shard);
      CheckShardCount(shard->count, static_cast<int>(samples.size()));
      auto [begin, end] = ShardRange(static_cast<int>(samples.size()), *shard);
      samples = std::vector<SegSample>(samples.begin() + begin, samples.begin() + end);
    }
    seg_segment_flags->ReadGiven(SegmentOptionFields(), seg_segment);
    auto segmenter = LoadSegmenter(ModelPathFor(seg_model), seg_segment);
    ProgressPrinter printer;
    SegmentationMetrics m = EvaluateSegmentation(*segmenter, samples, seg_options, printer.Callback());
    printer.Finish();
    nlohmann::json json = m.ToJson();
    if (shard) json["shard"] = {{"index", shard->index}, {"count", shard->count}, {"images_total", total_images}};
    if (!seg_json.empty()) WriteFileAtomic(seg_json, json.dump(2) + "\n");
    if (!seg_md.empty()) WriteFileAtomic(seg_md, m.ToMarkdown());
    fmt::print("{}\n{}\n", m.ToMarkdown(), m.BriefReport());
    return 0;
  }

  if (merge_cmd->parsed()) {
    MergeEvalShards(merge_dir, merge_shards);
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
