// The verdict (plan/verdict.h) on panorama surveys of a synthetic room
// whose labels are drawn exactly from its geometry, with known faults put
// in: a wrong camera height, a tilted camera, a mirror, a wall hidden
// behind furniture, a door labelled as wall. The clean room is "good"; each
// fault lowers the verdict and names its cause.

#include <array>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/pipeline/survey.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace verdict_room {  // Named: the test's unity build shares a file with pano_survey_test's box room.
namespace fs = std::filesystem;

// A 5.0 × 4.0 m room, 2.6 m high; a 0.9 m door (2.05 m high) on the north
// wall (y = 2) from x = −1.2 to −0.3; the camera 1.5 m above (0.3, −0.4).
constexpr double kX0 = -2.5, kX1 = 2.5, kY0 = -2.0, kY1 = 2.0, kCeiling = 2.6;
constexpr double kDoorX0 = -1.2, kDoorX1 = -0.3, kDoorTop = 2.05;

struct Faults {
  double claimed_height_m = 1.5;  // The camera height capture.json states (true: 1.5).
  double tilt_deg = 0.0;          // The camera leans this far toward +x.
  bool mirror = false;            // A 1.6 m wide floor-to-2 m mirror on the east wall.
  bool furniture = false;         // A 0.9 m high, 0.6 m deep sideboard along most of the south wall.
  bool door_as_wall = false;      // The door labelled as wall.
};

const Vec3 kCamera(0.3, -0.4, 1.5);

unsigned char LabelOfRay(Vec3 origin, Vec3 ray, const Faults& f, int depth = 0) {
  double best = INFINITY;
  int axis_hit = -1;
  double plane_hit = 0;
  for (int axis = 0; axis < 2; ++axis) {
    for (double plane : axis == 0 ? std::array{kX0, kX1} : std::array{kY0, kY1}) {
      if (std::abs(ray[axis]) < 1e-12) continue;
      const double t = (plane - origin[axis]) / ray[axis];
      if (t > 1e-9 && t < best) best = t, axis_hit = axis, plane_hit = plane;
    }
  }
  if (f.furniture) {  // The sideboard's top and front faces.
    constexpr double kFx0 = -2.0, kFx1 = 1.6, kFy = kY0 + 0.6, kFz = 0.9;
    if (std::abs(ray.z()) > 1e-12) {
      const double t = (kFz - origin.z()) / ray.z();
      const Vec3 p = origin + t * ray;
      if (t > 0 && t < best && p.x() > kFx0 && p.x() < kFx1 && p.y() < kFy && p.y() > kY0) return 0;
    }
    if (std::abs(ray.y()) > 1e-12) {
      const double t = (kFy - origin.y()) / ray.y();
      const Vec3 p = origin + t * ray;
      if (t > 0 && t < best && p.x() > kFx0 && p.x() < kFx1 && p.z() < kFz && p.z() > 0) return 0;
    }
  }
  if (!std::isfinite(best)) return 0;
  const Vec3 hit = origin + best * ray;
  if (hit.z() < 0 || hit.z() > kCeiling) return 0;
  if (f.mirror && depth == 0 && axis_hit == 0 && plane_hit == kX1 && hit.y() > -0.6 && hit.y() < 1.0 && hit.z() < 2.0) {
    return LabelOfRay(hit, Vec3(-ray.x(), ray.y(), ray.z()), f, depth + 1);
  }
  if (axis_hit == 1 && plane_hit == kY1 && hit.x() > kDoorX0 && hit.x() < kDoorX1 && hit.z() < kDoorTop) {
    return f.door_as_wall ? 1 : 2;
  }
  return 1;
}

Plan TruthPlan() {
  Plan p;
  const std::vector<Vec2> c = {{kX0, kY0}, {kX1, kY0}, {kX1, kY1}, {kX0, kY1}};
  for (int i = 0; i < 4; ++i) p.walls.push_back({.start = c[i], .end = c[(i + 1) % 4], .height = kCeiling});
  p.openings.push_back({.kind = OpeningKind::kDoor,
                        .wall = 2,
                        .start = {kDoorX1, kY1},
                        .end = {kDoorX0, kY1},
                        .width = kDoorX1 - kDoorX0,
                        .height = kDoorTop,
                        .sill = 0.0});
  p.rooms.push_back({.polygon = c, .area_m2 = (kX1 - kX0) * (kY1 - kY0)});
  return p;
}

SurveyOptions Options() {
  SurveyOptions o{.write_report = false};
  o.panorama_views = {.width_px = 160, .height_px = 320, .fx = 80.0};
  o.plan.door_casing_m = 0.0;  // Exact labels mark the clear opening.
  return o;
}

// Labels of the views the survey cuts, drawn through the (faulty) camera.
SurveyResult SurveyWith(const std::string& name, const Faults& faults) {
  const fs::path dir = fs::temp_directory_path() / ("asbuilt_verdict_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir / "labels");
  SurveyOptions options = Options();
  cv::imwrite((dir / "pano.png").string(), cv::Mat(256, 512, CV_8UC3, cv::Scalar(128, 128, 128)));
  const nlohmann::json capture = {{"version", 1},
                                  {"kind", "panorama"},
                                  {"panorama", "pano.png"},
                                  {"position_m", {kCamera.x(), kCamera.y(), faults.claimed_height_m}}};
  WriteFileAtomic(dir / "capture.json", capture.dump());
  const double tilt = faults.tilt_deg * 3.14159265358979323846 / 180.0;
  const Eigen::Matrix3d lean = Eigen::AngleAxisd(tilt, Vec3::UnitY()).toRotationMatrix();
  const std::vector<PanoView> views = TurnInPlaceViews(options.panorama_views);
  for (std::size_t i = 0; i < views.size(); ++i) {
    cv::Mat labels(views[i].camera.height_px, views[i].camera.width_px, CV_8U);
    for (int v = 0; v < labels.rows; ++v) {
      for (int u = 0; u < labels.cols; ++u) {
        labels.at<unsigned char>(v, u) = LabelOfRay(kCamera, lean * views[i].RayInWorld(Vec2(u, v)), faults);
      }
    }
    cv::imwrite((dir / "labels" / fmt::format("{:03d}.png", i)).string(), labels);
  }
  WritePlan(TruthPlan(), dir / "truth.json");
  options.labels_dir = dir / "labels";
  return RunSurvey(dir / "capture.json", dir / "out", options);
}

std::string Reasons(const PlanVerdict& v) {
  std::string out = v.BriefReport();
  for (std::size_t w = 0; w < v.walls.size(); ++w) {
    out += fmt::format("\n  wall {}: {} {:.2f}", w, VerdictName(v.walls[w].verdict), v.walls[w].confidence);
    for (const std::string& r : v.walls[w].reasons) out += "; " + r;
  }
  return out;
}

bool Mentions(const PlanVerdict& v, const std::string& word) {
  if (v.BriefReport().find(word) != std::string::npos) return true;
  for (const WallVerdict& w : v.walls) {
    for (const std::string& r : w.reasons) {
      if (r.find(word) != std::string::npos) return true;
    }
  }
  return false;
}

TEST(Verdict, TheCleanRoomIsGood) {
  const SurveyResult r = SurveyWith("clean", {});
  ASSERT_TRUE(r.summary.room_overlap);
  EXPECT_GE(r.summary.room_overlap->Iou(), 0.97) << r.summary.BriefReport();
  const PlanVerdict& v = r.summary.verdict;
  EXPECT_EQ(v.verdict, Verdict::kGood) << Reasons(v);
  EXPECT_GE(v.confidence, 0.85) << Reasons(v);
  for (const WallVerdict& w : v.walls) EXPECT_EQ(w.verdict, Verdict::kGood) << Reasons(v);
  EXPECT_LT(v.tilt.tilt_deg, 0.05);
}

TEST(Verdict, AWrongCameraHeightIsNamed) {
  const SurveyResult r = SurveyWith("height", {.claimed_height_m = 1.0});
  const PlanVerdict& v = r.summary.verdict;
  EXPECT_NE(v.verdict, Verdict::kGood) << Reasons(v);
  EXPECT_TRUE(Mentions(v, "camera height")) << Reasons(v);
}

TEST(Verdict, ATiltedCameraIsNamed) {
  const SurveyResult r = SurveyWith("tilt", {.tilt_deg = 2.0});
  const PlanVerdict& v = r.summary.verdict;
  EXPECT_NE(v.verdict, Verdict::kGood) << Reasons(v);
  EXPECT_TRUE(Mentions(v, "tilt")) << Reasons(v);
  EXPECT_NEAR(v.tilt.tilt_deg, 2.0, 0.15);
  EXPECT_NEAR(std::remainder(v.tilt.toward_deg, 360.0), 0.0, 5.0);  // Leaning toward +x.
}

TEST(Verdict, AMirrorIsNamed) {
  const SurveyResult r = SurveyWith("mirror", {.mirror = true});
  const PlanVerdict& v = r.summary.verdict;
  EXPECT_NE(v.verdict, Verdict::kGood) << Reasons(v);
  EXPECT_TRUE(Mentions(v, "mirror")) << Reasons(v);
  EXPECT_NE(v.walls[1].verdict, Verdict::kGood) << Reasons(v);  // The east wall, x = 2.5.
}

TEST(Verdict, AWallHiddenByFurnitureIsNamed) {
  const SurveyResult r = SurveyWith("furniture", {.furniture = true});
  const PlanVerdict& v = r.summary.verdict;
  EXPECT_TRUE(Mentions(v, "furniture")) << Reasons(v);
  EXPECT_NE(v.walls[0].verdict, Verdict::kGood) << Reasons(v);  // The south wall, y = −2.
  EXPECT_FALSE(Mentions(v, "tilt")) << Reasons(v);              // The sideboard's top is no lean.
  // summary.json carries each wall's evidence, the hidden floor edge among it.
  const nlohmann::json summary =
      nlohmann::json::parse(ReadFile(fs::temp_directory_path() / "asbuilt_verdict_furniture/out/summary.json"));
  const nlohmann::json& south = summary.at("verdict_evidence").at("walls").at(0);
  EXPECT_NEAR(south.at("hidden_floor").get<double>(), v.walls[0].evidence.hidden_floor, 1e-9) << south.dump();
  EXPECT_GT(south.at("hidden_floor").get<double>(), 0.5) << south.dump();
  EXPECT_TRUE(south.contains("offset_sigma_m") && south.contains("run_on_m")) << south.dump();
}

}  // namespace verdict_room
}  // namespace asbuilt
