#include "asbuilt/dataset/check.h"

#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/dataset/mix.h"
#include "asbuilt/labels/label_io.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

fs::path CheckTestDir() {
  fs::path dir = fs::temp_directory_path() /
                 ("asbuilt_check_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(dir);
  return dir;
}

void MakePair(const fs::path& dir, const std::string& stem, cv::Mat label, cv::Size image_size = {8, 6}) {
  WriteImageAtomic(dir / "images" / (stem + ".png"), cv::Mat(image_size, CV_8UC3, cv::Scalar(1, 2, 3)));
  WriteLabelImage(dir / "labels" / (stem + ".png"), label);
}

TEST(CheckDataset, ReportsEachBadPairByNameAndCountsTheGoodOnes) {
  fs::path dir = CheckTestDir();
  cv::Mat good(6, 8, CV_8UC1, cv::Scalar(1));
  good.colRange(0, 2).setTo(2);
  good.at<std::uint8_t>(0, 7) = 255;
  MakePair(dir, "a", good);
  MakePair(dir, "b", cv::Mat(6, 8, CV_8UC1, cv::Scalar(3)));
  cv::Mat bad_ids(6, 8, CV_8UC1, cv::Scalar(0));
  bad_ids.at<std::uint8_t>(1, 1) = 7;
  MakePair(dir, "c", bad_ids);
  MakePair(dir, "d", cv::Mat(5, 8, CV_8UC1, cv::Scalar(0)));  // Size mismatch.
  MakePair(dir, "e", good);
  WriteFileAtomic(dir / "images/e.png", "corrupt");
  WriteImageAtomic(dir / "labels/f.png", cv::Mat(6, 8, CV_8UC3, cv::Scalar(0)));  // Colour label, no image.
  WriteImageAtomic(dir / "images/f.png", cv::Mat(6, 8, CV_8UC3, cv::Scalar(0)));

  DatasetCheckSummary s = CheckDataset({.num_threads = 2}, dir);
  EXPECT_EQ(s.pairs, 6);
  EXPECT_EQ(s.bad_pairs, 4);
  ASSERT_EQ(s.problems.size(), 4u);
  EXPECT_EQ(s.problems[0].ToString(),
            (dir / "images/e.png").string() + ": pair e: cannot decode image (not a PNG/JPEG/… or corrupt)");
  EXPECT_EQ(s.problems[1].ToString(),
            (dir / "labels/c.png").string() + ": pair c: label ids outside {0, 1, 2, 3, 255}: 7 (1 px)");
  EXPECT_EQ(s.problems[2].ToString(),
            (dir / "labels/d.png").string() + ": pair d: label is 8x5 but image d.png is 8x6");
  EXPECT_NE(s.problems[3].message.find("pair f: expected a single-channel 8-bit label PNG"), std::string::npos);
  const ClassHistogram& h = s.histograms.at("all");
  EXPECT_EQ(h.pairs, 2);
  EXPECT_EQ(h.pixels[1], 48 - 12 - 1);
  EXPECT_EQ(h.pixels[2], 12);
  EXPECT_EQ(h.pixels[3], 48);
  EXPECT_EQ(h.pixels[4], 1);
  EXPECT_EQ(h.images_with[3], 1);
  EXPECT_EQ(s.BriefReport().substr(0, 15), "checked 6 pairs");
  EXPECT_NE(s.HistogramTable().find("all"), std::string::npos);
}

TEST(CheckDataset, ChecksAManifestBySplitAndSource) {
  fs::path dir = CheckTestDir();
  for (int i = 0; i < 20; ++i) {
    MakePair(dir / "real", fmt::format("{:02d}", i), cv::Mat(6, 8, CV_8UC1, cv::Scalar(1)));
    MakePair(dir / "synth", fmt::format("{:02d}", i), cv::Mat(6, 8, CV_8UC1, cv::Scalar(2)));
  }
  MixDataset({.config = "RS5050", .checksums = false}, dir / "real", dir / "synth", {}, dir / "manifest.json");
  fs::remove(dir / "synth/labels/03.png");
  DatasetCheckSummary s = CheckDataset({}, dir / "manifest.json");
  EXPECT_GE(s.problems.size(), 1u);
  EXPECT_NE(s.problems[0].message.find("file not found"), std::string::npos) << s.problems[0].ToString();
  EXPECT_EQ(s.histograms.at("test").pairs, 2);
  EXPECT_EQ(s.histograms.at("test").pixels[1], 2 * 48);
  EXPECT_EQ(s.histograms.at("real").pixels[2], 0);
  EXPECT_GT(s.histograms.at("synthetic").pixels[2], 0);
}

TEST(CheckDataset, MissingPathIsAnInputError) { EXPECT_THROW(CheckDataset({}, "/nonexistent/dataset"), InputError); }

}  // namespace
}  // namespace asbuilt
