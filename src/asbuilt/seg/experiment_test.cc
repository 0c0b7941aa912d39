#include "asbuilt/seg/experiment.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "asbuilt/imageio/image_io.h"
#include "asbuilt/seg/toy_rooms.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Two toy-room sets stand in for "real" and "synthetic" (different seeds):
// the test is about the plumbing, not the domains.
RatioExperimentOptions TinyExperiment(const fs::path& dir) {
  WriteToyRoomSet(dir / "real", 10, {.width_px = 64, .height_px = 48, .seed = 11});
  WriteToyRoomSet(dir / "synthetic", 10, {.width_px = 64, .height_px = 48, .seed = 12});
  RatioExperimentOptions o;
  o.real_dir = dir / "real";
  o.synthetic_dir = dir / "synthetic";
  o.out_dir = dir / "out";
  o.train.arch = "tiny";
  o.train.epochs = 1;
  o.train.steps_per_epoch = 2;
  o.train.lr = 1e-3;
  o.train.augment = {.scale_width_px = 64, .scale_height_px = 48, .crop_width_px = 48, .crop_height_px = 48};
  o.train.threads = 1;  // Spinning OpenMP barriers crawl on loaded CI machines.
  return o;
}

bool InUnitInterval(const nlohmann::json& v) {
  if (!v.is_number()) return false;
  double x = v.get<double>();
  return std::isfinite(x) && x >= 0.0 && x <= 1.0;
}

TEST(RatioExperiment, TrainsAndScoresEveryConfigOnTheSameRealTestSet) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("asbuilt_seg_experiment_test_{}", ::getpid());
  fs::remove_all(dir);
  RatioExperimentOptions options = TinyExperiment(dir);
  RatioExperimentSummary summary = RunRatioExperiment(options);

  ASSERT_EQ(summary.rows.size(), 4u);
  const char* expected[] = {"R100", "S100", "RS5050", "RS8020"};
  for (size_t i = 0; i < 4; ++i) {
    const RatioExperimentRow& row = summary.rows[i];
    EXPECT_EQ(row.config, expected[i]);
    EXPECT_EQ(row.test_pairs, summary.rows[0].test_pairs) << row.config << ": same test set for every config";
    EXPECT_GT(row.train_pairs, 0) << row.config;
    for (double m : {row.test.miou, row.test.mfscore, row.test.mprecision, row.test.mrecall}) {
      EXPECT_TRUE(std::isfinite(m) && m >= 0.0 && m <= 1.0) << row.config << ": " << m;
    }
  }
  EXPECT_EQ(summary.rows[0].test_pairs, 1);  // ceil(10 % of 10 real pairs).

  // results.json: one object per config with the four metrics in [0, 1].
  nlohmann::json results = nlohmann::json::parse(ReadText(options.out_dir / "results.json"));
  ASSERT_TRUE(results.contains("rows")) << results.dump();
  ASSERT_EQ(results["rows"].size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    const nlohmann::json& r = results["rows"][i];
    EXPECT_EQ(r["config"], expected[i]);
    for (const char* key : {"mIoU", "mFscore", "mPrecision", "mRecall"}) {
      EXPECT_TRUE(InUnitInterval(r[key])) << expected[i] << " " << key << " = " << r[key];
    }
  }
  // results.md: the paper's table, one row per config.
  const std::string md = ReadText(options.out_dir / "results.md");
  EXPECT_NE(md.find("| config |"), std::string::npos) << md;
  for (const char* c : expected) EXPECT_NE(md.find(fmt::format("| {} |", c)), std::string::npos) << c << "\n" << md;
  // plot.png: a decodable image with something drawn on it.
  const cv::Mat plot = ReadColourImage(options.out_dir / "plot.png");
  EXPECT_GT(plot.cols, 300);
  EXPECT_GT(plot.rows, 200);
  EXPECT_LT(cv::mean(plot)[0], 254.0);  // Not a blank canvas.
  for (const char* c : expected) EXPECT_TRUE(fs::exists(options.out_dir / c / "test_metrics.json")) << c;

  // Re-running resumes: no config is trained again, the table is the same.
  RatioExperimentSummary again = RunRatioExperiment(options);
  ASSERT_EQ(again.rows.size(), 4u);
  for (size_t i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(again.rows[i].test.miou, summary.rows[i].test.miou);
  fs::remove_all(dir);
}

TEST(RatioExperimentOptions, BadConfigsAreRejectedByName) {
  RatioExperimentOptions o;
  o.real_dir = "real";
  o.synthetic_dir = "synthetic";
  o.out_dir = "out";
  o.Check();
  o.configs = {"R100", "RS6050"};
  try {
    o.Check();
    FAIL() << "RS6050 accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("RS6050"), std::string::npos) << e.what();
  }
  o.configs = {"RS5050"};
  o.synthetic_dir.clear();
  EXPECT_THROW(o.Check(), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
