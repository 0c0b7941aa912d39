#include "asbuilt/review/review_test_fixtures.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <mutex>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/pano/perspective.h"
#include "asbuilt/pipeline/demo.h"
#include "asbuilt/pipeline/survey.h"
#include "asbuilt/util/file.h"

namespace asbuilt::review_test {
namespace fs = std::filesystem;
namespace {

unsigned char LabelOfRay(const Vec3& ray) {
  double best = INFINITY;
  Vec3 hit = Vec3::Zero();
  for (int axis = 0; axis < 2; ++axis) {
    for (double plane : axis == 0 ? std::array{kX0, kX1} : std::array{kY0, kY1}) {
      if (std::abs(ray[axis]) < 1e-12) continue;
      const double t = (plane - kCamera[axis]) / ray[axis];
      if (t > 0 && t < best) best = t, hit = kCamera + t * ray;
    }
  }
  if (!std::isfinite(best) || hit.z() < 0 || hit.z() > kCeiling) return 0;
  if (std::abs(hit.y() - kY1) < 1e-9 && hit.x() > -0.6 && hit.x() < 0.3 && hit.z() < 2.0) return 2;
  return 1;
}

fs::path Root() { return fs::temp_directory_path() / fmt::format("asbuilt_review_test_{}", ::getpid()); }

fs::path MakePanoramaSurvey() {
  const fs::path dir = Root() / "pano_source";
  fs::remove_all(dir);
  fs::create_directories(dir / "labels");
  // A painted panorama: floor dark, walls light, ceiling white (only shown, never read).
  cv::Mat pano(kPanoHeight, kPanoWidth, CV_8UC3);
  for (int v = 0; v < kPanoHeight; ++v) {
    for (int u = 0; u < kPanoWidth; ++u) {
      const Vec3 ray = DirectionFromEquirectPixel(Vec2(u, v), kPanoWidth, kPanoHeight);
      const unsigned char label = LabelOfRay(ray);
      pano.at<cv::Vec3b>(v, u) = label == 2    ? cv::Vec3b(60, 90, 140)
                                 : label == 1  ? cv::Vec3b(200, 205, 210)
                                 : ray.z() > 0 ? cv::Vec3b(250, 250, 250)
                                               : cv::Vec3b(90, 100, 110);
    }
  }
  cv::imwrite((dir / "pano.png").string(), pano);
  const nlohmann::json capture = {{"version", 1},
                                  {"kind", "panorama"},
                                  {"panorama", "pano.png"},
                                  {"position_m", {kCamera.x(), kCamera.y(), kCamera.z()}}};
  WriteFileAtomic(dir / "capture.json", capture.dump());
  SurveyOptions options{.write_report = false};
  options.panorama_views = {.width_px = 128, .height_px = 256, .fx = 64.0};
  options.plan.door_casing_m = 0.0;  // Exact labels mark the clear opening.
  const std::vector<PanoView> views = TurnInPlaceViews(options.panorama_views);
  for (std::size_t i = 0; i < views.size(); ++i) {
    cv::Mat labels(views[i].camera.height_px, views[i].camera.width_px, CV_8U);
    for (int v = 0; v < labels.rows; ++v) {
      for (int u = 0; u < labels.cols; ++u) {
        labels.at<unsigned char>(v, u) = LabelOfRay(views[i].RayInWorld(Vec2(u, v)));
      }
    }
    cv::imwrite((dir / "labels" / fmt::format("{:03d}.png", i)).string(), labels);
  }
  options.labels_dir = dir / "labels";
  RunSurvey(dir / "capture.json", dir / "out", options);
  return dir / "out";
}

// The label a ray from kLCamera sees in the L room (walls only, no openings).
unsigned char LRoomLabelOfRay(const Vec3& ray) {
  const std::vector<Vec2> c = LRoomCorners();
  double best = INFINITY;
  const Vec2 o = kLCamera.head<2>(), d = ray.head<2>();
  for (std::size_t i = 0; i < c.size(); ++i) {
    const Vec2 a = c[i], e = c[(i + 1) % c.size()] - a;
    const double denom = Cross(d, e);
    if (std::abs(denom) < 1e-12) continue;
    const double t = Cross(a - o, e) / denom, s = Cross(a - o, d) / denom;
    if (t > 0 && s >= 0 && s <= 1) best = std::min(best, t);
  }
  if (!std::isfinite(best)) return 0;
  const double z = kLCamera.z() + best * ray.z();
  return z >= 0 && z <= kCeiling ? 1 : 0;
}

fs::path MakeLRoomSurvey() {
  const fs::path dir = Root() / "lroom_source";
  fs::remove_all(dir);
  fs::create_directories(dir / "labels");
  cv::Mat pano(kPanoHeight, kPanoWidth, CV_8UC3, cv::Scalar(180, 180, 180));
  cv::imwrite((dir / "pano.png").string(), pano);
  const nlohmann::json capture = {{"version", 1},
                                  {"kind", "panorama"},
                                  {"panorama", "pano.png"},
                                  {"position_m", {kLCamera.x(), kLCamera.y(), kLCamera.z()}}};
  WriteFileAtomic(dir / "capture.json", capture.dump());
  SurveyOptions options{.write_report = false};
  options.panorama_views = {.width_px = 128, .height_px = 256, .fx = 64.0};
  const std::vector<PanoView> views = TurnInPlaceViews(options.panorama_views);
  for (std::size_t i = 0; i < views.size(); ++i) {
    cv::Mat labels(views[i].camera.height_px, views[i].camera.width_px, CV_8U);
    for (int v = 0; v < labels.rows; ++v) {
      for (int u = 0; u < labels.cols; ++u) {
        labels.at<unsigned char>(v, u) = LRoomLabelOfRay(views[i].RayInWorld(Vec2(u, v)));
      }
    }
    cv::imwrite((dir / "labels" / fmt::format("{:03d}.png", i)).string(), labels);
  }
  options.labels_dir = dir / "labels";
  RunSurvey(dir / "capture.json", dir / "out", options);
  return dir / "out";
}

fs::path MakeClassroomSurvey() {
  const fs::path dir = Root() / "classroom";
  fs::remove_all(dir);
  DemoOptions options{.samples_per_pixel = 1};
  options.survey.use_capture_labels = true;
  options.survey.write_report = false;
  RunDemo(dir, options);
  return dir / "survey";
}

fs::path FreshCopy(const fs::path& source, const std::string& name) {
  const fs::path dir = Root() / name;
  fs::remove_all(dir);
  fs::copy(source, dir, fs::copy_options::recursive);
  return dir;
}

}  // namespace

fs::path PanoramaSurvey(const std::string& name) {
  static std::once_flag once;
  static fs::path source;
  std::call_once(once, [] { source = MakePanoramaSurvey(); });
  return FreshCopy(source, name);
}

fs::path ClassroomSurvey(const std::string& name) {
  static std::once_flag once;
  static fs::path source;
  std::call_once(once, [] { source = MakeClassroomSurvey(); });
  return FreshCopy(source, name);
}

std::vector<Vec2> LRoomCorners() { return {{-2, -1.5}, {2, -1.5}, {2, 3.5}, {0.5, 3.5}, {0.5, 1.5}, {-2, 1.5}}; }

fs::path LRoomSurvey(const std::string& name) {
  static std::once_flag once;
  static fs::path source;
  std::call_once(once, [] { source = MakeLRoomSurvey(); });
  return FreshCopy(source, name);
}

Vec2 LRoomPanoPixel(const Vec3& p) { return EquirectPixelFromDirection(p - kLCamera, kPanoWidth, kPanoHeight); }

Plan ClassroomTruth() { return ReadPlan(Root() / "classroom" / "capture" / "truth.json"); }

Vec2 PanoPixel(const Vec3& p) { return EquirectPixelFromDirection(p - kCamera, kPanoWidth, kPanoHeight); }

}  // namespace asbuilt::review_test
