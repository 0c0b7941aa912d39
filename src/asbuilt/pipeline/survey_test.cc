#include "asbuilt/pipeline/survey.h"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/render/capture_render.h"
#include "asbuilt/scene/procedural.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

fs::path Room(const char* name) { return fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public" / name; }

// The method's upper bound on Blender-rendered rooms: exact labels in, plan
// out, scored against the truth beside the capture.
TEST(RunSurvey, ExactLabelsOnBlenderRectangleMeetTargets) {
  fs::path capture = Room("p01_rect_1door_2win") / "capture.json";
  ASSERT_TRUE(fs::exists(capture)) << capture;
  fs::path out = fs::temp_directory_path() / "asbuilt_survey_p01";
  fs::remove_all(out);
  SurveyResult r = RunSurvey(capture, out, {.use_capture_labels = true, .report_frames = 2});
  ASSERT_TRUE(r.summary.score.has_value());
  const PlanScore& s = *r.summary.score;
  EXPECT_EQ(s.walls.matched, s.walls.truth) << s.Table();
  EXPECT_LE(s.wall_length.Median().value_or(1), 0.02) << s.Table();
  EXPECT_LE(s.wall_length.Max().value_or(1), 0.05) << s.Table();
  EXPECT_EQ(s.doors.matched, s.doors.truth) << s.Table();
  EXPECT_EQ(s.windows.matched, s.windows.truth) << s.Table();
  // Opening widths from the label edges on the wall (stereo boundary points):
  // 0.6–1.8 % here, 5.5 % median before them.
  EXPECT_LE(s.opening_width.Median().value_or(1), 0.02) << s.Table();
  EXPECT_LE(s.opening_width.Max().value_or(1), 0.03) << s.Table();
  EXPECT_LE(s.area_relative_error.value_or(1), 0.02) << s.Table();
  for (const char* f : {"plan.json", "plan.svg", "plan.dxf", "plan.pdf", "plan.png", "plan.ifc", "points.txt",
                        "points.ply", "score.json", "summary.json", "report.html"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
  }
  std::string html = ReadFile(out / "report.html");
  EXPECT_NE(html.find("Accuracy against the truth plan"), std::string::npos);
  EXPECT_NE(html.find("exact labels"), std::string::npos);
  // plan.ifc, read back by IFC++ (plan/ifc_check.cc), holds every wall,
  // opening and room of plan.json.
  if (std::string(ASBUILT_IFC_CHECK).empty()) GTEST_SKIP() << "IFC++ (libifcplusplus-dev) not installed";
  std::string cmd = fmt::format("{} {} {} > {} 2>&1", ASBUILT_IFC_CHECK, (out / "plan.ifc").string(),
                                (out / "plan.json").string(), (out / "ifc_check.txt").string());
  EXPECT_EQ(std::system(cmd.c_str()), 0) << ReadFile(out / "ifc_check.txt");
  EXPECT_EQ(ReadFile(out / "ifc_check.txt").rfind("ok: 4 walls, 1 door, 2 windows, 1 space", 0), 0u)
      << ReadFile(out / "ifc_check.txt");
}

// The L room's door stands open into the room: its leaf must not widen it,
// nor make a second door on the neighbouring wall.
TEST(RunSurvey, ExactLabelsOnBlenderLShapeMeasureOpeningWidths) {
  fs::path capture = Room("p02_L_shape") / "capture.json";
  ASSERT_TRUE(fs::exists(capture)) << capture;
  fs::path out = fs::temp_directory_path() / "asbuilt_survey_p02";
  fs::remove_all(out);
  SurveyResult r = RunSurvey(capture, out, {.use_capture_labels = true, .report_frames = 1});
  ASSERT_TRUE(r.summary.score.has_value());
  const PlanScore& s = *r.summary.score;
  EXPECT_EQ(s.walls.matched, s.walls.truth) << s.Table();
  EXPECT_EQ(s.doors.matched, s.doors.truth) << s.Table();
  EXPECT_EQ(s.doors.predicted, s.doors.truth) << s.Table();
  EXPECT_EQ(s.windows.matched, s.windows.truth) << s.Table();
  EXPECT_LE(s.window_width.Max().value_or(1), 0.02) << s.Table();
  EXPECT_LE(s.opening_width.Median().value_or(1), 0.02) << s.Table();
  // The hinge side of the open door is hidden by its leaf (no label edge on
  // the wall there); its width comes from the leaf: 4.3 % today, 7.0 % from
  // the points' extent, 63 % before the boundary points.
  EXPECT_LE(s.door_width.Max().value_or(1), 0.06) << s.Table();
  EXPECT_EQ(r.summary.plan.door_leaves, 1);
}

// Issue 9's accuracy targets on the Blender rooms with the shipped segmenter,
// as a user with a real camera would run it (no labels given): wall length
// error median ≤ 2 %, max ≤ 5 %; opening width median ≤ 3 %; every wall and
// opening found.
TEST(RunSurvey, ShippedModelOnBlenderRoomsMeetsTheTargets) {
  if (!SegmenterAvailable() || !fs::exists(DefaultModelPath())) {
    GTEST_SKIP() << "no LibTorch in this build, or no shipped model";
  }
  for (const char* room : {"p01_rect_1door_2win", "p02_L_shape"}) {
    const fs::path out = fs::temp_directory_path() / fmt::format("asbuilt_survey_model_{}", room);
    fs::remove_all(out);
    SurveyResult r = RunSurvey(Room(room) / "capture.json", out, {.write_report = false, .report_frames = 1});
    ASSERT_TRUE(r.summary.score.has_value()) << room;
    const PlanScore& s = *r.summary.score;
    EXPECT_EQ(s.walls.matched, s.walls.truth) << room << "\n" << s.Table();
    EXPECT_LE(s.wall_length.Median().value_or(1), 0.02) << room << "\n" << s.Table();
    EXPECT_LE(s.wall_length.Max().value_or(1), 0.05) << room << "\n" << s.Table();
    EXPECT_EQ(s.doors.matched + s.windows.matched, s.doors.truth + s.windows.truth) << room << "\n" << s.Table();
    EXPECT_LE(s.opening_width.Median().value_or(1), 0.03) << room << "\n" << s.Table();
    fs::remove_all(out);
  }
}

// asbuilt's own random rooms have plain painted walls: SGBM matches render
// noise there (1.3–1.6 px median error, bench/results/survey.md), and a plan
// from stereo alone was 2/4 walls at 36 % here. The stereo check sees it and
// the walls come from their floor/ceiling label edges (contacts) instead.
TEST(RunSurvey, PlainPaintedRoomIsMeasuredFromItsContacts) {
  const Scene scene = RandomScene({}, 5);  // `scene random --seed 5`: a furnished rectangle.
  const fs::path dir = fs::temp_directory_path() / "asbuilt_survey_plain";
  fs::remove_all(dir);
  RenderCapture(scene, dir / "capture", {.views = 12, .width_px = 320, .height_px = 240});
  SurveyOptions options{.use_capture_labels = true, .report_frames = 1};
  SurveyResult r = RunSurvey(dir / "capture" / "capture.json", dir / "survey", options);
  long checked = 0, agreed = 0;
  for (const FrameCues& c : r.summary.frame_cues) checked += c.stereo_checked, agreed += c.stereo_agreed;
  ASSERT_GT(checked, 2000);
  EXPECT_LT(static_cast<double>(agreed) / checked, 0.6) << "plain walls: stereo scatters down the columns";
  EXPECT_NE(r.summary.wall_cue.find("contacts"), std::string::npos) << r.summary.wall_cue;
  ASSERT_TRUE(r.summary.score.has_value());
  const PlanScore& s = *r.summary.score;
  EXPECT_EQ(s.walls.matched, s.walls.truth) << s.Table();
  EXPECT_LE(s.wall_length.Median().value_or(1), 0.02) << s.Table();
  EXPECT_LE(s.wall_length.Max().value_or(1), 0.05) << s.Table();
  EXPECT_TRUE(std::isfinite(r.summary.ceiling_height_m));
  EXPECT_NEAR(r.summary.ceiling_height_m, scene.rooms.at(0).height_m, 0.03);
  EXPECT_NE(ReadFile(dir / "survey" / "summary.json").find("\"wall_cue\""), std::string::npos);
}

// Labels given as a folder are a segmenter's unless said to be exact (a
// renderer's label pass): then they snap and carry ± as a capture's own.
TEST(SurveyOptions, GivenLabelsAreExactOnlyWhenSaidSo) {
  EXPECT_FALSE(SurveyOptions{.labels_dir = fs::path("labels")}.ExactLabels());
  EXPECT_TRUE((SurveyOptions{.labels_dir = fs::path("labels"), .labels_exact = true}.ExactLabels()));
  EXPECT_TRUE(SurveyOptions{.use_capture_labels = true}.ExactLabels());
  EXPECT_THROW(SurveyOptions{.labels_exact = true}.Check(), InvalidArgument);
}

TEST(RunSurvey, MissingLabelDirectoryNamesTheFile) {
  fs::path capture = Room("p01_rect_1door_2win") / "capture.json";
  fs::path out = fs::temp_directory_path() / "asbuilt_survey_missing";
  fs::remove_all(out);
  try {
    RunSurvey(capture, out, {.labels_dir = fs::path("/nonexistent/labels")});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/labels"), std::string::npos) << e.what();
  }
  // Nothing half-written.
  EXPECT_FALSE(fs::exists(out / "plan.json"));
}

}  // namespace
}  // namespace asbuilt
