// `asbuilt cluster <synth|status>` — sharded work on Slurm (cluster/,
// docs/cluster.md): a dataset rendered by an array job and merged after it,
// and what each shard has done.

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/cli/dataset_synth_flags.h"
#include "asbuilt/cluster/synth_job.h"

namespace asbuilt::cli {
namespace {

void AddSlurmFlags(CLI::App& app, SlurmOptions& slurm) {
  app.add_option("--partition", slurm.partition, "Slurm partition (default: the cluster's)");
  app.add_option("--time", slurm.time, "time limit of each task, e.g. 2:00:00");
  app.add_option("--account", slurm.account, "Slurm account to charge");
  app.add_option("--mem", slurm.mem, "memory per task's node, e.g. 8G");
  app.add_option("--cpus-per-task", slurm.cpus_per_task, "cores of each task (0: the cluster's default)");
}

// The synth options `cluster synth --resume` runs with when none are given:
// the ones the run was submitted with.
DatasetSynthOptions RecordedSynthOptions(const ClusterRunRecord& run) {
  CLI::App app;
  DatasetSynthFlags flags;
  AddDatasetSynthFlags(app, flags);
  std::vector<std::string> args(run.synth_args.rbegin(), run.synth_args.rend());  // CLI11 parses back to front.
  app.parse(args);
  return ResolveDatasetSynthFlags(flags);
}

}  // namespace

int RunClusterCommand(int argc, char** argv) {
  CLI::App app(
      "Sharded work on a Slurm cluster (docs/cluster.md).\n"
      "  synth   a synthetic dataset rendered by an array job (task i: dataset synth --shard i/N), then merged\n"
      "  status  each shard's items, state and host, from the folder and the queue",
      "asbuilt cluster");
  AddCommonFlags(app);
  app.require_subcommand(1);

  CLI::App* synth = app.add_subcommand(
      "synth",
      "render a dataset on Slurm: an array job of --shards tasks, each `asbuilt dataset synth --shard i/N\n"
      "--resume` with the options below, and a merge job after them (`asbuilt dataset merge`). DIR must be\n"
      "on a filesystem every node sees. The batch scripts (scripts/slurm/) are written to DIR/cluster/");
  std::string synth_dir;
  int shards = 0;
  bool dry_run = false, resume = false;
  ClusterSynthRequest request;
  DatasetSynthFlags synth_flags;
  synth->add_option("-o,--out", synth_dir, "dataset folder, shared by every node")->required();
  synth->add_option("--shards", shards, "array tasks (the dataset's items split among them); required unless --resume");
  AddSlurmFlags(*synth, request.slurm);
  synth->add_flag("--dry-run", dry_run, "print the batch scripts and the sbatch commands; write and submit nothing");
  synth->add_flag("--resume", resume,
                  "finish an earlier run in DIR: submit only its shards with items missing (options and shards\n"
                  "default to the run's)");
  CLI::App* synth_group = synth->add_option_group("dataset synth options", "what each item is (as dataset synth)");
  AddDatasetSynthFlags(*synth_group, synth_flags);

  CLI::App* status = app.add_subcommand("status", "each shard's items complete, state and host; merged or not");
  std::string status_dir;
  bool status_json = false;
  SlurmOptions status_slurm;
  status->add_option("dir", status_dir, "folder of a cluster run")->required();
  status->add_flag("--json", status_json, "print JSON instead of the table");

  Parse(app, argc, argv);

  if (synth->parsed()) {
    const std::optional<ClusterRunRecord> earlier = ReadClusterRun(synth_dir);
    bool options_given = false;
    for (const CLI::Option* option : synth_group->get_options()) options_given = options_given || option->count() > 0;
    DatasetSynthOptions options =
        resume && earlier && !options_given ? RecordedSynthOptions(*earlier) : ResolveDatasetSynthFlags(synth_flags);
    if (shards == 0 && resume && earlier) shards = earlier->shards;
    if (shards < 1) throw CLI::ValidationError("--shards", "give the number of array tasks (>= 1)");
    request.dir = synth_dir;
    request.shards = shards;
    request.count = options.count;
    request.record = SynthRecordOptions(options);
    request.synth_args = DatasetSynthArgs(options);
    request.asbuilt = std::filesystem::canonical("/proc/self/exe");
    request.resume = resume;
    request.dry_run = dry_run;
    ClusterSynthResult result = SubmitClusterSynth(request);
    if (dry_run) {
      fmt::print("# {}/cluster/synth.sbatch\n{}\n# {}/cluster/merge.sbatch\n{}\n", synth_dir, result.synth_script,
                 synth_dir, result.merge_script);
      fmt::print(
          "# would run: sbatch --parsable --array=<{} tasks> synth.sbatch; then\n"
          "#            sbatch --parsable --dependency=afterany:<array job> merge.sbatch\n",
          result.tasks.size());
    }
    fmt::print("{}\n", result.BriefReport(synth_dir));
    return 0;
  }
  if (status->parsed()) {
    ClusterStatus s = ReadClusterStatus(status_dir, status_slurm);
    fmt::print("{}", status_json ? s.ToJson().dump(1) + "\n" : s.Table());
    return 0;
  }
  return 2;
}

}  // namespace asbuilt::cli
