#include "asbuilt/stereo/calibrate.h"

#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

std::vector<fs::path> SampleViews(const std::string& side) {
  std::vector<fs::path> out;
  for (int i : {1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14}) {
    out.push_back(fs::path(ASBUILT_SHARED_DATA_DIR) / "opencv_stereo_calib" / fmt::format("{}{:02d}.jpg", side, i));
  }
  return out;
}

// OpenCV's stereo_calib sample: RMS 0.634 px, mean epipolar error 0.445 px.
TEST(CalibrateStereo, MatchesOrBeatsOpenCvSampleOnItsImages) {
  CalibrationSummary s = CalibrateStereo(SampleViews("left"), SampleViews("right"), {.square_m = 0.025});
  std::printf("%s\n", s.BriefReport().c_str());
  for (const ViewReport& v : s.views) std::printf("  %s\n", v.ToString().c_str());
  EXPECT_GE(s.views_used, 11);
  EXPECT_LE(s.calibration.rms_px, 0.634);
  EXPECT_LE(s.calibration.epipolar_error_px, 0.445);
  // Baseline ≈ 3.34 squares.
  EXPECT_NEAR(cv::norm(s.calibration.T) / 0.025, 3.34, 0.1);
}

TEST(CalibrateStereo, ReportsAViewWithoutABoardByName) {
  auto left = SampleViews("left"), right = SampleViews("right");
  left.resize(4);
  right.resize(4);
  // A picture with no chessboard: a rendered room, same size as the boards.
  const fs::path room = fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public" / "p01_rect_1door_2win";
  left.push_back(room / "left" / "000.png");
  right.push_back(room / "right" / "000.png");
  CalibrationSummary s = CalibrateStereo(left, right, {});
  ASSERT_EQ(s.views.size(), 5u);
  EXPECT_FALSE(s.views[4].used);
  EXPECT_NE(s.views[4].ToString().find("000.png"), std::string::npos);
  EXPECT_NE(s.views[4].reason.find("no 9x6 board"), std::string::npos) << s.views[4].reason;
}

TEST(CalibrateStereo, TooFewViewsIsAnInputError) {
  std::vector<fs::path> none = {fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public" / "p01_rect_1door_2win" /
                                "left" / "003.png"};
  EXPECT_THROW(CalibrateStereo(none, none, {}), InputError);
}

TEST(CalibrateOptions, RejectsNonPositiveSquare) {
  EXPECT_THROW(CalibrateOptions{.square_m = 0}.Check(), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
