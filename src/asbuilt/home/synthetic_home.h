#ifndef ASBUILT_HOME_SYNTHETIC_HOME_H_
#define ASBUILT_HOME_SYNTHETIC_HOME_H_

// Random homes with exact truth, to develop and test the placement on
// (tests, bench_home) rather than on a real home kept for measurement: a
// procedural home's layout (scene/procedural_home.h) "surveyed" room by room:
// each room's plan in a frame of its own, its walls and openings jittered as
// a survey measures them, and some of its doors missed.

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "asbuilt/home/placement.h"
#include "asbuilt/scene/procedural_home.h"

namespace asbuilt {

struct SyntheticHomeOptions {
  HomeLayoutOptions layout;
  double jitter_m = 0.01;    // 1σ per wall end and opening end, as measured.
  double missed_door = 0.0;  // Chance that one side of a door is not found by its room's survey.
};

struct SyntheticHome {
  std::vector<HomeRoomInput> rooms;                // Each in its own frame, as surveyed.
  std::vector<Eigen::Isometry2d> floor_from_room;  // The truth.
  std::vector<std::vector<Vec2>> outlines;         // True outlines, home frame.
  int doors = 0;
};

SyntheticHome MakeSyntheticHome(unsigned seed, const SyntheticHomeOptions& options = {});

}  // namespace asbuilt

#endif  // ASBUILT_HOME_SYNTHETIC_HOME_H_
