// Surveys of mono and panorama captures (issue 22) on a synthetic box room
// whose labels are drawn exactly from its geometry: the contact cue's
// geometry end to end, with no segmenter; and the same room painted as a
// photo, surveyed with the panorama's layout (--pano-layout).

#include <array>
#include <cmath>
#include <algorithm>
#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/pano/perspective.h"
#include "asbuilt/pipeline/survey.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

// A 4.0 × 3.0 m room, 2.5 m high, the camera at (0.4, −0.3, 1.4); a 0.9 m
// door (2.0 m high) on the north wall (y = 1.5) from x = −0.6 to 0.3.
constexpr double kX0 = -2.0, kX1 = 2.0, kY0 = -1.5, kY1 = 1.5, kCeiling = 2.5;
const Vec3 kCamera(0.4, -0.3, 1.4);

unsigned char LabelOfRay(const Vec3& ray, const Vec3& camera = kCamera) {
  double best = INFINITY;
  Vec3 hit = Vec3::Zero();
  for (int axis = 0; axis < 2; ++axis) {
    for (double plane : axis == 0 ? std::array{kX0, kX1} : std::array{kY0, kY1}) {
      if (std::abs(ray[axis]) < 1e-12) continue;
      const double t = (plane - camera[axis]) / ray[axis];
      if (t > 0 && t < best) best = t, hit = camera + t * ray;
    }
  }
  if (!std::isfinite(best) || hit.z() < 0 || hit.z() > kCeiling) return 0;
  if (std::abs(hit.y() - kY1) < 1e-9 && hit.x() > -0.6 && hit.x() < 0.3 && hit.z() < 2.0) return 2;
  return 1;
}

Plan TruthPlan() {
  Plan p;
  const std::vector<Vec2> c = {{kX0, kY0}, {kX1, kY0}, {kX1, kY1}, {kX0, kY1}};
  for (int i = 0; i < 4; ++i) p.walls.push_back({.start = c[i], .end = c[(i + 1) % 4], .height = kCeiling});
  p.openings.push_back({.kind = OpeningKind::kDoor,
                        .wall = 2,
                        .start = {0.3, kY1},
                        .end = {-0.6, kY1},
                        .width = 0.9,
                        .height = 2.0,
                        .sill = 0.0});
  p.rooms.push_back({.polygon = c, .area_m2 = 12.0});
  return p;
}

fs::path Fresh(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("asbuilt_pano_survey_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A grey 2:1 panorama, the capture beside it, and exact labels for the views
// survey cuts (TurnInPlaceViews(SurveyOptions::panorama_views)).
fs::path WritePanoramaCapture(const fs::path& dir, const SurveyOptions& options, const Vec3& camera = kCamera) {
  cv::imwrite((dir / "pano.png").string(), cv::Mat(256, 512, CV_8UC3, cv::Scalar(128, 128, 128)));
  const nlohmann::json capture = {{"version", 1},
                                  {"kind", "panorama"},
                                  {"panorama", "pano.png"},
                                  {"position_m", {camera.x(), camera.y(), camera.z()}}};
  WriteFileAtomic(dir / "capture.json", capture.dump());
  const std::vector<PanoView> views = TurnInPlaceViews(options.panorama_views);
  fs::create_directories(dir / "labels");
  for (std::size_t i = 0; i < views.size(); ++i) {
    const PanoView& view = views[i];
    cv::Mat labels(view.camera.height_px, view.camera.width_px, CV_8U);
    for (int v = 0; v < labels.rows; ++v) {
      for (int u = 0; u < labels.cols; ++u)
        labels.at<unsigned char>(v, u) = LabelOfRay(view.RayInWorld(Vec2(u, v)), camera);
    }
    cv::imwrite((dir / "labels" / fmt::format("{:03d}.png", i)).string(), labels);
  }
  WritePlan(TruthPlan(), dir / "truth.json");
  return dir / "capture.json";
}

SurveyOptions SmallViews() {
  SurveyOptions o{.write_report = false};
  o.panorama_views = {.width_px = 128, .height_px = 256, .fx = 64.0};
  o.plan.door_casing_m = 0.0;  // Exact labels mark the clear opening.
  return o;
}

TEST(RunSurvey, PanoramaCaptureWithExactLabelsRecoversTheBoxRoom) {
  const fs::path dir = Fresh("box");
  SurveyOptions options = SmallViews();
  const fs::path capture = WritePanoramaCapture(dir, options);
  options.labels_dir = dir / "labels";
  const SurveyResult r = RunSurvey(capture, dir / "out", options);
  ASSERT_TRUE(r.summary.score) << r.summary.BriefReport();
  const PlanScore& s = *r.summary.score;
  EXPECT_EQ(r.summary.capture_kind, "panorama");
  EXPECT_EQ(s.walls.matched, 4) << s.Table();
  EXPECT_LE(s.wall_length.Max().value_or(1), 0.02) << s.Table();
  EXPECT_EQ(s.doors.matched, 1) << s.Table();
  EXPECT_LE(s.opening_width.Max().value_or(1), 0.05) << s.Table();
  ASSERT_TRUE(r.summary.room_overlap);
  EXPECT_GE(r.summary.room_overlap->Iou(), 0.98) << r.summary.room_overlap->ToString();
  EXPECT_NEAR(r.summary.ceiling_height_m, kCeiling, 0.03);
  EXPECT_NE(r.summary.wall_cue.find("floor/ceiling contacts"), std::string::npos) << r.summary.wall_cue;
  ASSERT_EQ(r.summary.wall_cues.size(), 4u);
  for (const std::string& c : r.summary.wall_cues) {
    EXPECT_NE(c.find("floor contacts"), std::string::npos) << c;
    EXPECT_NE(c.find("ceiling contacts"), std::string::npos) << c;
  }
  EXPECT_EQ(r.summary.walls_unseen, 0);
  const nlohmann::json summary = nlohmann::json::parse(ReadFile(dir / "out/summary.json"));
  EXPECT_EQ(summary["capture_kind"], "panorama");
  EXPECT_GE(summary["room_iou"].get<double>(), 0.98);
}

// The camera 0.6 m from the door's wall: the views see neither the door's
// foot nor the wall's beside it (the floor shows from 0.7 m), only the wall's
// ceiling edge above the door. The door's sides and head are placed at that
// edge's depth once the ceiling's height is known.
TEST(RunSurvey, PanoramaCaptureMeasuresADoorBesideTheCamera) {
  const fs::path dir = Fresh("near_door");
  SurveyOptions options = SmallViews();
  const fs::path capture = WritePanoramaCapture(dir, options, Vec3(-0.15, 0.9, 1.4));
  options.labels_dir = dir / "labels";
  const SurveyResult r = RunSurvey(capture, dir / "out", options);
  ASSERT_TRUE(r.summary.score) << r.summary.BriefReport();
  const PlanScore& s = *r.summary.score;
  EXPECT_EQ(s.walls.matched, 4) << s.Table();
  EXPECT_EQ(s.doors.matched, 1) << s.Table();
  EXPECT_LE(s.opening_width.Max().value_or(1), 0.05) << s.Table();
}

TEST(RunSurvey, PanoramaCaptureSaysWhenPartOfTheRoomWasNotSeen) {
  // The same room, but views 3–8 (the half behind the camera) see nothing
  // labelled: the walls there are unseen or inferred, and a note says so.
  const fs::path dir = Fresh("half");
  SurveyOptions options = SmallViews();
  const fs::path capture = WritePanoramaCapture(dir, options);
  for (int i = 3; i <= 8; ++i) {
    cv::imwrite((dir / "labels" / fmt::format("{:03d}.png", i)).string(), cv::Mat::zeros(256, 128, CV_8U));
  }
  options.labels_dir = dir / "labels";
  const SurveyResult r = RunSurvey(capture, dir / "out", options);
  EXPECT_GE(r.summary.walls_unseen, 1) << r.summary.BriefReport();
  bool noted = false;
  for (const std::string& n : r.summary.notes)
    noted |= n.find("larger than what this capture sees") != std::string::npos;
  EXPECT_TRUE(noted);
}

// The box room as a photo: dark floor, light walls (each axis its own
// shade), a white ceiling; 2048 × 1024; taken by a camera turned by `lean`.
// `panelled`: walls of 0.6 m panels (vertical lines to level by).
cv::Mat PaintBoxRoom(const Eigen::Matrix3d& lean = Eigen::Matrix3d::Identity(), bool panelled = false) {
  cv::Mat out(1024, 2048, CV_8UC3);
  for (int y = 0; y < out.rows; ++y) {
    for (int x = 0; x < out.cols; ++x) {
      const Vec3 ray = lean * DirectionFromEquirectPixel(Vec2(x, y), out.cols, out.rows);
      double best = INFINITY;
      int axis_hit = 0;
      for (int axis = 0; axis < 2; ++axis) {
        for (double plane : axis == 0 ? std::array{kX0, kX1} : std::array{kY0, kY1}) {
          if (std::abs(ray[axis]) < 1e-12) continue;
          const double t = (plane - kCamera[axis]) / ray[axis];
          if (t > 0 && t < best) best = t, axis_hit = axis;
        }
      }
      const double z = kCamera.z() + best * ray.z();
      cv::Vec3b& p = out.at<cv::Vec3b>(y, x);
      if (z < 0) {
        p = {50, 80, 120};
      } else if (z > kCeiling) {
        p = {240, 240, 240};
      } else {
        p = axis_hit == 0 ? cv::Vec3b{190, 195, 200} : cv::Vec3b{170, 175, 180};
        const Vec3 hit = kCamera + best * ray;
        const double along = axis_hit == 0 ? hit.y() : hit.x();
        if (panelled && std::abs(std::remainder(along, 0.6)) < 0.01) p -= cv::Vec3b(30, 30, 30);
      }
    }
  }
  return out;
}

// A panorama capture of the painted box room in a fresh folder, its truth beside it.
fs::path WritePaintedCapture(const std::string& name, const cv::Mat& pano) {
  const fs::path dir = Fresh(name);
  cv::imwrite((dir / "pano.png").string(), pano);
  const nlohmann::json capture = {{"version", 1},
                                  {"kind", "panorama"},
                                  {"panorama", "pano.png"},
                                  {"position_m", {kCamera.x(), kCamera.y(), kCamera.z()}}};
  WriteFileAtomic(dir / "capture.json", capture.dump());
  WritePlan(TruthPlan(), dir / "truth.json");
  return dir / "capture.json";
}

TEST(RunSurvey, PanoramaLayoutRecoversTheBoxRoomFromThePhoto) {
  if (!SegmenterAvailable() || !fs::exists(DefaultModelPath())) GTEST_SKIP() << "no segmenter in this build";
  const fs::path capture = WritePaintedCapture("layout", PaintBoxRoom());
  const fs::path dir = capture.parent_path();
  SurveyOptions options{.pano_layout = true, .write_report = true};
  const SurveyResult r = RunSurvey(capture, dir / "out", options);
  ASSERT_TRUE(r.summary.room_overlap) << r.summary.BriefReport();
  EXPECT_GT(r.summary.room_overlap->Iou(), 0.9) << r.summary.BriefReport();
  EXPECT_NEAR(r.summary.ceiling_height_m, kCeiling, 0.05);
  EXPECT_TRUE(fs::exists(dir / "out" / "layout.png"));
  EXPECT_NE(r.summary.labels_source.find("redrawn on the panorama's layout"), std::string::npos);
}

TEST(RunSurvey, PanoramaSegmentedThroughTurnedViewsRecoversThePaintedRoom) {
  if (!SegmenterAvailable() || !fs::exists(DefaultModelPath())) GTEST_SKIP() << "no segmenter in this build";
  const fs::path capture = WritePaintedCapture("turned", PaintBoxRoom());
  const fs::path dir = capture.parent_path();
  SurveyOptions options{.write_report = false};
  options.panorama_views = {.width_px = 256, .height_px = 512, .fx = 128.0};  // Quick: a quarter of the pixels.
  options.segment_wide_views = true;
  const SurveyResult r = RunSurvey(capture, dir / "out", options);
  EXPECT_NE(r.summary.labels_source.find("three 40°-turned square views"), std::string::npos)
      << r.summary.labels_source;
  ASSERT_TRUE(r.summary.room_overlap) << r.summary.BriefReport();
  EXPECT_GT(r.summary.room_overlap->Iou(), 0.8) << r.summary.BriefReport();
  // Surveyed with the renders-only model, a panorama says which model reads real photos.
  const bool renders = IsRendersOnlyModel(DefaultModelPath());
  const bool noted = std::any_of(r.summary.notes.begin(), r.summary.notes.end(),
                                 [](const std::string& n) { return n.find("--model real") != std::string::npos; });
  EXPECT_EQ(noted, renders);
}

TEST(RunSurvey, ATiltedPanoramaIsLevelledAndSurveyedAsWellAsALevelOne) {
  if (!SegmenterAvailable() || !fs::exists(DefaultModelPath())) GTEST_SKIP() << "no segmenter in this build";
  auto survey = [](const std::string& name, const Eigen::Matrix3d& lean) {
    const fs::path capture = WritePaintedCapture(name, PaintBoxRoom(lean, /*panelled=*/true));
    SurveyOptions options{.write_report = false};
    options.panorama_views = {.width_px = 256, .height_px = 512, .fx = 128.0};  // Quick: a quarter of the pixels.
    return RunSurvey(capture, capture.parent_path() / "out", options);
  };
  const SurveyResult level = survey("level", Eigen::Matrix3d::Identity());
  const SurveyResult tilted =
      survey("leaning", Eigen::AngleAxisd(DegToRad(1.5), Vec3(1, 1, 0).normalized()).toRotationMatrix());
  ASSERT_TRUE(tilted.summary.panorama_tilt);
  EXPECT_TRUE(tilted.summary.panorama_levelled);
  EXPECT_NEAR(tilted.summary.panorama_tilt->tilt_deg, 1.5, 0.1) << tilted.summary.panorama_tilt->BriefReport();
  ASSERT_TRUE(level.summary.room_overlap && tilted.summary.room_overlap)
      << "level: " << level.summary.BriefReport() << "\ntilted: " << tilted.summary.BriefReport();
  EXPECT_GT(tilted.summary.room_overlap->Iou(), level.summary.room_overlap->Iou() - 0.02)
      << "level: " << level.summary.BriefReport() << "\ntilted: " << tilted.summary.BriefReport();
  EXPECT_TRUE(fs::exists(fs::temp_directory_path() / "asbuilt_pano_survey_leaning/out/review/panorama.jpg"));
}

// A camera on a tripod whose axis leans 1.5°: eight portrait views of the
// painted room, turned 45° apart, each said to be level. The survey reads the
// rig's lean from the views' lines and surveys them levelled: each is then
// the view a level rig takes (the review draws on them).
TEST(RunSurvey, AMonoRigThatLeansIsSurveyedFromItsViewsLevelled) {
  if (!SegmenterAvailable() || !fs::exists(DefaultModelPath())) GTEST_SKIP() << "no segmenter in this build";
  const std::vector<PanoView> views =
      TurnInPlaceViews({.width_px = 256, .height_px = 512, .fx = 128.0, .views = 8, .yaw_step_deg = 45.0});
  const Image level_pano = AsImage(PaintBoxRoom(Eigen::Matrix3d::Identity(), /*panelled=*/true));
  const Image leaning_pano =
      AsImage(PaintBoxRoom(Eigen::AngleAxisd(DegToRad(1.5), Vec3(1, -1, 0).normalized()).toRotationMatrix(), true));
  const fs::path dir = Fresh("mono_leaning");
  nlohmann::json frames = nlohmann::json::array();
  for (std::size_t i = 0; i < views.size(); ++i) {
    const std::string file = fmt::format("v{}.png", i);
    cv::imwrite((dir / file).string(), AsMat(RenderPanoView(leaning_pano, views[i])));
    frames.push_back({{"index", i},
                      {"image", file},
                      {"yaw_deg", views[i].yaw_deg},
                      {"position_m", {kCamera.x(), kCamera.y(), kCamera.z()}}});
  }
  const nlohmann::json capture = {
      {"version", 1},
      {"kind", "mono"},
      {"camera", {{"width", 256}, {"height", 512}, {"fx", 128}, {"fy", 128}, {"cx", 127.5}, {"cy", 255.5}}},
      {"frames", frames}};
  WriteFileAtomic(dir / "capture.json", capture.dump());
  const SurveyResult r = RunSurvey(dir / "capture.json", dir / "out", {.write_report = false});
  ASSERT_TRUE(r.summary.panorama_tilt);
  EXPECT_TRUE(r.summary.panorama_levelled);
  EXPECT_NEAR(r.summary.panorama_tilt->tilt_deg, 1.5, 0.15) << r.summary.panorama_tilt->BriefReport();
  // Each view as surveyed against the level rig's: far closer than as taken.
  auto grey = [](const cv::Mat& bgr) {
    cv::Mat g;
    cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
    return g;
  };
  for (std::size_t i = 0; i < views.size(); i += 3) {
    const cv::Mat want = grey(AsMat(RenderPanoView(level_pano, views[i])));
    const cv::Mat taken = grey(AsMat(RenderPanoView(leaning_pano, views[i])));
    const cv::Mat surveyed =
        cv::imread((dir / "out/review/views" / fmt::format("{:03d}.jpg", i)).string(), cv::IMREAD_GRAYSCALE);
    ASSERT_EQ(surveyed.size(), want.size()) << i;
    cv::Mat d_taken, d_surveyed;
    cv::absdiff(taken, want, d_taken);
    cv::absdiff(surveyed, want, d_surveyed);
    EXPECT_LT(cv::mean(d_surveyed)[0], 0.5 * cv::mean(d_taken)[0]) << "view " << i;
  }
}

TEST(RunSurvey, MonoCaptureWithATiltedViewIsRefusedAndWritesNothing) {
  const fs::path dir = Fresh("tilted");
  cv::imwrite((dir / "v.png").string(), cv::Mat(48, 64, CV_8UC3, cv::Scalar(128, 128, 128)));
  WriteFileAtomic(dir / "capture.json", R"({"version": 1, "kind": "mono",
      "camera": {"width": 64, "height": 48, "fx": 40, "fy": 40, "cx": 31.5, "cy": 23.5},
      "frames": [{"index": 0, "image": "v.png", "yaw_deg": 0, "pitch_deg": 10, "position_m": [0, 0, 1.4]}]})");
  try {
    RunSurvey(dir / "capture.json", dir / "out", {.labels_dir = dir, .write_report = false});
    FAIL() << "a tilted mono view was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("frames[0].pitch_deg"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace asbuilt
