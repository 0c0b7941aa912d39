#ifndef ASBUILT_HOME_HOME_PLAN_H_
#define ASBUILT_HOME_HOME_PLAN_H_

// One plan of a placed home (docs/home.md): every room's walls, openings
// and outline in the home frame, each room named with its pose and what
// placed it; the two faces of a partition merged into one wall with its
// measured thickness; each door between two rooms written once, with the
// rooms it joins. A room that could not be placed is drawn beside the plan,
// to the right, and says so in `placed_by`.
//
// And the score of a placement against a true one (the home benchmark and
// tests): after the one rigid transform that best aligns the whole home, a
// room is placed when its centroid is within position_tolerance_m and its
// yaw within yaw_tolerance_deg of the truth's.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/home/placement.h"

namespace asbuilt {

struct HomePlanOptions {
  double beside_gap_m = 1.0;  // Between the plan and a room drawn beside it.
  // Faces of two rooms are one partition when anti-parallel, at most this
  // far apart, and the shorter overlaps the longer along this share of it.
  double max_wall_thickness_m = 0.40;
  double min_partition_overlap = 0.9;
  void Check() const;
};

Plan HomePlan(const std::vector<HomeRoomInput>& rooms, const HomePlacement& placement,
              const HomePlanOptions& options = {});

// Where HomePlan draws each room (floor_from_room): its placement, or beside
// the placed rooms when it has none.
std::vector<Eigen::Isometry2d> DrawnRoomPoses(const std::vector<HomeRoomInput>& rooms, const HomePlacement& placement,
                                              const HomePlanOptions& options = {});

struct HomeScoreOptions {
  double position_tolerance_m = 0.10;
  double yaw_tolerance_deg = 1.0;
};

struct HomeScore {
  int rooms = 0;
  int placed = 0;                                       // Rooms the placement placed (links or hints).
  int within = 0;                                       // Of those, within the tolerances after alignment.
  double floor_iou = 0.0;                               // Union of placed outlines against union of true outlines.
  std::vector<double> centroid_error_m, yaw_error_deg;  // Per room (NaN: not placed).
  Eigen::Isometry2d truth_from_home = Eigen::Isometry2d::Identity();
  std::string ToString() const;  // "12/13 rooms within 10 cm and 1°, floor IoU 0.962".
};

// `truth_floor_from_room[r]` and `truth_outline[r]` (in the truth's floor
// frame; empty: none) per room, in the order of `rooms`.
HomeScore ScoreHome(const std::vector<HomeRoomInput>& rooms, const HomePlacement& placement,
                    const std::vector<Eigen::Isometry2d>& truth_floor_from_room,
                    const std::vector<std::vector<Vec2>>& truth_outline, const HomeScoreOptions& options = {});

}  // namespace asbuilt

#endif  // ASBUILT_HOME_HOME_PLAN_H_
