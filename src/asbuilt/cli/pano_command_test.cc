// CLI tests of `asbuilt pano views` and `asbuilt eval zind` on the ZInD
// sample tour in ../shared/data (skipped without it), and of `asbuilt pano
// level` on a CC0 panorama there. Outputs go to the temporary folder: they
// are derived from ZInD and never kept.

#include <unistd.h>

#include <cmath>
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

const fs::path kTour = testing_util::kData / "zind_sample_tour";
constexpr const char* kNotice = "ZInD: academic use only; research measurement only, never training data";

fs::path PanoTempDir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / fmt::format("asbuilt_cli_pano_{}_{}", name, ::getpid());
  fs::remove_all(d);
  return d;
}

TEST(PanoCommand, WritesViewsLabelsAndTruthOfAZindPanorama) {
  if (!fs::exists(kTour / "zind_data.json")) GTEST_SKIP() << "shared data not present: " << kTour;
  const fs::path d = PanoTempDir("views");
  auto r =
      RunAsbuilt(fmt::format("pano views pano_15 --zind {} -o {} --size 160x120 --fx 100 --views 3 --yaw-step 120 "
                             "--overlay",
                             kTour.string(), d.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find(kNotice), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("3 views + layout labels + truth.json"), std::string::npos) << r.out;
  for (const char* f : {"images/002.png", "labels/002.png", "overlays/000.png", "truth.json", "capture.json"}) {
    EXPECT_TRUE(fs::exists(d / f)) << f;
  }
  EXPECT_NE(ReadFile(d / "capture.json").find("\"yaw_deg\": 240.0"), std::string::npos);
  // The plain form: any 2:1 image, by path, without labels.
  r = RunAsbuilt(fmt::format("pano views {} -o {} --views 1",
                             (kTour / "panos/floor_01_partial_room_01_pano_15.jpg").string(), (d / "plain").string()));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_TRUE(fs::exists(d / "plain/images/000.png"));
  EXPECT_FALSE(fs::exists(d / "plain/labels"));
  fs::remove_all(d);
}

TEST(PanoCommand, EvalZindScoresTheShippedModelAndSaysZindIsForResearchOnly) {
  if (!fs::exists(kTour / "zind_data.json")) GTEST_SKIP() << "shared data not present: " << kTour;
  const fs::path model = fs::path(ASBUILT_SOURCE_DIR) / "models/segformer_b0_asbuilt.pt";
  const fs::path d = PanoTempDir("eval");
  auto r =
      RunAsbuilt(fmt::format("eval zind --model {} --zind {} -o {} --max-panoramas 1 --views 2 --size 160x120 "
                             "--fx 100 --yaw-step 180",
                             model.string(), kTour.string(), d.string()));
  if (r.out.find("LibTorch") != std::string::npos) GTEST_SKIP() << "this build has no LibTorch";
  ASSERT_EQ(r.exit_code, 0) << r.out;
  ASSERT_NE(r.out.find(kNotice), std::string::npos) << r.out;
  EXPECT_LT(r.out.find(kNotice), r.out.find("mIoU")) << r.out;  // Said before any figure.
  EXPECT_NE(r.out.find("ZInD 1 panoramas, 2 views: mIoU"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Upper half (above the horizon)"), std::string::npos) << r.out;
  for (const char* f : {"metrics.json", "metrics.md", "report.html"}) EXPECT_TRUE(fs::exists(d / f)) << f;
  EXPECT_NE(ReadFile(d / "metrics.md").find(kNotice), std::string::npos);
  fs::remove_all(d);
}

// The tilt in `asbuilt pano level`'s first line ("tilted 0.76° toward …"), NaN if none.
double PrintedTiltDeg(const std::string& out) {
  const std::size_t at = out.find("tilted ");
  return at == std::string::npos ? NAN : std::stod(out.substr(at + 7));
}

TEST(PanoCommand, LevelsATiltedPhotoAndPrintsItsTilt) {
  const fs::path photo = testing_util::kData / "cc0-panoramas/annotated/pine_attic/pano.jpg";
  if (!fs::exists(photo)) GTEST_SKIP() << "shared data not present: " << photo;
  const fs::path d = PanoTempDir("level");
  auto r = RunAsbuilt(fmt::format("pano level {} -o {}", photo.string(), (d / "level.jpg").string()));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NEAR(PrintedTiltDeg(r.out), 0.8, 0.1) << r.out;
  EXPECT_NE(r.out.find("(column "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("levelled → "), std::string::npos) << r.out;
  const cv::Mat levelled = cv::imread((d / "level.jpg").string());
  EXPECT_EQ(levelled.cols, 1024);
  EXPECT_EQ(levelled.rows, 512);
  // The levelled photo, estimated only: level now, and nothing written.
  r = RunAsbuilt(fmt::format("pano level {} --estimate-only", (d / "level.jpg").string()));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_LT(PrintedTiltDeg(r.out), 0.15) << r.out;
  EXPECT_EQ(r.out.find("levelled → "), std::string::npos) << r.out;
  fs::remove_all(d);
}

TEST(PanoCommand, LevelSaysWhatIsMissingOrWrong) {
  const fs::path d = PanoTempDir("level_bad");
  fs::create_directories(d);
  auto r = RunAsbuilt(fmt::format("pano level {}", (d / "any.jpg").string()));
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--out (or --estimate-only) is required"), std::string::npos) << r.out;
  cv::imwrite((d / "square.png").string(), cv::Mat(64, 64, CV_8UC3, cv::Scalar(1, 2, 3)));
  r = RunAsbuilt(fmt::format("pano level {} --estimate-only", (d / "square.png").string()));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("64x64 is not an equirectangular panorama"), std::string::npos) << r.out;
  // A blank panorama has no lines: said, and no image written.
  cv::imwrite((d / "blank.png").string(), cv::Mat(64, 128, CV_8UC3, cv::Scalar(1, 2, 3)));
  r = RunAsbuilt(fmt::format("pano level {} -o {}", (d / "blank.png").string(), (d / "out.png").string()));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("no tilt estimate: 0 vertical lines, too few"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "out.png"));
  fs::remove_all(d);
}

}  // namespace
}  // namespace asbuilt
