// `asbuilt cluster <synth|eval|train|status>` — work on Slurm (cluster/,
// docs/cluster.md): a dataset rendered by an array job and merged after it,
// a segmenter scored by one and its confusion matrices summed, a model
// trained data-parallel by the tasks of one job, and how each is going.

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/cli/dataset_synth_flags.h"
#include "asbuilt/cluster/cluster_job.h"
#include "asbuilt/seg/seg_data.h"
#include "asbuilt/util/error.h"

namespace asbuilt::cli {
namespace fs = std::filesystem;
namespace {

// Flags every cluster submission takes.
struct SubmitFlags {
  std::string out;
  int shards = 0;
  bool dry_run = false, resume = false;
  SlurmOptions slurm;
};

void AddSubmitFlags(CLI::App& app, SubmitFlags& flags, const std::string& what, bool sharded = true) {
  app.add_option("-o,--out", flags.out, what + ", on a filesystem every node sees")->required();
  if (sharded) {
    app.add_option("--shards", flags.shards, "array tasks (the work split among them); required unless --resume");
  }
  app.add_option("--partition", flags.slurm.partition, "Slurm partition (default: the cluster's)");
  app.add_option("--time", flags.slurm.time, "time limit of each task, e.g. 2:00:00");
  app.add_option("--account", flags.slurm.account, "Slurm account to charge");
  app.add_option("--mem", flags.slurm.mem, "memory per task's node, e.g. 8G");
  app.add_option("--cpus-per-task", flags.slurm.cpus_per_task, "cores of each task (0: the cluster's default)");
  app.add_flag("--dry-run", flags.dry_run, "print the batch scripts and the sbatch commands; write and submit nothing");
  app.add_flag("--resume", flags.resume,
               "finish an earlier run in the folder: submit only its shards not done (options and shards\n"
               "default to the run's)");
}

// The options `cluster synth --resume` runs with when none are given: the
// ones the run was submitted with.
DatasetSynthOptions RecordedSynthOptions(const ClusterRunRecord& run) {
  CLI::App app;
  DatasetSynthFlags flags;
  AddDatasetSynthFlags(app, flags);
  std::vector<std::string> args(run.args.rbegin(), run.args.rend());  // CLI11 parses back to front.
  app.parse(args);
  return ResolveDatasetSynthFlags(flags);
}

// Bad training flags fail here, at submission, with train's own message,
// rather than on the cluster after the job has waited in the queue.
void CheckTrainFlags(const std::string& out, const std::vector<std::string>& args, int tasks) {
  std::vector<std::string> words = {"train", "-o", out};
  words.insert(words.end(), args.begin(), args.end());
  words.insert(words.end(), {"--distributed", "--check-flags", std::to_string(std::max(tasks, 1))});
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  try {
    RunTrainCommand(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError& e) {
    throw InvalidArgument(fmt::format("the training flags: {} (asbuilt train --help lists them)", e.what()));
  }
}

int Submit(const SubmitFlags& flags, ClusterRequest request) {
  request.dir = flags.out;
  request.shards = flags.shards;
  request.asbuilt = fs::canonical("/proc/self/exe");
  request.slurm = flags.slurm;
  request.resume = flags.resume;
  request.dry_run = flags.dry_run;
  if (request.shards < 1) {
    throw CLI::ValidationError(request.kind == ClusterJobKind::kTrain ? "--tasks" : "--shards",
                               "give the number of tasks (>= 1)");
  }
  const ClusterSubmission result = SubmitClusterJob(request);
  if (flags.dry_run && request.kind == ClusterJobKind::kTrain) {
    fmt::print("# {}/cluster/train.sbatch\n{}\n# would run: sbatch --parsable train.sbatch\n", flags.out,
               result.task_script);
  } else if (flags.dry_run) {
    const std::string kind = ClusterJobKindName(request.kind);
    fmt::print("# {}/cluster/{}.sbatch\n{}\n# {}/cluster/{}-merge.sbatch\n{}\n", flags.out, kind, result.task_script,
               flags.out, kind, result.merge_script);
    fmt::print(
        "# would run: sbatch --parsable --array=<{} tasks> {}.sbatch; then\n"
        "#            sbatch --parsable --dependency=afterany:<array job> {}-merge.sbatch\n",
        result.tasks.size(), kind, kind);
  }
  fmt::print("{}\n", result.BriefReport(flags.out));
  return 0;
}

}  // namespace

int RunClusterCommand(int argc, char** argv) {
  CLI::App app(
      "Sharded work on a Slurm cluster (docs/cluster.md).\n"
      "  synth   a synthetic dataset rendered by an array job (task i: dataset synth --shard i/N), then merged\n"
      "  eval    a segmenter scored by an array job (task i: eval seg --shard i/N), the metrics merged exactly\n"
      "  train   a model trained data-parallel by the K tasks of one job (srun asbuilt train --distributed)\n"
      "  status  each shard's progress, state and host, from the folder and the queue",
      "asbuilt cluster");
  AddCommonFlags(app);
  app.require_subcommand(1);

  CLI::App* synth = app.add_subcommand(
      "synth",
      "render a dataset on Slurm: an array job of --shards tasks, each `asbuilt dataset synth --shard i/N\n"
      "--resume` with the options below, and a merge job after them (`asbuilt dataset merge`). The batch\n"
      "scripts (scripts/slurm/) are written to DIR/cluster/");
  SubmitFlags synth_flags;
  DatasetSynthFlags synth_options;
  AddSubmitFlags(*synth, synth_flags, "dataset folder");
  CLI::App* synth_group = synth->add_option_group("dataset synth options", "what each item is (as dataset synth)");
  AddDatasetSynthFlags(*synth_group, synth_options);

  CLI::App* eval = app.add_subcommand(
      "eval",
      "score a segmenter on Slurm: an array job of --shards tasks, each `asbuilt eval seg --shard i/N`, and\n"
      "a merge job after them (`asbuilt eval merge`: the confusion matrices summed into OUT/metrics.json and\n"
      "metrics.md, what one process gives)");
  SubmitFlags eval_flags;
  std::string eval_model, eval_dataset, eval_split = "test", eval_label_map = "asbuilt", eval_mode = "whole";
  AddSubmitFlags(*eval, eval_flags, "evaluation folder");
  eval->add_option("model", eval_model, "a checkpoint, a .tflite file, or a shipped model's name")->required();
  eval->add_option("dataset", eval_dataset, "a dataset folder (images/ + labels/, …) or a manifest .json")->required();
  eval->add_option("--split", eval_split, "manifest list to score: test, val or train")->capture_default_str();
  eval->add_option("--label-map", eval_label_map, "label ids: asbuilt, ade20k, nyu40")->capture_default_str();
  eval->add_option("--mode", eval_mode, "whole or slide")->capture_default_str();

  CLI::App* train = app.add_subcommand(
      "train",
      "train on Slurm: one job of --tasks K tasks, each a rank of `asbuilt train --distributed` (gradients\n"
      "all-reduced every step; --batch is the global batch, divisible by K; rank 0 writes OUT). Every flag\n"
      "not listed here goes to `asbuilt train` as it is (e.g. --images DIR --epochs 20 --batch 8). Submitted\n"
      "again (--resume), the run continues from OUT/last.pt");
  SubmitFlags train_flags;
  AddSubmitFlags(*train, train_flags, "training run folder", /*sharded=*/false);
  train->add_option("--tasks", train_flags.shards, "ranks (Slurm tasks, one process each); required unless --resume");
  train->allow_extras();

  CLI::App* status = app.add_subcommand("status", "each shard's progress, state and host; merged or not");
  std::string status_dir;
  bool status_json = false;
  status->add_option("dir", status_dir, "folder of a cluster run")->required();
  status->add_flag("--json", status_json, "print JSON instead of the table");

  Parse(app, argc, argv);

  if (synth->parsed()) {
    const std::optional<ClusterRunRecord> earlier = ReadClusterRun(synth_flags.out);
    bool options_given = false;
    for (const CLI::Option* option : synth_group->get_options()) options_given = options_given || option->count() > 0;
    const bool recorded = synth_flags.resume && earlier && earlier->kind == ClusterJobKind::kSynth;
    const DatasetSynthOptions options =
        recorded && !options_given ? RecordedSynthOptions(*earlier) : ResolveDatasetSynthFlags(synth_options);
    if (synth_flags.shards == 0 && recorded) synth_flags.shards = earlier->shards;
    return Submit(synth_flags, {.kind = ClusterJobKind::kSynth,
                                .count = options.count,
                                .record = SynthRecordOptions(options),
                                .args = DatasetSynthArgs(options)});
  }
  if (eval->parsed()) {
    const std::optional<ClusterRunRecord> earlier = ReadClusterRun(eval_flags.out);
    if (eval_flags.shards == 0 && eval_flags.resume && earlier) eval_flags.shards = earlier->shards;
    const bool manifest = fs::path(eval_dataset).extension() == ".json";
    const fs::path dataset = fs::absolute(eval_dataset);
    std::size_t images = 0;
    if (manifest) {
      const SegDataSplit split = SplitFromManifest(dataset);
      images = (eval_split == "val" ? split.val : eval_split == "train" ? split.train : split.test).size();
    } else {
      images = SplitFromFolders(dataset, "", 0.0).train.size();
    }
    // A path names the same file on every node; a shipped model's name is found there by its own binary.
    const std::string model = fs::exists(eval_model) ? fs::absolute(eval_model).string() : eval_model;
    std::vector<std::string> args = {"--model",        model,         manifest ? "--manifest" : "--images",
                                     dataset.string(), "--label-map", eval_label_map,
                                     "--mode",         eval_mode};
    if (manifest) args.insert(args.end(), {"--split", eval_split});
    return Submit(eval_flags, {.kind = ClusterJobKind::kEval, .count = static_cast<int>(images), .args = args});
  }
  if (train->parsed()) {
    std::vector<std::string> args = train->remaining();
    for (const std::string& a : args) {
      if (a == "--distributed" || a == "-o" || a == "--out" || a.rfind("--out=", 0) == 0) {
        throw CLI::ValidationError(a, "cluster train sets it itself (-o is the run folder; every task is distributed)");
      }
    }
    const std::optional<ClusterRunRecord> earlier = ReadClusterRun(train_flags.out);
    const bool recorded = train_flags.resume && earlier && earlier->kind == ClusterJobKind::kTrain;
    if (recorded && args.empty()) args = earlier->args;
    if (recorded && train_flags.shards == 0) train_flags.shards = earlier->shards;
    if (args.empty())
      throw CLI::ValidationError("cluster train", "give the training flags (e.g. --images DIR --epochs 20)");
    CheckTrainFlags(train_flags.out, args, train_flags.shards);
    return Submit(train_flags, {.kind = ClusterJobKind::kTrain, .args = args});
  }
  if (status->parsed()) {
    ClusterStatus s = ReadClusterStatus(status_dir);
    fmt::print("{}", status_json ? s.ToJson().dump(1) + "\n" : s.Table());
    return 0;
  }
  return 2;
}

}  // namespace asbuilt::cli
