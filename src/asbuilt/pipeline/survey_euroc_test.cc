// Issue 9, real cameras: the two raw EuRoC V1_01 stereo pairs (Vicon room,
// 752×480, radial-tangential distortion) as an unrectified capture whose
// calibration was converted from the dataset's sensor.yaml files, surveyed
// end to end. The room shows mat-covered walls and a floor ~1.9 m in front of
// the rig and no doors or windows; there is no truth plan, so the tests assert
// what is true of any honest survey: it runs, writes its files, its depths
// agree with the dataset's reference disparity, and what it cannot measure
// is said in the notes instead of invented.

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/formats/capture.h"
#include "asbuilt/formats/points_file.h"
#include "asbuilt/pipeline/report.h"
#include "asbuilt/pipeline/survey.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/stereo/euroc_calibration.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

const fs::path kEuroc = fs::path(ASBUILT_SHARED_DATA_DIR) / "euroc_v1_01_vicon_room_stereo";
constexpr const char* kStamps[] = {"1403715273262142976", "1403715277962142976"};

// What a user does: `asbuilt calibrate --from-euroc`, copy the raw images,
// write capture.json with `rectified: false` (the first `frames` pairs).
fs::path MakeEurocCapture(const fs::path& dir, int frames) {
  fs::remove_all(dir);
  fs::create_directories(dir / "cam0");
  fs::create_directories(dir / "cam1");
  const StereoCalibration calibration =
      CalibrationFromEuroc(kEuroc / "cam0" / "sensor.yaml", kEuroc / "cam1" / "sensor.yaml");
  WriteCalibration(calibration, dir / "calibration.yml");
  const StereoRectifier rectifier = MakeStereoRectifier(calibration, {});
  Capture capture;
  capture.camera = {.width = calibration.image_size.width,
                    .height = calibration.image_size.height,
                    .fx = rectifier.camera.fx,
                    .fy = rectifier.camera.fy,
                    .cx = rectifier.camera.cx,
                    .cy = rectifier.camera.cy,
                    .baseline_m = rectifier.baseline_m};
  capture.rectified = false;
  capture.calibration = "calibration.yml";
  for (int index = 0; index < frames; ++index) {
    const std::string stamp = kStamps[index];
    const std::string name = stamp + ".png";
    fs::copy_file(kEuroc / "cam0" / name, dir / "cam0" / name);
    fs::copy_file(kEuroc / "cam1" / name, dir / "cam1" / name);
    // The MAV sat still: both frames are the same view (yaw and height are
    // not known in the rig's frame; the plan is drawn in the first view's).
    capture.frames.push_back({.index = index,
                              .left = "cam0/" + name,
                              .right = "cam1/" + name,
                              .yaw_deg = 0.0,
                              .position_m = Vec3(0, 0, 1.0)});
  }
  WriteCapture(capture, dir / "capture.json");
  return dir / "capture.json";
}

class SurveyEuroc : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kEuroc / "cam0" / "sensor.yaml")) GTEST_SKIP() << kEuroc << " absent";
    dir_ = fs::temp_directory_path() / fmt::format("asbuilt_survey_euroc_{}_{}",
                                                   ::testing::UnitTest::GetInstance()->current_test_info()->name(),
                                                   ::getpid());
    // Both pairs show the same view; the segmenter's test takes one (CPU time).
    const bool model_test =
        std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()).find("ShippedModel") !=
        std::string::npos;
    capture_ = MakeEurocCapture(dir_, model_test ? 1 : 2);
  }
  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }
  void ExpectOutputs(const fs::path& out) {
    for (const char* f : {"plan.json", "points.txt", "points.ply", "summary.json", "report.html"}) {
      EXPECT_TRUE(fs::exists(out / f)) << f;
    }
    EXPECT_FALSE(fs::exists(out / "score.json")) << "there is no truth plan to score against";
  }
  // A capture of one direction cannot close a room: the notes must say so
  // whenever walls were drawn.
  static void ExpectCoverageNote(const SurveyResult& r) {
    if (r.plan.walls.empty()) return;
    const bool said = std::any_of(r.summary.notes.begin(), r.summary.notes.end(), [](const std::string& n) {
      return n.rfind("the views cover ", 0) == 0 && n.find("walls outside them are not measured") != std::string::npos;
    });
    EXPECT_TRUE(said) << "no note about the partial view coverage";
  }
  static void Print(const SurveySummary& s) {
    std::printf("%s\n", s.BriefReport().c_str());
    for (const FrameCues& c : s.frame_cues) std::printf("  %s\n", c.BriefReport().c_str());
    for (const std::string& n : s.notes) std::printf("  note: %s\n", n.c_str());
    for (const StageTiming& t : s.stages) std::printf("  %s %.2f s\n", t.stage.c_str(), t.seconds);
  }
  fs::path dir_, capture_;
};

TEST_F(SurveyEuroc, CaptureAndConvertedCalibrationValidate) {
  const FileReport report = CheckCaptureFile(capture_);
  EXPECT_TRUE(report.errors.empty()) << report.errors.front().ToString();
  EXPECT_TRUE(CheckCalibrationFile(dir_ / "calibration.yml").errors.empty());
  EXPECT_FALSE(ReadCapture(capture_).rectified);
}

// Given labels (every pixel "wall", as a user could paint them): rectify →
// disparity → dense points run on the real pair, and the points lie where the
// dataset's reference puts the mats: median disparity 25 px → Z ≈ 1.92 m.
TEST_F(SurveyEuroc, GivenLabelsPutWallPointsAtTheReferenceDepth) {
  const fs::path labels = dir_ / "labels";
  fs::create_directories(labels);
  for (int i = 0; i < 2; ++i) {
    cv::imwrite((labels / fmt::format("{:03d}.png", i)).string(), cv::Mat(480, 752, CV_8UC1, cv::Scalar(1)));
  }
  const fs::path out = dir_ / "out_labels";
  const SurveyResult r = RunSurvey(capture_, out, {.labels_dir = labels, .report_frames = 2});
  Print(r.summary);
  ExpectOutputs(out);
  EXPECT_EQ(r.summary.frames, 2);
  ASSERT_GT(r.summary.points, 1000);
  // Yaw 0 looks along +Y, so a point's depth along the optical axis is ≈ its world y.
  std::vector<double> depth_m;
  for (const ClassPoint& p : ReadPoints(out / "points.txt")) depth_m.push_back(p.position_m.y());
  std::nth_element(depth_m.begin(), depth_m.begin() + depth_m.size() / 2, depth_m.end());
  const double median_m = depth_m[depth_m.size() / 2];
  std::printf("median depth of the wall points %.3f m (reference 1.92 m)\n", median_m);
  EXPECT_NEAR(median_m, 1.92, 0.4);
  // Every wall and note the survey makes is its own; nothing is scored.
  EXPECT_FALSE(r.summary.score.has_value());
  ExpectCoverageNote(r);
}

// The shipped segmenter on real grey images it was never trained on: the
// survey must finish, write everything, and say what it could not measure.
TEST_F(SurveyEuroc, ShippedModelRunsEndToEndAndSaysWhatItCannotMeasure) {
  if (!SegmenterAvailable() || !fs::exists(DefaultModelPath())) GTEST_SKIP() << "no segmenter in this build";
  const fs::path out = dir_ / "out_model";
  const SurveyResult r = RunSurvey(capture_, out, {.report_frames = 2});
  Print(r.summary);
  ExpectOutputs(out);
  EXPECT_EQ(r.summary.frames, 1);
  EXPECT_EQ(static_cast<int>(r.summary.frame_cues.size()), 1);
  EXPECT_FALSE(r.summary.score.has_value());
  if (r.plan.walls.empty()) {
    EXPECT_NE(std::find(r.summary.notes.begin(), r.summary.notes.end(), "no walls could be measured from this capture"),
              r.summary.notes.end());
    // The empty plan.json says why it is empty: it is no measurement.
    const Plan written = ReadPlan(out / "plan.json");
    ASSERT_TRUE(written.verdict);
    EXPECT_EQ(written.verdict->verdict, "unreliable");
  }
  EXPECT_NE(r.summary.verdict.verdict, Verdict::kGood);  // A real capture of one direction is never good.
  ExpectCoverageNote(r);
  const std::string html = ReadFile(out / "report.html");
  for (const std::string& note : r.summary.notes) {
    EXPECT_NE(html.find(HtmlEscape(note.substr(0, 20))), std::string::npos) << "report.html lacks the note: " << note;
  }
}

}  // namespace
}  // namespace asbuilt
