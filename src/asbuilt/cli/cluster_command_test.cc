// Sharded synthesis end to end with the real binary (issue 41): one process,
// three shards, and a run killed with SIGKILL then resumed all merge into the
// same manifest, byte for byte; a folder made with other options is refused;
// `cluster synth` prints its scripts on a dry run and says how to get sbatch.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/cli/cli_test_util.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;
using testing_util::RunAsbuilt;
using testing_util::RunResult;

constexpr const char* kItems = "--count 6 --seed 5 --size 160x120 --spp 2 --items-per-scene 3";

int TempFiles(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) n += e.path().filename().string()[0] == '.' ? 1 : 0;
  return n;
}

TEST(ClusterCommand, ShardedAndKilledRunsMergeToTheManifestOfOneProcess) {
  const fs::path d = testing_util::FreshTestDir("asbuilt_cli_synth_");
  ASSERT_EQ(RunAsbuilt(fmt::format("dataset synth -o {} {}", (d / "whole").string(), kItems)).exit_code, 0);
  RunResult merged = RunAsbuilt("dataset merge " + (d / "whole").string());
  ASSERT_EQ(merged.exit_code, 0) << merged.out;
  EXPECT_NE(merged.out.find("merged 6 items (30 files"), std::string::npos) << merged.out;
  const std::string manifest = ReadFile(d / "whole" / "synth_manifest.json");

  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(
        RunAsbuilt(fmt::format("dataset synth -o {} {} --shard {}/3", (d / "shards").string(), kItems, k)).exit_code,
        0);
  }
  ASSERT_EQ(RunAsbuilt("dataset merge --shards 3 " + (d / "shards").string()).exit_code, 0);
  EXPECT_EQ(ReadFile(d / "shards" / "synth_manifest.json"), manifest);

  // Killed -9 as soon as its first item is complete, then resumed.
  const fs::path killed = d / "killed";
  const std::string cmd =
      fmt::format("exec {} dataset synth -o {} {} >/dev/null 2>&1", ASBUILT_CLI, killed.string(), kItems);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(killed / "meta" / "000000.json") && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  RunResult early = RunAsbuilt("dataset merge --shards 1 " + killed.string());
  EXPECT_EQ(early.exit_code, 1) << early.out;
  EXPECT_NE(early.out.find("shard 0/1 (items 0-5)"), std::string::npos) << early.out;
  ASSERT_EQ(RunAsbuilt(fmt::format("dataset synth -o {} {} --resume", killed.string(), kItems)).exit_code, 0);
  ASSERT_EQ(RunAsbuilt("dataset merge " + killed.string()).exit_code, 0);
  EXPECT_EQ(ReadFile(killed / "synth_manifest.json"), manifest);
  EXPECT_EQ(TempFiles(killed), 0);
  EXPECT_EQ(RunAsbuilt("dataset verify " + killed.string()).exit_code, 0);

  // Other options into the same folder: refused, nothing touched.
  RunResult other = RunAsbuilt(fmt::format(
      "dataset synth -o {} --count 6 --seed 5 --size 160x120 --spp 3 --items-per-scene 3", (d / "whole").string()));
  EXPECT_EQ(other.exit_code, 1) << other.out;
  EXPECT_NE(other.out.find("options.render: this folder was made with"), std::string::npos) << other.out;
  EXPECT_EQ(RunAsbuilt("dataset verify " + (d / "whole").string()).exit_code, 0);
}

TEST(ClusterCommand, DryRunPrintsTheScriptsAndBadInputIsRefused) {
  const fs::path d = testing_util::FreshTestDir("asbuilt_cli_cluster_");
  RunResult dry = RunAsbuilt(fmt::format(
      "cluster synth -o {} --shards 2 --count 4 --seed 9 --partition short --dry-run", (d / "ds").string()));
  ASSERT_EQ(dry.exit_code, 0) << dry.out;
  EXPECT_NE(dry.out.find("#SBATCH --partition=short"), std::string::npos) << dry.out;
  EXPECT_NE(dry.out.find("export ASBUILT_SHARDS=2\n"), std::string::npos) << dry.out;
  EXPECT_NE(dry.out.find("export ASBUILT_ARGS='--count 4 --seed 9 --width-px 320 --height-px 240 "), std::string::npos)
      << dry.out;
  EXPECT_NE(dry.out.find("$ASBUILT\" dataset merge"), std::string::npos) << dry.out;
  EXPECT_FALSE(fs::exists(d / "ds")) << "a dry run writes nothing";

  RunResult many = RunAsbuilt(fmt::format("cluster synth -o {} --shards 5 --count 4", (d / "ds").string()));
  EXPECT_EQ(many.exit_code, 2) << many.out;
  EXPECT_NE(many.out.find("5 shards over 4 items"), std::string::npos) << many.out;

  const std::string no_sbatch = fmt::format("PATH=/nonexistent {} cluster synth -o {} --shards 2 --count 4 2>&1",
                                            ASBUILT_CLI, (d / "ds").string());
  std::FILE* pipe = ::popen(no_sbatch.c_str(), "r");
  std::string out;
  char buffer[4096];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  EXPECT_NE(::pclose(pipe), 0);
  EXPECT_NE(out.find("sbatch: not found on PATH"), std::string::npos) << out;
  EXPECT_NE(out.find("--dry-run"), std::string::npos) << out;

  RunResult train = RunAsbuilt(
      fmt::format("cluster train -o {} --tasks 2 --images {} --batchh 4 --dry-run", (d / "run").string(), d.string()));
  EXPECT_EQ(train.exit_code, 2) << train.out;
  EXPECT_NE(train.out.find("the training flags: The following arguments were not expected"), std::string::npos)
      << train.out;
  RunResult odd = RunAsbuilt(
      fmt::format("cluster train -o {} --tasks 2 --images {} --batch 3 --dry-run", (d / "run").string(), d.string()));
  EXPECT_EQ(odd.exit_code, 2) << odd.out;
  EXPECT_NE(odd.out.find("must be divisible by the 2 ranks"), std::string::npos) << odd.out;
  RunResult own = RunAsbuilt(
      fmt::format("cluster train -o {} --tasks 2 --images {} --distributed", (d / "run").string(), d.string()));
  EXPECT_EQ(own.exit_code, 2) << own.out;
  EXPECT_FALSE(fs::exists(d / "run"));

  RunResult status = RunAsbuilt("cluster status " + (d / "nothing").string());
  EXPECT_EQ(status.exit_code, 1) << status.out;
  EXPECT_NE(status.out.find("job.json: not found"), std::string::npos) << status.out;
}

TEST(EvalCommand, ShardsMergeToTheMetricsOfOneProcessExactly) {
  const fs::path d = testing_util::FreshTestDir("asbuilt_cli_eval_shards_");
  const fs::path toy = d / "toy";
  ASSERT_EQ(
      RunAsbuilt(fmt::format("experiment toy-rooms -o {} --count 7 --width 48 --height 32 --seed 5", toy.string()))
          .exit_code,
      0);
  RunResult whole = RunAsbuilt(
      fmt::format("eval seg --model default --images {} --json {}", toy.string(), (d / "whole.json").string()));
  if (whole.out.find("no LibTorch") != std::string::npos) GTEST_SKIP() << "this build has no LibTorch";
  ASSERT_EQ(whole.exit_code, 0) << whole.out;
  for (int k : {0, 2}) {
    RunResult r =
        RunAsbuilt(fmt::format("eval seg --model default --images {} --shard {}/3 --json {}/shards/{}-of-3.json",
                               toy.string(), k, d.string(), k));
    ASSERT_EQ(r.exit_code, 0) << r.out;
  }
  RunResult early = RunAsbuilt(fmt::format("eval merge {} --shards 3", d.string()));
  EXPECT_EQ(early.exit_code, 1) << early.out;
  EXPECT_NE(early.out.find("shard(s) 1 of 3 missing"), std::string::npos) << early.out;
  ASSERT_EQ(RunAsbuilt(fmt::format("eval seg --model default --images {} --shard 1/3 --json {}/shards/1-of-3.json",
                                   toy.string(), d.string()))
                .exit_code,
            0);
  RunResult merged = RunAsbuilt(fmt::format("eval merge {} --shards 3", d.string()));
  ASSERT_EQ(merged.exit_code, 0) << merged.out;
  EXPECT_EQ(ReadFile(d / "metrics.json"), ReadFile(d / "whole.json")) << "summed confusion matrices, exactly";

  RunResult other = RunAsbuilt(fmt::format("eval merge {} --shards 2", d.string()));
  EXPECT_EQ(other.exit_code, 1) << other.out;
  RunResult many = RunAsbuilt(fmt::format("eval seg --model default --images {} --shard 0/8", toy.string()));
  EXPECT_EQ(many.exit_code, 2) << many.out;
  EXPECT_NE(many.out.find("8 shards over 7 items"), std::string::npos) << many.out;
}

}  // namespace
}  // namespace asbuilt
