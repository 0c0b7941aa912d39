#include "asbuilt/dataset/level_views.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

fs::path Fresh(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("asbuilt_level_views_" + name);
  fs::remove_all(d);
  fs::create_directories(d / "images");
  fs::create_directories(d / "labels");
  return d;
}

TEST(CutLevelViews, CutsATallViewIntoThreeLevelWindowsAndKeepsAWideOne) {
  const fs::path in = Fresh("in"), out = fs::temp_directory_path() / "asbuilt_level_views_out";
  fs::remove_all(out);
  cv::Mat tall(200, 100, CV_8UC3), label(200, 100, CV_8UC1);
  for (int v = 0; v < 200; ++v) {
    tall.row(v).setTo(cv::Scalar(v, v, v));
    label.row(v).setTo(v / 50);  // Four bands of 50 rows.
  }
  cv::imwrite((in / "images" / "000.png").string(), tall);
  cv::imwrite((in / "labels" / "000.png").string(), label);
  cv::imwrite((in / "images" / "001.png").string(), cv::Mat(75, 100, CV_8UC3, cv::Scalar(9, 9, 9)));
  cv::imwrite((in / "labels" / "001.png").string(), cv::Mat(75, 100, CV_8UC1, cv::Scalar(1)));
  const LevelViewsSummary summary = CutLevelViews(in, out);
  EXPECT_EQ(summary.tall, 1);
  EXPECT_EQ(summary.skipped, 1);
  // 100 × 75 windows: the middle one from row 63, the others 31 rows (0.3125 widths) above and below.
  const int tops[3] = {32, 63, 94};
  for (int k = 0; k < 3; ++k) {
    const cv::Mat image = cv::imread((out / "images" / ("000_" + std::to_string(k) + ".png")).string());
    const cv::Mat cut =
        cv::imread((out / "labels" / ("000_" + std::to_string(k) + ".png")).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(image.size(), cv::Size(100, 75));
    ASSERT_EQ(cut.size(), cv::Size(100, 75));
    EXPECT_EQ(image.at<cv::Vec3b>(0, 0)[0], tops[k]);
    EXPECT_EQ(cut.at<std::uint8_t>(0, 0), tops[k] / 50);
    EXPECT_EQ(cut.at<std::uint8_t>(74, 99), (tops[k] + 74) / 50);
  }
  EXPECT_TRUE(fs::is_regular_file(out / "images" / "001.png"));
  EXPECT_TRUE(fs::is_regular_file(out / "labels" / "001.png"));
  EXPECT_THROW(CutLevelViews(Fresh("empty"), out / "none"), InputError);
  EXPECT_FALSE(fs::exists(out / "none"));
}

}  // namespace
}  // namespace asbuilt
