#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/cluster/slurm.h"
#include "asbuilt/cluster/cluster_job.h"
#include "asbuilt/formats/synth_dataset.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/shard.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("asbuilt_cluster_{}_{}", name, ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void WriteExecutable(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  fs::permissions(path, fs::perms::owner_all);
}

// Every file of item i, as a finished synth leaves it.
void MakeItem(const fs::path& dir, int i) {
  for (const fs::path& file : SynthItemFiles(dir, i)) {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << "x";
  }
}

// A fake sbatch that logs its arguments and answers job ids 100, 101, …
SlurmOptions FakeSlurm(const fs::path& bin, const std::string& squeue_output = "") {
  fs::create_directories(bin);
  WriteExecutable(bin / "sbatch", fmt::format("#!/bin/sh\necho \"$@\" >> {0}/sbatch.log\n"
                                              "n=$(wc -l < {0}/sbatch.log)\necho $((99 + n))\n",
                                              bin.string()));
  WriteExecutable(bin / "squeue", "#!/bin/sh\nprintf '" + squeue_output + "'\n");
  return {.sbatch = (bin / "sbatch").string(), .squeue = (bin / "squeue").string()};
}

ClusterRequest Request(const fs::path& dir, const SlurmOptions& slurm) {
  return {.kind = ClusterJobKind::kSynth,
          .dir = dir,
          .shards = 4,
          .count = 8,
          .record = {{"count", 8}, {"seed", 7}},
          .args = {"--count", "8", "--seed", "7", "--photo-dir", "/photos/with space"},
          .asbuilt = "/opt/asbuilt",
          .slurm = slurm};
}

TEST(MakeBatchScript, ReplacesTheTemplatesDirectivesAndSetsItsVariables) {
  const std::string script = MakeBatchScript(SlurmTemplate("synth"), {"--job-name=x", "--partition=gpu"},
                                             {{"ASBUILT_OUT", "/data/it's here"}});
  EXPECT_EQ(script.rfind("#!/bin/bash\n#SBATCH --job-name=x\n#SBATCH --partition=gpu\n", 0), 0u) << script;
  EXPECT_EQ(script.find("#SBATCH --output=asbuilt-synth"), std::string::npos) << "the template's own directive";
  EXPECT_NE(script.find("export ASBUILT_OUT='/data/it'\\''s here'\n"), std::string::npos) << script;
  EXPECT_EQ(ShellQuote("--count"), "--count");
  EXPECT_EQ(ShellQuote(""), "''");
  EXPECT_NE(script.find("dataset synth -o \"$ASBUILT_OUT\" --shard \"$task/$ASBUILT_SHARDS\""), std::string::npos);
  EXPECT_THROW(SlurmTemplate("render"), InvalidArgument);
  EXPECT_NE(SlurmTemplate("eval").find("eval seg"), std::string_view::npos);
}

TEST(SynthBatchScript, RunsItsShardWithTheArgumentsAsGivenAndLeavesItsExitStatus) {
  const fs::path dir = FreshDir("script");
  const fs::path bin = dir / "bin";
  fs::create_directories(bin);
  // A stand-in asbuilt: one argument per line, then fails when asked to.
  WriteExecutable(bin / "asbuilt", fmt::format("#!/bin/sh\nfor a in \"$@\"; do echo \"$a\"; done > {}/args\n"
                                               "exit ${{FAKE_EXIT:-0}}\n",
                                               dir.string()));
  ClusterSubmission r = SubmitClusterJob([&] {
    ClusterRequest q = Request(dir / "ds", {});
    q.asbuilt = bin / "asbuilt";
    q.dry_run = true;
    return q;
  }());
  EXPECT_FALSE(fs::exists(dir / "ds" / "synth.json")) << "a dry run writes nothing";
  WriteExecutable(dir / "synth.sbatch", r.task_script);
  ASSERT_EQ(std::system(fmt::format("SLURM_ARRAY_TASK_ID=2 bash {}/synth.sbatch", dir.string()).c_str()), 0);
  EXPECT_EQ(ReadFile(dir / "args"), fmt::format("dataset\nsynth\n-o\n{}\n--shard\n2/4\n--count\n8\n--seed\n7\n"
                                                "--photo-dir\n/photos/with space\n",
                                                fs::absolute(dir / "ds").string()));
  EXPECT_EQ(ReadFile(dir / "ds" / "cluster" / "synth" / "2.exit"), "0\n");
  EXPECT_TRUE(fs::exists(dir / "ds" / "cluster" / "synth" / "2.started"));
  EXPECT_NE(std::system(fmt::format("FAKE_EXIT=3 SLURM_ARRAY_TASK_ID=1 bash {}/synth.sbatch", dir.string()).c_str()),
            0);
  EXPECT_EQ(ReadFile(dir / "ds" / "cluster" / "synth" / "1.exit"), "3\n");
}

TEST(SubmitClusterJob, SubmitsTheArrayThenTheMergeAfterItAndResumesOnlyWhatIsUnfinished) {
  const fs::path dir = FreshDir("submit");
  const SlurmOptions slurm = FakeSlurm(dir / "bin");
  ClusterSubmission first = SubmitClusterJob(Request(dir / "ds", slurm));
  EXPECT_EQ(first.array_job, "100");
  EXPECT_EQ(first.merge_job, "101");
  EXPECT_EQ(first.tasks, (std::vector<int>{0, 1, 2, 3}));
  const fs::path ds = fs::absolute(dir / "ds");
  EXPECT_EQ(ReadFile(dir / "bin" / "sbatch.log"),
            fmt::format("--parsable --array=0-3 {0}/cluster/synth.sbatch\n"
                        "--parsable --dependency=afterany:100 {0}/cluster/synth-merge.sbatch\n",
                        ds.string()));
  EXPECT_EQ(ReadSynthRecord(ds), (nlohmann::json{{"count", 8}, {"seed", 7}}));

  try {
    SubmitClusterJob(Request(dir / "ds", slurm));
    FAIL() << "a second run on the same folder without --resume";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--resume"), std::string::npos) << e.what();
  }
  for (int i : {0, 1, 2, 3, 6, 7}) MakeItem(ds, i);  // Shards 0, 1 and 3 complete.
  ClusterRequest resume = Request(dir / "ds", slurm);
  resume.resume = true;
  ClusterSubmission second = SubmitClusterJob(resume);
  EXPECT_EQ(second.tasks, (std::vector<int>{2}));
  EXPECT_NE(ReadFile(dir / "bin" / "sbatch.log").find("--parsable --array=2 "), std::string::npos);
  resume.shards = 2;
  EXPECT_THROW(SubmitClusterJob(resume), InputError);
}

TEST(SubmitClusterJob, RefusesAFolderMadeWithOtherOptionsAndWritesNothing) {
  const fs::path dir = FreshDir("other");
  ClaimSynthDir(dir / "ds", {{"count", 8}, {"seed", 6}});
  const std::string before = ReadFile(dir / "ds" / "synth.json");
  try {
    SubmitClusterJob(Request(dir / "ds", FakeSlurm(dir / "bin")));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("options.seed: this folder was made with 6, this run asks for 7"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(ReadFile(dir / "ds" / "synth.json"), before);
  EXPECT_FALSE(fs::exists(dir / "ds" / "cluster"));
  EXPECT_FALSE(fs::exists(dir / "bin" / "sbatch.log"));
}

TEST(SubmitClusterJob, SaysHowToGetSbatchWhenItIsMissingAndRefusesMoreShardsThanItems) {
  const fs::path dir = FreshDir("nosbatch");
  try {
    SubmitClusterJob(Request(dir / "ds", {.sbatch = "asbuilt-no-such-sbatch"}));
    FAIL() << "expected Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--dry-run"), std::string::npos) << e.what();
  }
  ClusterRequest q = Request(dir / "ds2", {});
  q.shards = 9;
  EXPECT_THROW(SubmitClusterJob(q), InvalidArgument);
  q.shards = 0;
  EXPECT_THROW(SubmitClusterJob(q), InvalidArgument);
}

TEST(ReadClusterStatus, TellsEachShardsStateFromTheFilesAndTheQueue) {
  const fs::path dir = FreshDir("status");
  const SlurmOptions slurm = FakeSlurm(dir / "bin", "100_3 PENDING\\n");
  SubmitClusterJob(Request(dir / "ds", slurm));
  const fs::path ds = fs::absolute(dir / "ds");
  for (int i : {0, 1, 2}) MakeItem(ds, i);  // Shard 0 done, shard 1 half.
  const fs::path state = ds / "cluster" / "synth";
  fs::create_directories(state);
  std::ofstream(state / "1.started") << "node7 100 0\n";
  std::ofstream(state / "1.exit") << "1\n";
  std::ofstream(state / "2.started") << "node8 100 0\n";
  ClusterStatus s = ReadClusterStatus(ds, slurm);
  ASSERT_EQ(s.shard_status.size(), 4u);
  EXPECT_EQ(s.shard_status[0].state, "done");
  EXPECT_EQ(s.shard_status[1].state, "failed (exit 1)");
  EXPECT_EQ(s.shard_status[1].complete, 1);
  EXPECT_EQ(s.shard_status[1].host, "node7");
  EXPECT_EQ(s.shard_status[2].state, "lost") << "started, no exit, not in the queue";
  EXPECT_EQ(s.shard_status[3].state, "pending");
  EXPECT_FALSE(s.all_done());
  EXPECT_NE(s.Table().find("--resume"), std::string::npos) << s.Table();
  EXPECT_NE(s.Table().find("items complete: 3 of 8"), std::string::npos) << s.Table();
  EXPECT_NE(s.Table().find("shards done: 1 of 4"), std::string::npos) << s.Table();
  EXPECT_THROW(ReadClusterStatus(dir / "nothing", slurm), InputError);
}

TEST(ReadClusterStatus, CountsAnEvalShardDoneWhenItsMetricsAreThere) {
  const fs::path dir = FreshDir("eval");
  const SlurmOptions slurm = FakeSlurm(dir / "bin");
  ClusterSubmission r = SubmitClusterJob({.kind = ClusterJobKind::kEval,
                                          .dir = dir / "ev",
                                          .shards = 2,
                                          .count = 5,
                                          .args = {"--model", "default", "--images", "/data/x"},
                                          .slurm = slurm});
  EXPECT_NE(r.task_script.find("export ASBUILT_ARGS='--model default --images /data/x'"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "ev" / "cluster" / "eval.sbatch"));
  EXPECT_FALSE(fs::exists(dir / "ev" / "synth.json")) << "an eval claims no dataset";
  fs::create_directories(dir / "ev" / "shards");
  std::ofstream(EvalShardPath(dir / "ev", 1, 2)) << "{}";
  ClusterStatus s = ReadClusterStatus(fs::absolute(dir / "ev"), slurm);
  EXPECT_EQ(s.kind, ClusterJobKind::kEval);
  EXPECT_EQ(s.shard_status[0].state, "not started") << "no file, never started, not queued";
  EXPECT_EQ(s.shard_status[1].state, "done");
  EXPECT_FALSE(s.merged);
  std::ofstream(dir / "ev" / "metrics.json") << "{}";
  EXPECT_TRUE(ReadClusterStatus(fs::absolute(dir / "ev"), slurm).merged);
}

TEST(SubmitClusterJob, SubmitsATrainingRunAsOneJobOfKTasksAndReadsItsEpochs) {
  const fs::path dir = FreshDir("train");
  const SlurmOptions slurm = FakeSlurm(dir / "bin");
  const ClusterRequest request = {.kind = ClusterJobKind::kTrain,
                                  .dir = dir / "run",
                                  .shards = 3,
                                  .args = {"--images", "/data/toy", "--batch", "6"},
                                  .slurm = slurm};
  ClusterSubmission r = SubmitClusterJob(request);
  EXPECT_EQ(r.array_job, "100");
  EXPECT_TRUE(r.merge_job.empty());
  EXPECT_NE(r.task_script.find("#SBATCH --ntasks=3\n"), std::string::npos) << r.task_script;
  EXPECT_NE(r.task_script.find("srun --kill-on-bad-exit=1 \"$ASBUILT\" train -o \"$ASBUILT_OUT\""), std::string::npos);
  EXPECT_EQ(ReadFile(dir / "bin" / "sbatch.log"),
            fmt::format("--parsable {}/cluster/train.sbatch\n", fs::absolute(dir / "run").string()));
  EXPECT_THROW(SubmitClusterJob(request), InputError) << "a second run needs --resume";
  std::ofstream(dir / "run" / "log.csv") << "epoch,train_loss\n1,0.5\n2,0.4\n";
  ClusterStatus s = ReadClusterStatus(fs::absolute(dir / "run"), slurm);
  EXPECT_EQ(s.kind, ClusterJobKind::kTrain);
  EXPECT_EQ(s.epochs_done, 2);
  EXPECT_NE(s.Table().find("job 100: not in the queue\nepochs done: 2"), std::string::npos) << s.Table();
  ClusterRequest resume = request;
  resume.resume = true;
  EXPECT_EQ(SubmitClusterJob(resume).array_job, "101");
  std::optional<ClusterRunRecord> run = ReadClusterRun(dir / "run");
  ASSERT_TRUE(run.has_value());
  EXPECT_EQ(run->shards, 3);
  EXPECT_EQ(run->args, request.args);
}

}  // namespace
}  // namespace asbuilt
