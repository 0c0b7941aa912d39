// `asbuilt points`, `asbuilt disparity`, `asbuilt calibrate`, `asbuilt rectify`
// through the real binary.

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "asbuilt/cli/cli_test_util.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

using testing_util::RunAsbuilt;
using testing_util::RunResult;

using testing_util::kData;
const fs::path kRoom = kData / "blender-rooms-public" / "p01_rect_1door_2win";

template <typename... Args>
std::string Join(const Args&... args) {
  std::string out;
  ((out += (out.empty() ? "" : " ") + std::string(args)), ...);
  return out;
}

fs::path PointsTempDir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("asbuilt_cli_stereo_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(PointsCommand, WritesPointsAndPlyFromALabelFolder) {
  const fs::path out = PointsTempDir("points");
  const RunResult r = RunAsbuilt(
      Join("points", (kRoom / "capture.json").string(), "--labels", (kRoom / "labels").string(), "-o", out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("12 frames (12 with points)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("corner+"), std::string::npos) << r.out;
  const std::string text = ReadFile(out / "points.txt");
  EXPECT_NE(text.find("wall "), std::string::npos);
  EXPECT_NE(text.find(" corner "), std::string::npos);
  EXPECT_EQ(ReadFile(out / "points.ply").rfind("ply\n", 0), 0u);
}

TEST(PointsCommand, MissingLabelFileIsAnInputErrorNamingIt) {
  const fs::path out = PointsTempDir("points_missing");
  const RunResult r = RunAsbuilt(
      Join("points", (kRoom / "capture.json").string(), "--labels", out.string(), "-o", (out / "o").string()));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("000.png"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out / "o" / "points.txt"));
}

TEST(PointsCommand, NeedsALabelSource) {
  const RunResult r = RunAsbuilt(Join("points", (kRoom / "capture.json").string(), "-o", "/tmp/x"));
  EXPECT_EQ(r.exit_code, 2) << r.out;
}

TEST(DisparityCommand, WritesPfmAndColourPicture) {
  const fs::path out = PointsTempDir("disparity");
  const RunResult r =
      RunAsbuilt(Join("disparity", (kRoom / "left" / "000.png").string(), (kRoom / "right" / "000.png").string(), "-o",
                      (out / "d.pfm").string(), "--num-disparities", "64"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(ReadFile(out / "d.pfm").rfind("Pf\n640 480\n", 0), 0u);
  EXPECT_TRUE(fs::exists(out / "d.png"));
  EXPECT_EQ(RunAsbuilt(Join("disparity", "a.png", "b.png", "-o", "d.pfm", "--matcher", "xx")).exit_code, 2);
  EXPECT_EQ(
      RunAsbuilt(Join("disparity", "/nonexistent.png", "/nonexistent.png", "-o", (out / "e.pfm").string())).exit_code,
      1);
}

TEST(CalibrateCommand, CalibratesRectifiesAndNamesAViewWithoutABoard) {
  const fs::path out = PointsTempDir("calibrate");
  const fs::path c = kData / "opencv_stereo_calib";
  std::string left, right;
  for (const char* n : {"01", "02", "03", "04", "05", "06"}) {
    left += " " + (c / ("left" + std::string(n) + ".jpg")).string();
    right += " " + (c / ("right" + std::string(n) + ".jpg")).string();
  }
  left += " " + (kRoom / "left" / "000.png").string();
  right += " " + (kRoom / "right" / "000.png").string();
  const RunResult r = RunAsbuilt("calibrate --left" + left + " --right" + right + " --board 9x6 --square-m 0.025 -o " +
                                 (out / "calibration.yml").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("000.png"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no 9x6 board"), std::string::npos) << r.out;
  EXPECT_NE(ReadFile(out / "calibration.yml").find("rms:"), std::string::npos);

  const RunResult rect = RunAsbuilt("rectify --calibration " + (out / "calibration.yml").string() + " --left " +
                                    (c / "left01.jpg").string() + " --right " + (c / "right01.jpg").string() + " -o " +
                                    (out / "rect").string());
  ASSERT_EQ(rect.exit_code, 0) << rect.out;
  EXPECT_TRUE(fs::exists(out / "rect" / "left" / "left01.jpg"));
  EXPECT_TRUE(fs::exists(out / "rect" / "right" / "right01.jpg"));
}

TEST(CalibrateCommand, NoBoardAnywhereIsAnInputError) {
  const RunResult r = RunAsbuilt("calibrate --left " + (kRoom / "left" / "000.png").string() + " --right " +
                                 (kRoom / "right" / "000.png").string() + " -o /tmp/asbuilt_never.yml");
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_FALSE(fs::exists("/tmp/asbuilt_never.yml"));
}

}  // namespace
}  // namespace asbuilt
