#include "asbuilt/pipeline/home_survey.h"

#include <array>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/pano/perspective.h"
#include "asbuilt/render/home_render.h"
#include "asbuilt/scene/procedural_home.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

// A box room in its capture's own frame (the camera above the origin, 1.4 m
// up; 2.5 m ceiling) with one 0.9 m door, 2.0 m high, on the wall x = x1
// (east) or x = x0 (west), from y = door_y0 to door_y1.
struct BoxRoom {
  double x0, x1, y0, y1;
  bool door_east;
  double door_y0, door_y1;

  unsigned char LabelOfRay(const Vec3& ray) const {
    const Vec3 camera(0, 0, 1.4);
    double best = INFINITY;
    Vec3 hit = Vec3::Zero();
    for (int axis = 0; axis < 2; ++axis) {
      for (double plane : axis == 0 ? std::array{x0, x1} : std::array{y0, y1}) {
        if (std::abs(ray[axis]) < 1e-12) continue;
        const double t = (plane - camera[axis]) / ray[axis];
        if (t > 0 && t < best) best = t, hit = camera + t * ray;
      }
    }
    if (!std::isfinite(best) || hit.z() < 0 || hit.z() > 2.5) return 0;
    const double door_x = door_east ? x1 : x0;
    if (std::abs(hit.x() - door_x) < 1e-9 && hit.y() > door_y0 && hit.y() < door_y1 && hit.z() < 2.0) return 2;
    return 1;
  }
};

SurveyOptions HomeSmallViews() {
  SurveyOptions o{.write_report = false};
  o.panorama_views = {.width_px = 128, .height_px = 256, .fx = 64.0};
  o.plan.door_casing_m = 0.0;  // Exact labels mark the clear opening.
  return o;
}

// The room's panorama capture and its exact view labels in DIR.
void WriteRoom(const fs::path& dir, const BoxRoom& room, const SurveyOptions& options) {
  fs::create_directories(dir / "labels");
  cv::imwrite((dir / "pano.png").string(), cv::Mat(256, 512, CV_8UC3, cv::Scalar(128, 128, 128)));
  const nlohmann::json capture = {
      {"version", 1}, {"kind", "panorama"}, {"panorama", "pano.png"}, {"position_m", {0.0, 0.0, 1.4}}};
  WriteFileAtomic(dir / "capture.json", capture.dump());
  const std::vector<PanoView> views = TurnInPlaceViews(options.panorama_views);
  for (std::size_t i = 0; i < views.size(); ++i) {
    cv::Mat labels(views[i].camera.height_px, views[i].camera.width_px, CV_8U);
    for (int v = 0; v < labels.rows; ++v) {
      for (int u = 0; u < labels.cols; ++u) {
        labels.at<unsigned char>(v, u) = room.LabelOfRay(views[i].RayInWorld(Vec2(u, v)));
      }
    }
    cv::imwrite((dir / "labels" / fmt::format("{:03d}.png", i)).string(), labels);
  }
}

fs::path FreshHomeDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("asbuilt_home_survey_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Two rooms through one door, in home axes: the living room x −2..2,
// y −1.5..1.5 (its capture frame is the home frame), a door on x = 2 for
// y 0.2..1.1; the study across a 0.12 m partition, x 2.12..5.12, its camera
// at (3.62, 0) and its capture frame turned 90° (the study's own x runs
// north). `with_missing_room` adds a room whose capture does not exist.
fs::path WriteTwoRoomHome(const fs::path& dir, const SurveyOptions& options, bool with_missing_room) {
  WriteRoom(dir / "living", BoxRoom{-2, 2, -1.5, 1.5, true, 0.2, 1.1}, options);
  // A ray in the study's frame, turned into home axes.
  struct Turned {
    BoxRoom b;
    unsigned char operator()(const Vec3& ray) const { return b.LabelOfRay(Vec3(-ray.y(), ray.x(), ray.z())); }
  };
  const BoxRoom study_home_axes{-1.5, 1.5, -1.5, 1.5, false, 0.2, 1.1};
  const fs::path sdir = dir / "study";
  fs::create_directories(sdir / "labels");
  cv::imwrite((sdir / "pano.png").string(), cv::Mat(256, 512, CV_8UC3, cv::Scalar(128, 128, 128)));
  WriteFileAtomic(
      sdir / "capture.json",
      nlohmann::json{{"version", 1}, {"kind", "panorama"}, {"panorama", "pano.png"}, {"position_m", {0.0, 0.0, 1.4}}}
          .dump());
  const Turned turned{study_home_axes};
  const std::vector<PanoView> views = TurnInPlaceViews(options.panorama_views);
  for (std::size_t i = 0; i < views.size(); ++i) {
    cv::Mat labels(views[i].camera.height_px, views[i].camera.width_px, CV_8U);
    for (int v = 0; v < labels.rows; ++v) {
      for (int u = 0; u < labels.cols; ++u) labels.at<unsigned char>(v, u) = turned(views[i].RayInWorld(Vec2(u, v)));
    }
    cv::imwrite((sdir / "labels" / fmt::format("{:03d}.png", i)).string(), labels);
  }
  nlohmann::json rooms =
      nlohmann::json::array({{{"name", "living"}, {"capture", "living/capture.json"}, {"labels", "living/labels"}},
                             {{"name", "study"}, {"capture", "study/capture.json"}, {"labels", "study/labels"}}});
  if (with_missing_room) rooms.push_back({{"name", "cellar"}, {"capture", "cellar/capture.json"}});
  WriteFileAtomic(dir / "home.json", nlohmann::json{{"version", 1}, {"kind", "home"}, {"rooms", rooms}}.dump(2));
  return dir / "home.json";
}

TEST(RunHomeSurvey, PlacesTwoRoomsThroughTheirDoorAndWritesOnePlan) {
  const fs::path dir = FreshHomeDir("two");
  HomeSurveyOptions options;
  options.survey = HomeSmallViews();
  const fs::path home = WriteTwoRoomHome(dir, options.survey, /*with_missing_room=*/true);
  std::vector<std::string> lines;
  const HomeSurveyResult r =
      RunHomeSurvey(home, dir / "out", options, [&](const std::string& l) { lines.push_back(l); });
  // One line per room, the missing capture named and the others surveyed.
  ASSERT_EQ(lines.size(), 3u);
  ASSERT_EQ(r.rooms.size(), 3u);
  EXPECT_TRUE(r.rooms[0].ok) << r.rooms[0].error;
  EXPECT_TRUE(r.rooms[1].ok) << r.rooms[1].error;
  EXPECT_FALSE(r.rooms[2].ok);
  EXPECT_NE(r.rooms[2].error.find("rooms[2].capture"), std::string::npos) << r.rooms[2].error;
  ASSERT_EQ(r.placement.best.Placed(), 2) << r.placement.best.ToString(r.inputs);
  // The study's capture frame: origin at (3.62, 0) turned 90° — its door's
  // face 0.12 m from the living room's by the default partition.
  const Eigen::Isometry2d& study = r.placement.best.rooms[1].floor_from_room;
  EXPECT_NEAR(study.translation().x(), 3.62, 0.06) << r.placement.best.ToString(r.inputs);
  EXPECT_NEAR(study.translation().y(), 0.0, 0.06) << r.placement.best.ToString(r.inputs);
  EXPECT_NEAR(std::abs(std::remainder(YawOf(study) - std::numbers::pi / 2, 2 * std::numbers::pi)), 0.0, 0.02);
  // One plan: two named rooms, the door once between them.
  const Plan plan = ReadPlan(dir / "out/plan.json");
  ASSERT_EQ(plan.rooms.size(), 2u);
  EXPECT_EQ(*plan.rooms[1].name, "study");
  EXPECT_NEAR(plan.rooms[0].area_m2 + plan.rooms[1].area_m2, 12.0 + 9.0, 0.4);
  int joined = 0;
  for (const PlanOpening& o : plan.openings) joined += o.rooms.has_value();
  EXPECT_EQ(joined, 1);
  for (const char* f : {"plan.svg", "plan.dxf", "plan.pdf", "plan.ifc", "summary.json", "rooms/living/plan.json",
                        "rooms/study/plan.json"}) {
    EXPECT_TRUE(fs::exists(dir / "out" / f)) << f;
  }
  EXPECT_FALSE(fs::exists(dir / "out/rooms/cellar"));
  const nlohmann::json summary = nlohmann::json::parse(ReadFile(dir / "out/summary.json"));
  EXPECT_EQ(summary["placed"], 2);
  EXPECT_EQ(summary["rooms"][2]["surveyed"], false);
  EXPECT_NE(ReadFile(dir / "out/plan.svg").find("STUDY"), std::string::npos);
}

TEST(RunHomeSurvey, ABadHomeFileIsRefusedBeforeAnythingIsWritten) {
  const fs::path dir = FreshHomeDir("bad");
  WriteFileAtomic(dir / "home.json",
                  R"({"version": 1, "kind": "home", "rooms": [{"name": "a", "capture": "a.json"},
                      {"name": "a", "capture": "b.json"}, {"name": "../x", "capture": "c.json"}]})");
  try {
    RunHomeSurvey(dir / "home.json", dir / "out");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("rooms[1].name"), std::string::npos) << what;
    EXPECT_NE(what.find("also rooms[0]'s name"), std::string::npos) << what;
    EXPECT_NE(what.find("rooms[2].name"), std::string::npos) << what;
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
  WriteFileAtomic(dir / "empty.json", R"({"version": 1, "kind": "home", "rooms": []})");
  EXPECT_THROW(RunHomeSurvey(dir / "empty.json", dir / "out"), InputError);
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// A home rendered by our renderer (scene/procedural_home.h,
// render/home_render.h): three or four rooms with a door in every partition,
// each a stereo capture turning in place in a frame of its own, surveyed
// with their exact labels; every room placed within 10 cm and 1°.
TEST(RunHomeSurvey, ARenderedHomeIsPlacedWithItsPartitionsMeasured) {
  const fs::path dir = std::filesystem::temp_directory_path() / "asbuilt_home_survey_rendered";
  std::filesystem::remove_all(dir);
  SceneRng rng(3);
  const HomeLayout layout = MakeHomeLayout(rng, {.min_rooms = 3,
                                                 .max_rooms = 4,
                                                 .min_width_m = 6.5,
                                                 .max_width_m = 7.5,
                                                 .min_depth_m = 5.0,
                                                 .max_depth_m = 6.0,
                                                 .min_room_m = 2.5,
                                                 .extra_door = 1.0});
  const Scene scene = HomeScene(layout, 3);
  HomeRenderOptions render;
  render.capture.views = 8;
  render.capture.width_px = 320;
  render.capture.height_px = 240;
  render.capture.render.samples_per_pixel = 1;
  render.capture.render.indirect_light = false;
  render.capture.render.camera_effects = 0;
  const HomeRenderSummary rendered = RenderHome(scene, dir / "home", render);
  ASSERT_EQ(rendered.rooms.size(), layout.rooms.size());

  HomeSurveyOptions options;
  options.survey.use_capture_labels = true;
  options.survey.write_report = false;
  const HomeSurveyResult r = RunHomeSurvey(rendered.home_json, dir / "out", options);
  ASSERT_EQ(r.placement.best.Placed(), static_cast<int>(layout.rooms.size())) << r.placement.best.ToString(r.inputs);
  std::vector<std::vector<Vec2>> outlines = layout.rooms;
  const HomeScore score = ScoreHome(r.inputs, r.placement.best, rendered.floor_from_room, outlines);
  std::string errors;
  for (std::size_t k = 0; k < score.centroid_error_m.size(); ++k) {
    errors += fmt::format(" {:.3f} m {:.2f}°", score.centroid_error_m[k], score.yaw_error_deg[k]);
  }
  EXPECT_EQ(score.within, score.rooms) << r.placement.best.ToString(r.inputs) << "\n" << errors;
  EXPECT_GT(score.floor_iou, 0.95);
  // Each partition's thickness as the two rooms' surveys put its faces: each
  // survey places a face a little inside its room (issue 37's bias), so more
  // than the placement alone gives from exact plans (docs/home.md).
  int partitions = 0;
  for (const PlanWall& w : r.plan.walls) {
    if (!w.thickness) continue;
    ++partitions;
    EXPECT_NEAR(*w.thickness, layout.wall_thickness_m, 0.05);
  }
  EXPECT_GE(partitions, static_cast<int>(layout.rooms.size()) - 1);
}

}  // namespace
}  // namespace asbuilt
