// kill -9 and resume for `asbuilt train` (issue #10): a run killed with
// SIGKILL after a checkpoint resumes from that checkpoint, leaves no corrupt
// checkpoint, loses no finished epoch and redoes none, and finishes leaving no
// temp file (a temp file the kill interrupted is removed by the resume).

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/cli/cli_test_util.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;
using testing_util::RunAsbuilt;

// log.csv rows after the header (one per finished epoch).
std::vector<std::string> LogRows(const fs::path& run) {
  std::ifstream in(run / "log.csv");
  std::vector<std::string> rows;
  std::string line;
  std::getline(in, line);  // Header.
  while (std::getline(in, line)) {
    if (!line.empty()) rows.push_back(line);
  }
  return rows;
}

// The columns of a log row that must not change when an epoch is not redone:
// epoch, step, lr, train_loss, validation scores (wall_s is the last column).
std::string Deterministic(const std::string& row) { return row.substr(0, row.rfind(',')); }

std::vector<std::string> TempFiles(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    std::string name = e.path().filename().string();
    if (name.find(".tmp") != std::string::npos || (name[0] == '.' && name != ".")) out.push_back(name);
  }
  return out;
}

pid_t Spawn(const std::string& args, const fs::path& log) {
  std::string cmd = fmt::format("exec {} {} >{} 2>&1 </dev/null", ASBUILT_CLI, args, log.string());
  pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

TEST(TrainKill, ResumesAfterSigkillWithoutLosingOrRedoingEpochs) {
  if (RunAsbuilt("train --images /nonexistent -o /nonexistent").out.find("no LibTorch") != std::string::npos) {
    GTEST_SKIP() << "this build has no LibTorch";
  }
  fs::path d = testing_util::FreshTestDir("asbuilt_train_kill_");
  auto r = RunAsbuilt(
      fmt::format("experiment toy-rooms -o {} --count 10 --width 48 --height 32 --seed 5", (d / "toy").string()));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const int epochs = 8;
  const fs::path run = d / "run";
  const std::string args = fmt::format(
      "train --images {} -o {} --arch tiny --epochs {} --steps-per-epoch 6 --batch 2 --scale 48x32 "
      "--crop 48x32 --lr 2e-3 --val-fraction 0.2 --seed 3 --threads 1 --no-photometric "
      "--no-blur-noise -q",
      (d / "toy").string(), run.string(), epochs);

  // Kill twice: once right after the first checkpoint appears, once a little
  // later (possibly while a checkpoint is being written).
  std::vector<std::string> rows_at_kill;
  for (int kill = 0; kill < 2; ++kill) {
    std::size_t rows_before = LogRows(run).size();
    pid_t pid = Spawn(args, d / fmt::format("train{}.log", kill));
    ASSERT_GT(pid, 0);
    auto start = std::chrono::steady_clock::now();
    bool progressed = false;
    while (std::chrono::steady_clock::now() - start < std::chrono::seconds(60)) {
      if (LogRows(run).size() > rows_before) {
        progressed = true;
        break;
      }
      int status;
      if (::waitpid(pid, &status, WNOHANG) == pid) FAIL() << "train ended before the kill";
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (kill == 1) std::this_thread::sleep_for(std::chrono::milliseconds(150));
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(progressed) << "no epoch finished within 60 s";
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "train finished before it was killed";
    rows_at_kill = LogRows(run);
    ASSERT_LT(rows_at_kill.size(), static_cast<std::size_t>(epochs)) << "killed too late to test a resume";
    // A kill in the middle of a write may leave that write's temp file (no
    // process can clean up after SIGKILL), but nothing else: no stray file and
    // no half-written checkpoint. The resumed run removes such temp files.
    for (const std::string& name : TempFiles(run)) {
      EXPECT_TRUE(IsAtomicTempName(name)) << name << " is not an atomic-write temp file";
    }
    for (const char* ckpt : {"last.pt", "best.pt"}) {
      auto seg = RunAsbuilt(fmt::format("segment --model {} {} -o {}", (run / ckpt).string(),
                                        (d / "toy" / "images").string(), (d / "seg").string()));
      EXPECT_EQ(seg.exit_code, 0) << ckpt << " does not load after kill " << kill << ":\n" << seg.out;
    }
  }

  // Resume and finish.
  auto resumed = RunAsbuilt(args);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.out;
  // It resumed from the last checkpoint: at least every epoch logged before the kill.
  int from = -1;
  auto at = resumed.out.find("resumed after epoch ");
  ASSERT_NE(at, std::string::npos) << resumed.out;
  from = std::stoi(resumed.out.substr(at + 20));
  EXPECT_GE(from, static_cast<int>(rows_at_kill.size())) << "an epoch finished before the kill was lost";
  EXPECT_NE(resumed.out.find(fmt::format("{} epochs", epochs)), std::string::npos) << resumed.out;

  // One row per epoch, 1..epochs, and the epochs done before the kill are kept as they were.
  std::vector<std::string> rows = LogRows(run);
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(epochs));
  for (int e = 0; e < epochs; ++e) EXPECT_EQ(rows[e].substr(0, rows[e].find(',')), std::to_string(e + 1));
  for (std::size_t e = 0; e < rows_at_kill.size(); ++e) {
    EXPECT_EQ(Deterministic(rows[e]), Deterministic(rows_at_kill[e])) << "epoch " << e + 1 << " changed";
  }
  EXPECT_TRUE(TempFiles(run).empty()) << ::testing::PrintToString(TempFiles(run));
  auto seg = RunAsbuilt(fmt::format("segment --model {} {} -o {}", (run / "last.pt").string(),
                                    (d / "toy" / "images").string(), (d / "seg").string()));
  EXPECT_EQ(seg.exit_code, 0) << seg.out;
  if (!HasFailure()) fs::remove_all(d);
}

}  // namespace
}  // namespace asbuilt
