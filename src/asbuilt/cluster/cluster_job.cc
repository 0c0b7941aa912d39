#include "asbuilt/cluster/cluster_job.h"

#include <chrono>
#include <ctime>
#include <fstream>
#include <algorithm>
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

ClusterJobKind KindFromName(const std::string& name, const fs::path& file) {
  if (name == "synth") return ClusterJobKind::kSynth;
  if (name == "eval") return ClusterJobKind::kEval;
  if (name == "train") return ClusterJobKind::kTrain;
  throw InputError(file.string(), "kind", fmt::format("expected \"synth\", \"eval\" or \"train\", got \"{}\"", name));
}

nlohmann::json ReadJobRecord(const fs::path& dir) {
  const fs::path path = JobRecordPath(dir);
  JsonDiagnostics diag(path.string());
  nlohmann::json record = ParseJsonFile(path, diag);
  diag.ThrowIfErrors();
  if (!record.is_object() || !record.contains("kind") || !record["kind"].is_string() || !record.contains("shards") ||
      !record["shards"].is_number_integer() || !record.contains("count") || !record["count"].is_number_integer()) {
    throw InputError(path.string(), "", "not an asbuilt cluster run record (kind, shards, count)");
  }
  KindFromName(record["kind"].get<std::string>(), path);
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

// Shard k's finished units and how many it has: complete items (synth), or
// its one result file (eval).
std::pair<int, int> ShardProgress(ClusterJobKind kind, const fs::path& dir, int count, int k, int shards) {
  if (kind == ClusterJobKind::kEval) return {fs::exists(EvalShardPath(dir, k, shards)) ? 1 : 0, 1};
  auto [begin, end] = ShardRange(count, k, shards);
  int complete = 0;
  for (int i = begin; i < end; ++i) complete += IsSynthItemComplete(dir, i) ? 1 : 0;
  return {complete, end - begin};
}

fs::path MergedPath(ClusterJobKind kind, const fs::path& dir) {
  if (kind == ClusterJobKind::kTrain) return dir / "last.pt";
  return kind == ClusterJobKind::kSynth ? SynthManifestPath(dir) : dir / "metrics.json";
}

// A training run's rows of log.csv (one per finished epoch, after a header).
int EpochsDone(const fs::path& dir) {
  std::ifstream in(dir / "log.csv");
  std::string line;
  int rows = -1;
  while (std::getline(in, line)) rows += line.empty() ? 0 : 1;
  return std::max(rows, 0);
}

// One job of `request.shards` tasks, one rank each (no array, no merge).
ClusterSubmission SubmitTrainJob(const ClusterRequest& request, const fs::path& dir, nlohmann::json& job,
                                 const std::vector<std::pair<std::string, std::string>>& variables) {
  ClusterSubmission result;
  std::vector<std::string> directives =
      SlurmDirectives(request.slurm, "asbuilt-train", dir / "cluster" / "logs" / "train-%j.out");
  directives.push_back(fmt::format("--ntasks={}", request.shards));
  result.task_script = MakeBatchScript(SlurmTemplate("train"), directives, variables);
  if (request.dry_run) return result;
  fs::create_directories(dir / "cluster" / "logs");
  WriteFileAtomic(dir / "cluster" / "train.sbatch", result.task_script);
  result.array_job = SubmitBatch(request.slurm, {}, dir / "cluster" / "train.sbatch");
  for (int k = 0; k < request.shards; ++k) result.tasks.push_back(k);
  job["submissions"].push_back({{"time", NowUtc()}, {"job", result.array_job}});
  WriteFileAtomic(JobRecordPath(dir), job.dump(1) + "\n");
  return result;
}

std::string MergeCommand(ClusterJobKind kind, const fs::path& dir, int shards) {
  return fmt::format("asbuilt {} merge {} --shards {}", kind == ClusterJobKind::kSynth ? "dataset" : "eval",
                     dir.string(), shards);
}

}  // namespace

const char* ClusterJobKindName(ClusterJobKind kind) {
  switch (kind) {
    case ClusterJobKind::kSynth:
      return "synth";
    case ClusterJobKind::kEval:
      return "eval";
    case ClusterJobKind::kTrain:
      break;
  }
  return "train";
}

fs::path EvalShardPath(const fs::path& dir, int index, int shards) {
  return dir / "shards" / fmt::format("{}-of-{}.json", index, shards);
}

void ClusterRequest::Check() const {
  CheckArgument(!dir.empty(), "ClusterRequest.dir is empty");
  if (kind == ClusterJobKind::kTrain) {
    CheckArgument(shards >= 1, fmt::format("{} tasks: need at least 1", shards));
  } else {
    CheckArgument(count >= 1, fmt::format("ClusterRequest.count = {}, must be >= 1", count));
    CheckShardCount(shards, count);
  }
  slurm.Check();
}

std::string ClusterSubmission::BriefReport(const fs::path& dir) const {
  if (array_job.empty() && merge_job.empty()) return "dry run: nothing written, nothing submitted";
  if (merge_job.empty()) {
    return fmt::format("submitted job {} ({} tasks, one rank each).\nprogress: asbuilt cluster status {}", array_job,
                       tasks.size(), dir.string());
  }
  std::string text = tasks.empty() ? "every shard is done; "
                                   : fmt::format("submitted {} task(s) as job {}; ", tasks.size(), array_job);
  return text +
         fmt::format("merge job {} runs after them.\nprogress: asbuilt cluster status {}", merge_job, dir.string());
}

ClusterSubmission SubmitClusterJob(const ClusterRequest& request) {
  request.Check();
  const fs::path dir = fs::absolute(request.dir);
  const fs::path cluster = dir / "cluster";
  const std::string kind = ClusterJobKindName(request.kind);
  nlohmann::json job = {{"version", 1},           {"kind", kind},         {"shards", request.shards},
                        {"count", request.count}, {"args", request.args}, {"submissions", nlohmann::json::array()}};
  if (fs::exists(JobRecordPath(dir))) {
    if (!request.resume) {
      throw InputError(JobRecordPath(dir).string(), "",
                       fmt::format("{} already has a cluster run: see `asbuilt cluster status {}`, and add --resume "
                                   "to submit its unfinished shards",
                                   dir.string(), dir.string()));
    }
    job = ReadJobRecord(dir);
    if (job["kind"] != kind || job["shards"].get<int>() != request.shards) {
      throw InputError(JobRecordPath(dir).string(), "",
                       fmt::format("this folder's run is a {} of {} shards; resume it as one", job["kind"].dump(),
                                   job["shards"].get<int>()));
    }
  }
  if (request.kind == ClusterJobKind::kSynth) {
    request.dry_run ? CheckSynthDir(dir, request.record) : ClaimSynthDir(dir, request.record);
  }

  ClusterSubmission result;
  for (int k = 0; k < request.shards && request.kind != ClusterJobKind::kTrain; ++k) {
    auto [done, units] = ShardProgress(request.kind, dir, request.count, k, request.shards);
    if (!request.resume || done < units) result.tasks.push_back(k);
  }
  std::vector<std::string> words;
  for (const std::string& a : request.args) words.push_back(ShellQuote(a));
  std::vector<std::pair<std::string, std::string>> variables = {
      {"ASBUILT", request.asbuilt.string()},
      {"ASBUILT_OUT", dir.string()},
      {"ASBUILT_ARGS", fmt::format("{}", fmt::join(words, " "))}};
  if (request.kind == ClusterJobKind::kTrain) return SubmitTrainJob(request, dir, job, variables);
  variables.emplace_back("ASBUILT_SHARDS", std::to_string(request.shards));
  result.task_script = MakeBatchScript(
      SlurmTemplate(kind), SlurmDirectives(request.slurm, "asbuilt-" + kind, cluster / "logs" / (kind + "-%A_%a.out")),
      variables);
  result.merge_script = MakeBatchScript(
      SlurmTemplate(kind + "-merge"),
      SlurmDirectives(request.slurm, "asbuilt-" + kind + "-merge", cluster / "logs" / (kind + "-merge-%j.out")),
      variables);
  if (request.dry_run) return result;

  fs::create_directories(cluster / "logs");
  const fs::path task_script = cluster / (kind + ".sbatch"), merge_script = cluster / (kind + "-merge.sbatch");
  WriteFileAtomic(task_script, result.task_script);
  WriteFileAtomic(merge_script, result.merge_script);
  nlohmann::json submission = {{"time", NowUtc()}, {"tasks", result.tasks}};
  if (!result.tasks.empty()) {
    result.array_job = SubmitBatch(request.slurm, {"--array=" + ArraySpec(result.tasks, request.shards)}, task_script);
    submission["array_job"] = result.array_job;
  }
  std::vector<std::string> merge_args;
  if (!result.array_job.empty()) merge_args.push_back("--dependency=afterany:" + result.array_job);
  result.merge_job = SubmitBatch(request.slurm, merge_args, merge_script);
  submission["merge_job"] = result.merge_job;
  job["submissions"].push_back(submission);
  WriteFileAtomic(JobRecordPath(dir), job.dump(1) + "\n");
  return result;
}

std::optional<ClusterRunRecord> ReadClusterRun(const fs::path& dir) {
  if (!fs::exists(JobRecordPath(dir))) return std::nullopt;
  const nlohmann::json job = ReadJobRecord(dir);
  ClusterRunRecord run{.kind = KindFromName(job["kind"].get<std::string>(), JobRecordPath(dir)),
                       .shards = job["shards"].get<int>(),
                       .count = job["count"].get<int>()};
  if (job.contains("args") && job["args"].is_array()) {
    for (const nlohmann::json& a : job["args"]) {
      if (a.is_string()) run.args.push_back(a.get<std::string>());
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
  if (kind == ClusterJobKind::kTrain) {
    return fmt::format("{}: train, {} tasks (one rank each), job {}: {}\nepochs done: {}{}\n", dir.string(), shards,
                       array_job.empty() ? "-" : array_job, job_state.empty() ? "not in the queue" : job_state,
                       epochs_done, merged ? fmt::format(" (checkpoint {})", MergedPath(kind, dir).string()) : "");
  }
  const bool synth = kind == ClusterJobKind::kSynth;
  std::string text = fmt::format("{}: {} of {} {} in {} shards (array job {}, merge job {})\n", dir.string(),
                                 ClusterJobKindName(kind), count, synth ? "items" : "images", shards,
                                 array_job.empty() ? "-" : array_job, merge_job.empty() ? "-" : merge_job);
  text +=
      fmt::format("{:>5}  {:>13}  {:>10}  {:<22} {}\n", "shard", synth ? "items" : "images", "done", "state", "host");
  int complete = 0;
  for (const ShardStatus& s : shard_status) {
    auto [begin, end] = ShardRange(count, s.index, shards);
    text += fmt::format("{:>5}  {:>13}  {:>10}  {:<22} {}\n", s.index, fmt::format("{}-{}", begin, end - 1),
                        fmt::format("{}/{}", s.complete, s.items), s.state, s.host);
    complete += s.state == "done" ? 1 : 0;
  }
  if (synth) {
    int items = 0;
    for (const ShardStatus& s : shard_status) items += s.complete;
    text += fmt::format("items complete: {} of {} ({:.1f} %)\n", items, count, 100.0 * items / count);
  }
  text += fmt::format("shards done: {} of {}\n", complete, shards);
  if (merged) {
    text += "merged: " + MergedPath(kind, dir).string() + "\n";
  } else if (all_done()) {
    text += "every shard is done; not merged yet: " + MergeCommand(kind, dir, shards) + "\n";
  } else {
    bool stuck = false;
    for (const ShardStatus& s : shard_status) {
      stuck = stuck || s.state.rfind("failed", 0) == 0 || s.state.rfind("killed", 0) == 0 || s.state == "cancelled" ||
              s.state == "lost";
    }
    if (stuck) {
      text += fmt::format("to finish the stopped shards: asbuilt cluster {} -o {} --resume\n", ClusterJobKindName(kind),
                          dir.string());
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
  nlohmann::json j = {
      {"dir", dir.string()}, {"kind", ClusterJobKindName(kind)}, {"count", count},        {"shards", shards_json},
      {"merged", merged},    {"array_job", array_job},           {"merge_job", merge_job}};
  if (kind == ClusterJobKind::kTrain) {
    j["tasks"] = shards;
    j["job_state"] = job_state;
    j["epochs_done"] = epochs_done;
  }
  return j;
}

ClusterStatus ReadClusterStatus(const fs::path& dir, const SlurmOptions& slurm) {
  if (!fs::exists(JobRecordPath(dir))) {
    throw InputError(JobRecordPath(dir).string(), "",
                     "not found: this folder has no cluster run (asbuilt cluster synth|eval -o DIR ...)");
  }
  const nlohmann::json job = ReadJobRecord(dir);
  ClusterStatus status;
  status.dir = dir;
  status.kind = KindFromName(job["kind"].get<std::string>(), JobRecordPath(dir));
  status.shards = job["shards"].get<int>();
  status.count = job["count"].get<int>();
  if (job.contains("submissions") && job["submissions"].is_array() && !job["submissions"].empty()) {
    const nlohmann::json& last = job["submissions"].back();
    status.array_job = last.value("array_job", "");
    status.merge_job = last.value("merge_job", "");
  }
  if (status.kind == ClusterJobKind::kTrain) {
    if (job.contains("submissions") && !job["submissions"].empty()) {
      status.array_job = job["submissions"].back().value("job", "");
    }
    status.job_state = JobState(slurm, status.array_job);
    status.epochs_done = EpochsDone(dir);
    status.merged = fs::exists(MergedPath(status.kind, dir));
    return status;
  }
  // The queue's word on the latest array job; an earlier submission's tasks have ended.
  const std::map<int, std::string> queue = ArrayTaskStates(slurm, status.array_job);
  const bool queue_answers = !FindProgram(slurm.squeue).empty() && !status.array_job.empty();
  const fs::path state_dir = dir / "cluster" / ClusterJobKindName(status.kind);
  for (int k = 0; k < status.shards; ++k) {
    ShardStatus s{.index = k};
    std::tie(s.complete, s.items) = ShardProgress(status.kind, dir, status.count, k, status.shards);
    const fs::path started = state_dir / fmt::format("{}.started", k);
    const fs::path exited = state_dir / fmt::format("{}.exit", k);
    if (fs::exists(started)) {
      const std::string line = FirstLine(started);
      s.host = line.substr(0, line.find(' '));
    }
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
  status.merged = fs::exists(MergedPath(status.kind, dir));
  return status;
}

}  // namespace asbuilt
