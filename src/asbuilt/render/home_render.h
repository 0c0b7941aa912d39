#ifndef ASBUILT_RENDER_HOME_RENDER_H_
#define ASBUILT_RENDER_HOME_RENDER_H_

// A home of several rooms (scene/procedural_home.h, or any scene with more
// than one room) rendered as a surveyor captures it: in each room a stereo
// rig turning in place where a surveyor would stand, one capture per room,
// each in a frame of its own (as captures of separate rooms are), and a
// home.json listing them (docs/home.md):
//
//   OUT/home.json                 {"kind": "home", "rooms": [{"name", "capture"}]}
//   OUT/home_truth.json           each room's true pose (floor_from_room) and outline
//   OUT/truth.json                the home's exact plan (home frame)
//   OUT/<room>/capture.json …     as `asbuilt render` writes it, in the room's frame

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "asbuilt/render/capture_render.h"
#include "asbuilt/scene/scene.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

struct HomeRenderOptions {
  CaptureRenderOptions capture = {.views = 12};  // Per room.
  double camera_height_m = 1.5;
  // Each room's capture in a random frame of its own (seeded); false: all in
  // the scene's frame.
  bool own_frames = true;
  std::uint64_t seed = 1;
  void Check() const;
};

struct HomeRenderSummary {
  std::vector<std::string> rooms;                  // Folder names, in the scene's order.
  std::vector<Eigen::Isometry2d> floor_from_room;  // Each capture's frame in the scene's.
  std::filesystem::path home_json;
  double seconds = 0.0;
};

// Throws InputError for a scene with fewer than one room or a room with no
// place to stand; Error on write failures.
HomeRenderSummary RenderHome(const Scene& home, const std::filesystem::path& out_dir,
                             const HomeRenderOptions& options = {}, const ProgressCallback& progress = {});

}  // namespace asbuilt

#endif  // ASBUILT_RENDER_HOME_RENDER_H_
