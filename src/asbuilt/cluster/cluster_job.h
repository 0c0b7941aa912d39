#ifndef ASBUILT_CLUSTER_CLUSTER_JOB_H_
#define ASBUILT_CLUSTER_CLUSTER_JOB_H_

// `asbuilt cluster synth|eval` and `asbuilt cluster status`: work split into
// the shards of a Slurm array job (task i runs an asbuilt command on shard
// i/N) and a job that depends on it and merges what the shards wrote; and
// what each shard has done, read from the folder itself (its results, the
// tasks' start and exit files), with the queue's word where squeue answers.
//
//   synth: task i = `asbuilt dataset synth --shard i/N` into DIR; merge =
//          `asbuilt dataset merge` (DIR/synth_manifest.json). A shard is done
//          when its items are complete (formats/synth_dataset.h).
//   eval:  task i = `asbuilt eval seg --shard i/N --json DIR/shards/i-of-N.json`;
//          merge = `asbuilt eval merge DIR` (DIR/metrics.json, metrics.md: the
//          shards' confusion matrices summed). A shard is done when its file is there.
//
//   train: one job of K tasks, `srun asbuilt train --distributed` (seg/distributed.h):
//          data-parallel ranks, rank 0 writes DIR/last.pt; submitted again, it resumes.
//
//   DIR/cluster/job.json            the run: kind, shards, the task arguments, every submission's job ids
//   DIR/cluster/KIND.sbatch         the array job; merge.sbatch the merge job
//   DIR/cluster/KIND/i.started      host, job id, time; i.exit the task's exit status
//   DIR/cluster/logs/               Slurm's output of every task

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/cluster/slurm.h"

namespace asbuilt {

enum class ClusterJobKind { kSynth, kEval, kTrain };
const char* ClusterJobKindName(ClusterJobKind kind);  // "synth", "eval", "train"

struct ClusterRequest {
  ClusterJobKind kind = ClusterJobKind::kSynth;
  std::filesystem::path dir;                  // Output folder, on a filesystem every node sees.
  int shards = 1;                             // Array tasks (train: the job's tasks, one rank each).
  int count = 0;                              // Items (synth) or images (eval) in all; train: unused.
  nlohmann::json record;                      // synth: what DIR/synth.json records (render/dataset_synth.h).
  std::vector<std::string> args;              // The task command's own flags (dataset synth's, eval seg's).
  std::filesystem::path asbuilt = "asbuilt";  // The binary the tasks run.
  SlurmOptions slurm;
  bool resume = false;   // Finish an earlier run: submit the shards not done.
  bool dry_run = false;  // Write nothing, submit nothing: the scripts are returned.

  void Check() const;
};

struct ClusterSubmission {
  std::vector<int> tasks;  // Array tasks submitted (all, or the unfinished ones on resume).
  std::string array_job;   // Job ids ("" on a dry run).
  std::string merge_job;
  std::string task_script;  // The scripts' text.
  std::string merge_script;

  std::string BriefReport(const std::filesystem::path& dir) const;
};

// Writes the scripts and the run record and submits the array and the merge
// (afterany: the merge names a failed shard rather than waiting forever); a
// train is one job of `shards` tasks and no merge (on resume, all of it). A
// synth claims DIR for its options first (refused, nothing written, when it
// was made with others). A folder with a run already needs `resume`, with
// the same kind and shards.
ClusterSubmission SubmitClusterJob(const ClusterRequest& request);

// What DIR/cluster/job.json says of an earlier run, if there is one (for
// `--resume` without the options again).
struct ClusterRunRecord {
  ClusterJobKind kind = ClusterJobKind::kSynth;
  int shards = 0;
  int count = 0;
  std::vector<std::string> args;
};
std::optional<ClusterRunRecord> ReadClusterRun(const std::filesystem::path& dir);

struct ShardStatus {
  int index = 0;
  int items = 0;     // In this shard (eval: its one result file).
  int complete = 0;  // Of those, done.
  // "done", "running", "pending", "failed (exit N)", "cancelled" (SIGTERM:
  // scancel, preemption, time limit), "killed (exit 137)", "lost" (started,
  // never ended, gone from the queue), "not started".
  std::string state;
  std::string host;  // Where it last started; "" if it never did.
};

struct ClusterStatus {
  std::filesystem::path dir;
  ClusterJobKind kind = ClusterJobKind::kSynth;
  int shards = 0;
  int count = 0;
  std::vector<ShardStatus> shard_status;
  bool merged = false;               // The merge's output is there (train: a checkpoint, DIR/last.pt).
  std::string array_job, merge_job;  // train: its job in array_job.
  std::string job_state;             // train: the queue's word on it ("" when it has left).
  int epochs_done = 0;               // train: rows of DIR/log.csv.

  bool all_done() const;
  // A table, one row per shard, and a closing line with what to do next.
  std::string Table() const;
  nlohmann::json ToJson() const;
};

// Throws InputError naming DIR/cluster/job.json when DIR has no cluster run.
ClusterStatus ReadClusterStatus(const std::filesystem::path& dir, const SlurmOptions& slurm = {});

// DIR/shards/i-of-N.json: where eval task i writes its shard's metrics.
std::filesystem::path EvalShardPath(const std::filesystem::path& dir, int index, int shards);

}  // namespace asbuilt

#endif  // ASBUILT_CLUSTER_CLUSTER_JOB_H_
