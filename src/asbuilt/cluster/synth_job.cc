#include "asbuilt/cluster/synth_job.h"

#include <chrono>
#include <ctime>
#include <fstream>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "asbuilt/formats/synth_dataset.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"
#include "asbuilt/util/shard.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

fs::path JobRecordPath(const fs::path& dir) { return dir / "cluster" / "job.json"; }

nlohmann::json ReadJobRecord(const fs::path& dir) {
  const fs::path path = JobRecordPath(dir);
  JsonDiagnostics diag(path.string());
  nlohmann::json record = ParseJsonFile(path, diag);
  diag.ThrowIfErrors();
  if (!record.is_object() || record.value("kind", "") != "synth" || !record.contains("shards") ||
      !record["shards"].is_number_integer() || !record.contains("count") || !record["count"].is_number_integer()) {
    throw InputError(path.string(), "", "not an asbuilt cluster synth record (kind, shards, count)");
  }
  return record;
}

std::string NowUtc() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

// "0-3" for every task, else "1,3".
std::string ArraySpec(const std::vector<int>& tasks, int shards) {
  if (static_cast<int>(tasks.size()) == shards) return fmt::format("0-{}", shards - 1);
  return fmt::format("{}", fmt::join(tasks, ","));
}

std::string FirstLine(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace

void ClusterSynthRequest::Check() const {
  CheckArgument(!dir.empty(), "ClusterSynthRequest.dir is empty");
  CheckArgument(count >= 1, fmt::format("ClusterSynthRequest.count = {}, must be >= 1", count));
  CheckShardCount(shards, count);
  slurm.Check();
}

std::string ClusterSynthResult::BriefReport(const fs::path& dir) const {
  if (array_job.empty() && merge_job.empty()) return "dry run: nothing written, nothing submitted";
  std::string text = tasks.empty() ? "every shard is complete; "
                                   : fmt::format("submitted {} synth task(s) as job {}; ", tasks.size(), array_job);
  return text +
         fmt::format("merge job {} runs after them.\nprogress: asbuilt cluster status {}", merge_job, dir.string());
}

ClusterSynthResult SubmitClusterSynth(const ClusterSynthRequest& request) {
  request.Check();
  const fs::path dir = fs::absolute(request.dir);
  const fs::path cluster = dir / "cluster";
  nlohmann::json job = {{"version", 1},
                        {"kind", "synth"},
                        {"shards", request.shards},
                        {"count", request.count},
                        {"synth_args", request.synth_args},
                        {"submissions", nlohmann::json::array()}};
  if (fs::exists(JobRecordPath(dir))) {
    if (!request.resume) {
      throw InputError(JobRecordPath(dir).string(), "",
                       fmt::format("{} already has a cluster run: see `asbuilt cluster status {}`, and add --resume "
                                   "to submit its unfinished shards",
                                   dir.string(), dir.string()));
    }
    job = ReadJobRecord(dir);
    if (job["shards"].get<int>() != request.shards) {
      throw InputError(JobRecordPath(dir).string(), "shards",
                       fmt::format("this run has {} shards; resume it with --shards {}", job["shards"].get<int>(),
                                   job["shards"].get<int>()));
    }
  }
  if (request.dry_run) {
    CheckSynthDir(dir, request.record);
  } else {
    ClaimSynthDir(dir, request.record);
  }

  ClusterSynthResult result;
  for (int k = 0; k < request.shards; ++k) {
    auto [begin, end] = ShardRange(request.count, k, request.shards);
    bool complete = true;
    for (int i = begin; i < end && complete; ++i) complete = IsSynthItemComplete(dir, i);
    if (!request.resume || !complete) result.tasks.push_back(k);
  }
  std::string args;
  for (const std::string& a : request.synth_args) args += (args.empty() ? "" : " ") + ShellQuote(a);
  const std::vector<std::pair<std::string, std::string>> variables = {
      {"ASBUILT", request.asbuilt.string()},
      {"ASBUILT_OUT", dir.string()},
      {"ASBUILT_SHARDS", std::to_string(request.shards)},
      {"ASBUILT_ARGS", args}};
  result.synth_script =
      MakeBatchScript(SlurmTemplate("synth"),
                      SlurmDirectives(request.slurm, "asbuilt-synth", cluster / "logs" / "synth-%A_%a.out"), variables);
  result.merge_script =
      MakeBatchScript(SlurmTemplate("merge"),
                      SlurmDirectives(request.slurm, "asbuilt-merge", cluster / "logs" / "merge-%j.out"), variables);
  if (request.dry_run) return result;

  fs::create_directories(cluster / "logs");
  WriteFileAtomic(cluster / "synth.sbatch", result.synth_script);
  WriteFileAtomic(cluster / "merge.sbatch", result.merge_script);
  nlohmann::json submission = {{"time", NowUtc()}, {"tasks", result.tasks}};
  if (!result.tasks.empty()) {
    result.array_job =
        SubmitBatch(request.slurm, {"--array=" + ArraySpec(result.tasks, request.shards)}, cluster / "synth.sbatch");
    submission["array_job"] = result.array_job;
  }
  std::vector<std::string> merge_args;
  if (!result.array_job.empty()) merge_args.push_back("--dependency=afterany:" + result.array_job);
  result.merge_job = SubmitBatch(request.slurm, merge_args, cluster / "merge.sbatch");
  submission["merge_job"] = result.merge_job;
  job["submissions"].push_back(submission);
  WriteFileAtomic(JobRecordPath(dir), job.dump(1) + "\n");
  return result;
}

std::optional<ClusterRunRecord> ReadClusterRun(const fs::path& dir) {
  if (!fs::exists(JobRecordPath(dir))) return std::nullopt;
  const nlohmann::json job = ReadJobRecord(dir);
  ClusterRunRecord run{.shards = job["shards"].get<int>(), .count = job["count"].get<int>()};
  if (job.contains("synth_args") && job["synth_args"].is_array()) {
    for (const nlohmann::json& a : job["synth_args"]) {
      if (a.is_string()) run.synth_args.push_back(a.get<std::string>());
    }
  }
  return run;
}

bool ClusterStatus::all_done() const {
  for (const ShardStatus& s : shard_status) {
    if (s.state != "done") return false;
  }
  return true;
}

std::string ClusterStatus::Table() const {
  std::string text = fmt::format("{}: {} items in {} shards (array job {}, merge job {})\n", dir.string(), count,
                                 shards, array_job.empty() ? "-" : array_job, merge_job.empty() ? "-" : merge_job);
  text += fmt::format("{:>5}  {:>13}  {:>15}  {:<22} {}\n", "shard", "items", "complete", "state", "host");
  int complete = 0;
  for (const ShardStatus& s : shard_status) {
    auto [begin, end] = ShardRange(count, s.index, shards);
    text += fmt::format("{:>5}  {:>13}  {:>15}  {:<22} {}\n", s.index, fmt::format("{}-{}", begin, end - 1),
                        fmt::format("{}/{}", s.complete, s.items), s.state, s.host);
    complete += s.complete;
  }
  text += fmt::format("items complete: {} of {} ({:.1f} %)\n", complete, count, 100.0 * complete / count);
  if (merged) {
    text += "merged: " + SynthManifestPath(dir).string() + "\n";
  } else if (all_done()) {
    text += fmt::format("every shard is complete; not merged yet: asbuilt dataset merge {} --shards {}\n", dir.string(),
                        shards);
  } else {
    bool stuck = false;
    for (const ShardStatus& s : shard_status) {
      stuck = stuck || s.state.rfind("failed", 0) == 0 || s.state.rfind("killed", 0) == 0 || s.state == "cancelled" ||
              s.state == "lost";
    }
    if (stuck) {
      text += fmt::format("to finish the failed shards: asbuilt cluster synth -o {} --shards {} --resume\n",
                          dir.string(), shards);
    }
  }
  return text;
}

nlohmann::json ClusterStatus::ToJson() const {
  nlohmann::json shards_json = nlohmann::json::array();
  for (const ShardStatus& s : shard_status) {
    shards_json.push_back(
        {{"index", s.index}, {"items", s.items}, {"complete", s.complete}, {"state", s.state}, {"host", s.host}});
  }
  return {{"dir", dir.string()}, {"count", count},         {"shards", shards_json},
          {"merged", merged},    {"array_job", array_job}, {"merge_job", merge_job}};
}

ClusterStatus ReadClusterStatus(const fs::path& dir, const SlurmOptions& slurm) {
  if (!fs::exists(JobRecordPath(dir))) {
    throw InputError(JobRecordPath(dir).string(), "",
                     "not found: this folder has no cluster run (asbuilt cluster synth -o DIR ...)");
  }
  const nlohmann::json job = ReadJobRecord(dir);
  ClusterStatus status;
  status.dir = dir;
  status.shards = job["shards"].get<int>();
  status.count = job["count"].get<int>();
  if (job.contains("submissions") && job["submissions"].is_array() && !job["submissions"].empty()) {
    const nlohmann::json& last = job["submissions"].back();
    status.array_job = last.value("array_job", "");
    status.merge_job = last.value("merge_job", "");
  }
  // The queue's word on the latest array job; an earlier submission's tasks have ended.
  const std::map<int, std::string> queue = ArrayTaskStates(slurm, status.array_job);
  const bool queue_answers = !FindProgram(slurm.squeue).empty() && !status.array_job.empty();
  const fs::path state_dir = dir / "cluster" / "synth";
  for (int k = 0; k < status.shards; ++k) {
    auto [begin, end] = ShardRange(status.count, k, status.shards);
    ShardStatus s{.index = k, .items = end - begin};
    for (int i = begin; i < end; ++i) s.complete += IsSynthItemComplete(dir, i) ? 1 : 0;
    const fs::path started = state_dir / fmt::format("{}.started", k);
    const fs::path exited = state_dir / fmt::format("{}.exit", k);
    if (fs::exists(started)) s.host = FirstLine(started).substr(0, FirstLine(started).find(' '));
    const auto queued = queue.find(k);
    if (s.complete == s.items) {
      s.state = "done";
    } else if (queued != queue.end()) {
      s.state = queued->second == "RUNNING" ? "running" : (queued->second == "PENDING" ? "pending" : queued->second);
    } else if (fs::exists(exited)) {
      const int code = std::atoi(FirstLine(exited).c_str());
      s.state = code == 143 || code == 130 ? "cancelled"
                : code == 137              ? "killed (exit 137)"
                                           : fmt::format("failed (exit {})", code);
    } else if (fs::exists(started)) {
      s.state = queue_answers ? "lost" : "running";
    } else {
      s.state = "not started";
    }
    status.shard_status.push_back(s);
  }
  status.merged = fs::exists(SynthManifestPath(dir));
  return status;
}

}  // namespace asbuilt
