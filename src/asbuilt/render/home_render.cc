#include "asbuilt/render/home_render.h"

#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "asbuilt/formats/capture.h"
#include "asbuilt/formats/plan_file.h"
#include "asbuilt/scene/furnish.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

// A room's folder name: its name with anything but letters, digits, '-' and
// '_' as '_' ("room 1" → "room_1"), or "room_N".
std::string FolderName(const Room& room, std::size_t index) {
  std::string name = room.name.empty() ? fmt::format("room_{}", index + 1) : room.name;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  }
  return name;
}

// Moves a capture's frames into another frame: positions and yaws.
void MoveCapture(const fs::path& capture_json, const Eigen::Isometry2d& room_from_scene) {
  Capture capture = ReadCapture(capture_json);
  const double turn_deg =
      std::atan2(room_from_scene.linear()(1, 0), room_from_scene.linear()(0, 0)) * 180 / std::numbers::pi;
  for (CaptureFrame& f : capture.frames) {
    const Vec2 xy = room_from_scene * Vec2(f.position_m.x(), f.position_m.y());
    f.position_m = Vec3(xy.x(), xy.y(), f.position_m.z());
    f.yaw_deg += turn_deg;
  }
  WriteCapture(capture, capture_json);
}

}  // namespace

void HomeRenderOptions::Check() const {
  capture.Check();
  if (capture.views <= 0) throw InvalidArgument("HomeRenderOptions: capture.views must be > 0 (a turn in place)");
  if (!(camera_height_m > 0.2 && camera_height_m < 3.0)) {
    throw InvalidArgument("HomeRenderOptions: camera_height_m must be in (0.2, 3)");
  }
}

HomeRenderSummary RenderHome(const Scene& home, const fs::path& out_dir, const HomeRenderOptions& options,
                             const ProgressCallback& progress) {
  options.Check();
  if (home.rooms.empty()) throw InputError("scene", "rooms", "a home needs at least one room");
  const auto start = std::chrono::steady_clock::now();
  HomeRenderSummary summary;
  SceneRng rng(options.seed);
  nlohmann::json rooms = nlohmann::json::array(), truth = nlohmann::json::array();
  for (std::size_t r = 0; r < home.rooms.size(); ++r) {
    const Room& room = home.rooms[r];
    const std::optional<Vec2> spot = SurveySpot(room.polygon);
    if (!spot) {
      throw InputError("scene", fmt::format("rooms[{}]", r), "no spot sees every wall: it needs more than one capture");
    }
    Scene scene = home;
    scene.viewpoints.clear();
    scene.turn = TurnInPlace{.position_m = Vec3(spot->x(), spot->y(), options.camera_height_m),
                             .step_deg = 360.0 / options.capture.views,
                             .count = options.capture.views};
    const std::string name = FolderName(room, r);
    ReportProgress(progress, {.stage = "render home",
                              .done = static_cast<std::int64_t>(r),
                              .total = static_cast<std::int64_t>(home.rooms.size()),
                              .detail = name});
    RenderCapture(scene, out_dir / name, options.capture);
    fs::remove(out_dir / name / "truth.json");  // The whole home's, in the scene's frame: OUT/truth.json instead.
    Eigen::Isometry2d floor_from_room = Eigen::Isometry2d::Identity();
    if (options.own_frames) {
      floor_from_room.linear() =
          Eigen::Rotation2Dd(rng.Uniform(-std::numbers::pi, std::numbers::pi)).toRotationMatrix();
      floor_from_room.translation() = Vec2(rng.Uniform(-5, 5), rng.Uniform(-5, 5));
      MoveCapture(out_dir / name / "capture.json", floor_from_room.inverse());
    }
    summary.rooms.push_back(name);
    summary.floor_from_room.push_back(floor_from_room);
    rooms.push_back({{"name", name}, {"capture", name + "/capture.json"}});
    nlohmann::json outline = nlohmann::json::array();
    for (const Vec2& p : room.polygon) outline.push_back({p.x(), p.y()});
    truth.push_back({{"name", name},
                     {"floor_from_room",
                      {{"position_m", {floor_from_room.translation().x(), floor_from_room.translation().y()}},
                       {"yaw_deg", std::atan2(floor_from_room.linear()(1, 0), floor_from_room.linear()(0, 0)) * 180 /
                                       std::numbers::pi}}},
                     {"outline", std::move(outline)}});
  }
  WritePlan(SceneTruth(home), out_dir / "truth.json");
  WriteFileAtomic(out_dir / "home_truth.json", nlohmann::json{{"version", 1}, {"rooms", truth}}.dump(1) + "\n");
  summary.home_json = out_dir / "home.json";
  WriteFileAtomic(summary.home_json, nlohmann::json{{"version", 1}, {"kind", "home"}, {"rooms", rooms}}.dump(2) + "\n");
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace asbuilt
