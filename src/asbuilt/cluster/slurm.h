#ifndef ASBUILT_CLUSTER_SLURM_H_
#define ASBUILT_CLUSTER_SLURM_H_

// Slurm from asbuilt: batch scripts made from the plain files in
// scripts/slurm/ (compiled in), submitted with sbatch, and the queue's view
// of an array job read with squeue (docs/cluster.md). Nothing here links the
// renderer or LibTorch: the tasks run the `asbuilt` binary.

#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace asbuilt {

// What to ask Slurm for; empty or 0 leaves the cluster's default.
struct SlurmOptions {
  std::string partition;
  std::string time;     // --time, e.g. "2:00:00".
  std::string account;  // --account.
  std::string mem;      // --mem per node, e.g. "8G".
  int cpus_per_task = 0;
  std::string sbatch = "sbatch";  // The programs; on PATH unless a path.
  std::string squeue = "squeue";

  void Check() const;
};

// The compiled-in text of scripts/slurm/NAME.sbatch ("synth", "synth-merge",
// "eval", "eval-merge", "train").
// Throws InvalidArgument for another name.
std::string_view SlurmTemplate(std::string_view name);

// A batch script from a template: its #SBATCH lines replaced by
// `directives` ("--job-name=x", without "#SBATCH "), and each variable set
// at the top (shell-quoted), so it runs as the template does by hand with
// those variables exported.
std::string MakeBatchScript(std::string_view template_text, const std::vector<std::string>& directives,
                            const std::vector<std::pair<std::string, std::string>>& variables);

// The directives of `options` plus the job name and log file pattern.
std::vector<std::string> SlurmDirectives(const SlurmOptions& options, std::string_view job_name,
                                         const std::filesystem::path& output_pattern);

// `text` as one word of a POSIX shell: as it is when it needs no quotes, else 'quoted'.
std::string ShellQuote(std::string_view text);

// The program's full path on PATH (or `program` itself when it has a '/' and
// is executable); empty when not found.
std::filesystem::path FindProgram(std::string_view program);

// `sbatch --parsable ARGS SCRIPT` → the job id. Throws Error with sbatch's
// own message when it refuses, or, when sbatch is not installed, one saying
// how to get it and that --dry-run shows the scripts without it.
std::string SubmitBatch(const SlurmOptions& options, const std::vector<std::string>& args,
                        const std::filesystem::path& script);

// The queue's state of job `job_id` ("PENDING", "RUNNING", …); empty when
// squeue is missing or the job has left the queue.
std::string JobState(const SlurmOptions& options, std::string_view job_id);

// The queue's state of each task of array job `job_id` ("PENDING",
// "RUNNING", …) by task index; empty when squeue is missing or the job has
// left the queue.
std::map<int, std::string> ArrayTaskStates(const SlurmOptions& options, std::string_view job_id);

}  // namespace asbuilt

#endif  // ASBUILT_CLUSTER_SLURM_H_
