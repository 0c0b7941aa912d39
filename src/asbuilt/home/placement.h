#ifndef ASBUILT_HOME_PLACEMENT_H_
#define ASBUILT_HOME_PLACEMENT_H_

// Placing a home's rooms (issue 40, docs/home.md): each room was surveyed
// from its own capture, in its own frame; this finds where each lies in one
// home frame from what rooms share — a door seen from both sides.
//
// A link says door i of room A and door j of room B are one door: B's door
// then lies on A's, across a partition `wall_thickness_m` thick, its face
// turned to face A's. Each link fixes B's pose from A's. A door one room's
// survey missed links one-sided, at a cost: the door of the other room onto
// this room's plain wall, slid to where the walls' ends line up, or centred.
// A beam search grows the home one link at a time from the first room
// (door-to-door links first, then one-sided ones for the rooms left), and
// again from the two rooms with most doors; each room added is scored
// against every room already placed (weights: docs/home.md):
//   + the partition faces the two rooms share (anti-parallel walls a
//     plausible thickness apart, metres of overlap), and walls running on
//     past a partition,
//   + doors that meet a door of a room already placed (a loop closes),
//   − the two doors' width difference, a one-sided link,
//   − floor shared with a room already placed (refused past max_overlap),
//   − a door or window that opens onto another room's plain wall,
//   − bounding-box floor of the home no room covers.
// The best few complete placements are kept (the first is the answer, the
// others are what a person picks from when it is wrong). Each is then refined
// by least squares over every link, loops included, and the faces of every
// partition, with the partition thickness one unknown of the whole home; a
// loop or face that cannot close within 5 cm is dropped. A room no link
// reaches is placed by its hint when it has one, else left unplaced, never
// guessed.
//
// Poses are floor_from_room: a room's capture frame → the home frame, which
// is the first room's frame (or its hint's pose).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "asbuilt/formats/plan_file.h"

namespace asbuilt {

struct HomeRoomInput {
  std::string name;
  Plan plan;  // In the room's own capture frame.
  std::optional<PlanPose> hint;
};

// An opening of one room: indices into the inputs and their plans' openings.
struct OpeningRef {
  int room = -1;
  int opening = -1;
  bool operator==(const OpeningRef& o) const { return room == o.room && opening == o.opening; }
};

// A door seen from one side only (the other room's survey missed it) links
// too, at a cost: that side's `opening` is −1 and `wall_a` / `wall_b` names
// the wall of its room the door opens onto.
struct RoomLink {
  OpeningRef a, b;  // a's room was placed first.
  int wall_a = -1, wall_b = -1;
  double score = 0.0;  // What adding b's room by it scored (tree links); 0 for loop links.
  bool loop = false;   // Found consistent after placing, not used to place.
  bool by_user = false;
};

// What a person said (the review page's link_openings / unlink_openings).
struct PlacementConstraints {
  std::vector<std::pair<OpeningRef, OpeningRef>> same;       // These are one door: used first.
  std::vector<std::pair<OpeningRef, OpeningRef>> different;  // Never linked.
  // Rooms a person put where they are (home frame): placed there first and
  // held; the others are placed around them.
  std::vector<std::pair<int, PlanPose>> fixed;
  // Where the rooms were before the person's last edit (home frame; empty,
  // or one per room, unset for a room that was not placed): a room placed
  // there again scores kept_room, so an edit changes only what it must.
  std::vector<std::optional<PlanPose>> previous;
  double kept_room = 3.0;
};

struct PlacementOptions {
  // Partition thickness between two linked doors' faces before the loops
  // measure it (a common interior wall: 100 mm stud + boards).
  double wall_thickness_m = 0.12;
  double max_wall_thickness_m = 0.40;  // Faces further apart are not one partition.
  // Two doors can be one when their widths differ by at most this plus
  // width_tolerance of the wider (ZInD's annotators: up to 0.15 m).
  double max_width_difference_m = 0.20;
  double width_tolerance = 0.15;
  // A room may share at most this fraction of the smaller floor with a room
  // already placed (surveyed outlines wander a little).
  double max_overlap = 0.15;
  int beam_width = 32;
  // Link a door seen from one side only to the other room's plain wall.
  bool one_sided_links = true;
  int alternatives = 3;  // Further complete placements kept beside the best.
  int improve = 3;       // Best placements improved by swapping links (placement_improve.h) before ranking.
  void Check() const;
};

struct RoomPlacement {
  bool placed = false;
  Eigen::Isometry2d floor_from_room = Eigen::Isometry2d::Identity();
  int link = -1;          // Index into HomePlacement::links that placed it; -1: first room, hint, or none.
  std::string placed_by;  // "first room", "door kitchen#1 = hall#3", "hint", "not placed: …".
};

struct HomePlacement {
  std::vector<RoomPlacement> rooms;
  std::vector<RoomLink> links;
  double score = 0.0;
  double wall_thickness_m = 0.0;  // Refined over the loops; the option's value without one.
  int loops = 0;                  // Links that closed a loop.
  int Placed() const;
  std::string ToString(const std::vector<HomeRoomInput>& rooms) const;
};

struct PlacementResult {
  HomePlacement best;
  std::vector<HomePlacement> alternatives;  // Next best distinct placements, best first.
  double seconds = 0.0;
};

// Throws InvalidArgument for no rooms or bad constraints (an index out of
// range, an opening linked to itself, a room fixed twice).
PlacementResult PlaceRooms(const std::vector<HomeRoomInput>& rooms, const PlacementOptions& options = {},
                           const PlacementConstraints& constraints = {});

// How well rooms fit at the given poses (floor_from_room per room; rooms
// not in `placed` are left out): the sum over pairs of the terms the beam
// search scores a room by, with per-pair detail in `detail` when asked.
double FitScore(const std::vector<HomeRoomInput>& rooms, const std::vector<Eigen::Isometry2d>& poses,
                const std::vector<char>& placed, const PlacementOptions& options = {},
                std::vector<std::string>* detail = nullptr);

// Yaw of a 2D rigid transform, radians counter-clockwise.
double YawOf(const Eigen::Isometry2d& t);
Eigen::Isometry2d PoseTransform(const PlanPose& pose);
PlanPose TransformPose(const Eigen::Isometry2d& t);

}  // namespace asbuilt

#endif  // ASBUILT_HOME_PLACEMENT_H_
