#include "asbuilt/labels/convert.h"

#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/labels/label_io.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

fs::path ConvertTestDir() {
  fs::path dir = fs::temp_directory_path() /
                 ("asbuilt_convert_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(dir);
  return dir;
}

cv::Vec3b Bgr(int r, int g, int b) { return cv::Vec3b(b, g, r); }

TEST(ConvertIdMap, NearestColourWinsAndFarPixelsBecomeBackground) {
  cv::Mat idmap(1, 5, CV_8UC3);
  idmap.at<cv::Vec3b>(0, 0) = Bgr(180, 50, 30);    // Near wall (200,40,40): d ≈ 24.5.
  idmap.at<cv::Vec3b>(0, 1) = Bgr(40, 160, 70);    // Near door.
  idmap.at<cv::Vec3b>(0, 2) = Bgr(50, 85, 170);    // Near window.
  idmap.at<cv::Vec3b>(0, 3) = Bgr(10, 5, 5);       // Near background.
  idmap.at<cv::Vec3b>(0, 4) = Bgr(200, 200, 200);  // Far from everything.
  std::int64_t beyond = -1;
  cv::Mat labels = ConvertIdMap(idmap, Palette::Nominal(), 80.0, &beyond);
  ASSERT_EQ(labels.type(), CV_8UC1);
  EXPECT_EQ(labels.at<std::uint8_t>(0, 0), 1);
  EXPECT_EQ(labels.at<std::uint8_t>(0, 1), 2);
  EXPECT_EQ(labels.at<std::uint8_t>(0, 2), 3);
  EXPECT_EQ(labels.at<std::uint8_t>(0, 3), 0);
  EXPECT_EQ(labels.at<std::uint8_t>(0, 4), 0);
  EXPECT_EQ(beyond, 1);
  // A tight threshold rejects the drifted wall pixel (24.5 > 20).
  EXPECT_EQ(ConvertIdMap(idmap, Palette::Nominal(), 20.0).at<std::uint8_t>(0, 0), 0);
}

TEST(ConvertIdMap, RejectsAnEmptyPalette) {
  EXPECT_THROW(ConvertIdMap(cv::Mat(2, 2, CV_8UC3), Palette{}, 10), InvalidArgument);
  EXPECT_THROW((ConvertOptions{.threshold = 0}.Check()), InvalidArgument);
}

TEST(ConvertIdMapFiles, ConvertsABatchKeepingNamesAndReportsBadFiles) {
  fs::path dir = ConvertTestDir();
  fs::create_directories(dir / "idmap");
  std::vector<fs::path> inputs;
  for (int i = 0; i < 6; ++i) {
    cv::Mat idmap(20, 30, CV_8UC3, cv::Scalar(0, 0, 0));
    idmap(cv::Rect(0, 0, 10 + i, 20)).setTo(cv::Scalar(40, 40, 200));  // Wall, BGR.
    fs::path p = dir / "idmap" / fmt::format("{:03d}.png", i);
    cv::imwrite(p.string(), idmap);
    inputs.push_back(p);
  }
  WriteFileAtomic(dir / "idmap/bad.png", "garbage");
  inputs.push_back(dir / "idmap/bad.png");
  ConvertSummary s = ConvertIdMapFiles({.threshold = 50, .num_threads = 2}, Palette::Nominal(), inputs, dir / "out");
  EXPECT_EQ(s.converted, 6);
  ASSERT_EQ(s.failed.size(), 1u);
  EXPECT_EQ(s.failed[0].file, (dir / "idmap/bad.png").string());
  EXPECT_EQ(s.pixels, 6 * 600);
  for (int i = 0; i < 6; ++i) {
    cv::Mat labels = ReadLabelImage(dir / "out" / fmt::format("{:03d}.png", i));
    EXPECT_EQ(cv::countNonZero(labels == 1), 20 * (10 + i));
    EXPECT_EQ(cv::countNonZero(labels == 0), 600 - 20 * (10 + i));
  }
  EXPECT_FALSE(fs::exists(dir / "out/bad.png"));
  EXPECT_NE(s.BriefReport().find("converted 6 ID maps"), std::string::npos) << s.BriefReport();
  EXPECT_NE(s.BriefReport().find("1 failed"), std::string::npos);
  EXPECT_EQ(ListImageFiles(dir / "idmap").size(), 7u);
}

}  // namespace
}  // namespace asbuilt
