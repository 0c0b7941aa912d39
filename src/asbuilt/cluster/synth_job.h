#ifndef ASBUILT_CLUSTER_SYNTH_JOB_H_
#define ASBUILT_CLUSTER_SYNTH_JOB_H_

// `asbuilt cluster synth` and `asbuilt cluster status`: a synthetic dataset
// rendered by a Slurm array job (task i runs `asbuilt dataset synth --shard
// i/N`), then merged by a job that depends on it (`asbuilt dataset merge`);
// and what each shard has done, read from the folder itself (the items, the
// tasks' start and exit files), with the queue's word where squeue answers.
//
//   DIR/cluster/job.json            the run: shards, count, every submission's job ids
//   DIR/cluster/synth.sbatch        the array job, merge.sbatch the merge job
//   DIR/cluster/synth/i.started     host, job id, time; i.exit the task's exit status
//   DIR/cluster/logs/               Slurm's output of every task

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/cluster/slurm.h"

namespace asbuilt {

struct ClusterSynthRequest {
  std::filesystem::path dir;                  // The dataset folder, on a filesystem every node sees.
  int shards = 1;                             // Array tasks.
  int count = 0;                              // The dataset's items.
  nlohmann::json record;                      // What DIR/synth.json records (render/dataset_synth.h).
  std::vector<std::string> synth_args;        // `dataset synth` flags that give those options.
  std::filesystem::path asbuilt = "asbuilt";  // The binary the tasks run.
  SlurmOptions slurm;
  bool resume = false;   // Finish an earlier run: submit the shards not complete.
  bool dry_run = false;  // Write nothing, submit nothing: the scripts are returned.

  void Check() const;
};

struct ClusterSynthResult {
  std::vector<int> tasks;  // Array tasks submitted (all, or the incomplete ones on resume).
  std::string array_job;   // Job ids ("" on a dry run).
  std::string merge_job;
  std::string synth_script;  // The scripts' text.
  std::string merge_script;

  std::string BriefReport(const std::filesystem::path& dir) const;
};

// Claims DIR for the options (refused, nothing written, when it was made with
// others), writes the scripts and the run record, submits the array and the
// merge (afterany: the merge names a failed shard rather than waiting
// forever). A folder with a run already needs `resume`, with the same shards.
ClusterSynthResult SubmitClusterSynth(const ClusterSynthRequest& request);

// What DIR/cluster/job.json says of an earlier run, if there is one (for
// `cluster synth --resume` without the options again).
struct ClusterRunRecord {
  int shards = 0;
  int count = 0;
  std::vector<std::string> synth_args;
};
std::optional<ClusterRunRecord> ReadClusterRun(const std::filesystem::path& dir);

struct ShardStatus {
  int index = 0;
  int items = 0;     // In this shard.
  int complete = 0;  // Of those, complete (formats/synth_dataset.h).
  // "done", "running", "pending", "failed (exit N)", "cancelled" (SIGTERM:
  // scancel, preemption, time limit), "killed (exit 137)", "lost" (started,
  // never ended, gone from the queue), "not started".
  std::string state;
  std::string host;  // Where it last started; "" if it never did.
};

struct ClusterStatus {
  std::filesystem::path dir;
  int shards = 0;
  int count = 0;
  std::vector<ShardStatus> shard_status;
  bool merged = false;  // DIR/synth_manifest.json is there.
  std::string array_job, merge_job;

  bool all_done() const;
  // A table, one row per shard, and a closing line with what to do next.
  std::string Table() const;
  nlohmann::json ToJson() const;
};

// Throws InputError naming DIR/cluster/job.json when DIR has no cluster run.
ClusterStatus ReadClusterStatus(const std::filesystem::path& dir, const SlurmOptions& slurm = {});

}  // namespace asbuilt

#endif  // ASBUILT_CLUSTER_SYNTH_JOB_H_
