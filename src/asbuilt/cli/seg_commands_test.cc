// CLI tests of `asbuilt train`, `segment`, `eval seg` and `experiment`
// on tiny toy-room sets (seconds, one thread).

#include <unistd.h>

#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/cli/cli_test_util.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;
using testing_util::RunAsbuilt;

fs::path SegTempDir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / fmt::format("asbuilt_cli_seg_{}_{}", name, ::getpid());
  fs::remove_all(d);
  return d;
}

TEST(SegCommands, TrainSegmentAndEvaluateToyRooms) {
  fs::path d = SegTempDir("flow");
  auto r = RunAsbuilt(
      fmt::format("experiment toy-rooms -o {} --count 8 --width 64 --height 48 --seed 2", (d / "toy").string()));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  r =
      RunAsbuilt(fmt::format("train --images {} -o {} --arch tiny --epochs 2 --steps-per-epoch 3 --scale 64x48 "
                             "--crop 48x48 --threads 1 --lr 1e-3",
                             (d / "toy").string(), (d / "run").string()));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("2 epochs"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(d / "run" / "best.pt"));
  EXPECT_TRUE(fs::exists(d / "run" / "options.json"));
  r = RunAsbuilt(fmt::format("segment --model {} {} -o {} --overlay --confidence", (d / "run" / "best.pt").string(),
                             (d / "toy" / "images").string(), (d / "seg").string()));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_TRUE(fs::exists(d / "seg" / "00000.png"));
  EXPECT_TRUE(fs::exists(d / "seg" / "00007_overlay.png"));
  // How sure the model was: a grey map per image and one row per image.
  const cv::Mat sure = cv::imread((d / "seg" / "00007_confidence.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(sure.empty());
  EXPECT_EQ(sure.type(), CV_8UC1);
  EXPECT_EQ(sure.size(), cv::imread((d / "seg" / "00007.png").string(), cv::IMREAD_UNCHANGED).size());
  const std::string csv = ReadFile(d / "seg" / "confidence.csv");
  EXPECT_EQ(csv.rfind("image,mean_confidence,unsure_share\n", 0), 0u) << csv;
  EXPECT_NE(csv.find("\n00007.png,"), std::string::npos) << csv;
  r = RunAsbuilt(fmt::format("eval seg --model {} --images {} --json {}", (d / "run" / "best.pt").string(),
                             (d / "toy").string(), (d / "m.json").string()));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("mIoU"), std::string::npos);
  EXPECT_TRUE(fs::exists(d / "m.json"));
}

// The paper's ratio experiment end to end through the CLI: two toy-room sets
// stand in for real and synthetic; tiny model, two steps per config.
TEST(SegCommands, ExperimentRatiosWritesTheTableAndPlotForEveryConfig) {
  fs::path d = SegTempDir("ratios");
  for (auto [name, seed] : {std::pair{"real", 21}, std::pair{"synth", 22}}) {
    auto r = RunAsbuilt(fmt::format("experiment toy-rooms -o {} --count 10 --width 64 --height 48 --seed {}",
                                    (d / name).string(), seed));
    ASSERT_EQ(r.exit_code, 0) << r.out;
  }
  auto r = RunAsbuilt(fmt::format(
      "experiment ratios --real {0}/real --synthetic {0}/synth --extra-test {0}/real --configs R100,S100,RS5050,RS8020 "
      "-o {0}/out --arch tiny --epochs 1 --steps-per-epoch 2 --scale 64x48 --crop 48x48 --threads 1 --lr 1e-3",
      d.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  for (const char* c : {"R100", "S100", "RS5050", "RS8020"}) {
    EXPECT_NE(r.out.find(fmt::format("| {} |", c)), std::string::npos) << c << "\n" << r.out;
    EXPECT_TRUE(fs::exists(d / "out" / c / "run" / "best.pt")) << c;
  }
  EXPECT_NE(r.out.find("Also scored on `real`"), std::string::npos) << r.out;
  EXPECT_GT(fs::file_size(d / "out" / "results.json"), 0u);
  EXPECT_GT(fs::file_size(d / "out" / "results.md"), 0u);
  EXPECT_GT(fs::file_size(d / "out" / "plot.png"), 0u);
  // A config name that is not a mix is a usage error naming it.
  r = RunAsbuilt(
      fmt::format("experiment ratios --real {0}/real --synthetic {0}/synth --configs RS6050 -o {0}/bad", d.string()));
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("RS6050"), std::string::npos) << r.out;
  r = RunAsbuilt(
      fmt::format("experiment ratios --real {0}/real --synthetic {0}/synth --scale 64 -o {0}/bad", d.string()));
  EXPECT_EQ(r.exit_code, 2) << r.out;
  fs::remove_all(d);
}

TEST(SegCommands, BadInputsExitWithClearErrors) {
  fs::path d = SegTempDir("bad");
  fs::create_directories(d);
  std::FILE* f = std::fopen((d / "fake.pt").c_str(), "w");
  std::fputs("not a checkpoint", f);
  std::fclose(f);
  auto r = RunAsbuilt(fmt::format("segment --model {} {} -o {}", (d / "fake.pt").string(), (d / "fake.pt").string(),
                                  (d / "out").string()));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("fake.pt"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "out"));
  r = RunAsbuilt("train --images /nonexistent -o " + (d / "run").string());
  EXPECT_EQ(r.exit_code, 1) << r.out;
  r = RunAsbuilt("train --arch b7 --images x -o y");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  r = RunAsbuilt("segment");
  EXPECT_EQ(r.exit_code, 2) << r.out;
}

}  // namespace
}  // namespace asbuilt
