#ifndef ASBUILT_HOME_SYNTHETIC_HOME_H_
#define ASBUILT_HOME_SYNTHETIC_HOME_H_

// Random homes with exact truth, to develop and test the placement on
// (tests, bench_home) rather than on a real home kept for measurement: a
// rectangular floor cut into rectangular rooms (guillotine cuts, partitions
// `wall_thickness_m` thick), a door between rooms that share a partition
// (a spanning tree of them, and some more), a window on some exterior walls.
// Each room is then "surveyed": its plan in a frame of its own, its walls and
// openings jittered as a survey measures them, and some of its doors missed.

#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "asbuilt/home/placement.h"

namespace asbuilt {

struct SyntheticHomeOptions {
  int min_rooms = 5, max_rooms = 10;
  double min_room_m = 1.8;  // Smallest room side.
  double wall_thickness_m = 0.10;
  double extra_door = 0.3;      // Chance of a door where two rooms already connect another way.
  double window = 0.7;          // Chance of a window per exterior wall of 2 m or more.
  double jitter_m = 0.01;       // 1σ per wall end and opening end, as measured.
  double missed_door = 0.0;     // Chance that one side of a door is not found by its room's survey.
};

struct SyntheticHome {
  std::vector<HomeRoomInput> rooms;               // Each in its own frame, as surveyed.
  std::vector<Eigen::Isometry2d> floor_from_room;  // The truth.
  std::vector<std::vector<Vec2>> outlines;         // True outlines, home frame.
  int doors = 0;
};

SyntheticHome MakeSyntheticHome(unsigned seed, const SyntheticHomeOptions& options = {});

}  // namespace asbuilt

#endif  // ASBUILT_HOME_SYNTHETIC_HOME_H_
