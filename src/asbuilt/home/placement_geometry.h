#ifndef ASBUILT_HOME_PLACEMENT_GEOMETRY_H_
#define ASBUILT_HOME_PLACEMENT_GEOMETRY_H_

// Rooms as the placement sees them, and what two placed rooms make of each
// other (internal to home/; the API is home/placement.h): each room's wall
// faces, doors and windows in some frame, and the terms of the score with
// their weights (docs/home.md).

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/home/placement.h"

namespace asbuilt::placement {

using Pose = Eigen::Isometry2d;

// Score weights, in metres of shared partition.
inline constexpr double kPlacedRoom = 2.0;      // Each room placed.
inline constexpr double kContactPerM = 1.0;     // Partition faces shared, per metre.
inline constexpr double kDoorsMeet = 3.0;       // A door lands on a door of a placed room.
inline constexpr double kDoorIntoWall = 1.0;    // A door lands on a placed room's plain wall.
inline constexpr double kWindowIntoWall = 2.0;  // A window looks into a placed room.
inline constexpr double kWidthPerM = 10.0;      // Linked doors' width difference.
inline constexpr double kOverlapPerM2 = 2.0;    // Floor shared with a placed room.
inline constexpr double kUserLink = 1000.0;     // A link the person asked for comes first.
inline constexpr double kEmptyPerM2 = 0.05;     // Floor of the home's bounding box no room covers.
inline constexpr double kContinues = 1.0;       // A wall continues another room's across a partition.
// Each room the door links left unplaced, when the best of their placements
// are picked to fill in by one-sided links: what such a room adds there.
inline constexpr double kRoomLeft = 12.0;
inline constexpr double kNoDoorOfItsOwn = 4.0;  // A one-sided link places a room whose survey found no door.
inline constexpr int kPlainWalls = 6;           // Plain walls per room a one-sided link may open onto.
inline constexpr double kThicknessPrior = 0.5;  // Weight of the partition's prior against one link's metre.
inline constexpr double kThinnestWall = 0.05;   // A partition thinner is none.
inline const double kAntiParallel = std::cos(10.0 * std::numbers::pi / 180.0);
inline const double kFacesAntiParallel = std::cos(3.0 * std::numbers::pi / 180.0);

// A wall's inner face.
struct Face {
  Vec2 a, b, n;  // Inner face from a to b; n: unit normal out of the room.
  Vec2 Dir() const { return (b - a).normalized(); }
  double Length() const { return (b - a).norm(); }
};

// A door or window on a face.
struct Hole {
  int opening = -1, wall = -1;
  Vec2 c, n;  // Centre on the face, the face's outward normal.
  double width = 0.0;
};

// A room's outline, faces and openings, in some frame.
struct RoomGeom {
  Plan outline;  // One room, for overlap areas; no room when the survey closed none.
  double area = 0.0;
  std::vector<Face> walls;
  std::vector<Hole> doors, windows;
  std::vector<char> wall_has_opening;  // Per wall: a door or window was found on it.
  std::vector<int> plain_walls;        // Walls with no opening found, longest first, at most kPlainWalls.
  Vec2 lo = Vec2::Constant(1e300), hi = Vec2::Constant(-1e300);  // Bounding box of walls and outline.
};

// A room's plan as faces with outward normals, the doors and windows on
// them, its outline and box, in the plan's frame.
RoomGeom GeomOf(const Plan& plan);

// `g` moved by `t` (its box recomputed).
RoomGeom Transformed(const RoomGeom& g, const Pose& t);

// B's pose relative to A's when A's door `a` and B's door `b` are one door,
// the faces `thickness` apart: B's door turned to face A's, centre on centre.
Pose LinkTransform(const Hole& a, const Hole& b, double thickness);

// B's pose when the point `s` along B's face g (its own frame) lies across
// the partition from the point `u` along the placed face f: g turned to face f.
Pose FaceTransform(const Face& f, double u, const Face& g, double s, double thickness);

// Where along a plain face of length `lg` a door seen at `u` along a face of
// length `lf` (turned to face it) can open: the faces' ends lined up either
// way, or centred on the door.
std::vector<double> Slides(double u, double lf, double lg, double width);

// A door one room's survey missed: placed room A's door onto one of B's plain
// walls, or B's door onto one of A's, slid as Slides says; B's pose for each.
// Door indices into RoomGeom::doors (−1 on the plain side), walls into
// RoomGeom::walls (−1 on the door's side). Doors marked in `used_*` are skipped.
struct OneSidedLink {
  int a_door = -1, b_door = -1, a_wall = -1, b_wall = -1;
  Pose pose = Pose::Identity();
};
std::vector<OneSidedLink> OneSidedLinks(const RoomGeom& placed_a, const RoomGeom& b, const std::vector<char>& used_a,
                                        const std::vector<char>& used_b, double thickness);

// Whether two doors are close enough in width to be one.
bool WidthsMatch(double a, double b, const PlacementOptions& o);

// Whether two placed doors face each other across a partition, centre on
// centre within 0.35 m, widths matching: one door seen from both sides.
bool DoorsMeet(const Hole& da, const Hole& db, const PlacementOptions& o);

// Where `f`'s line lies along `n` from `p`, and whether `p` projects onto the
// face at least `inset` from its ends.
struct FaceHit {
  double along = 0.0;  // Position on the face from f.a.
  bool within = false;
};
FaceHit ProjectOnFace(const Face& f, const Vec2& p, double inset);

// The face of `y` a door or window of a placed room opens onto (within a
// partition's thickness in front of it), or nullptr.
const Face* FaceInFront(const Hole& h, const RoomGeom& y, const PlacementOptions& o);

// What the openings of `x` make of the walls of `y` (both placed): a door
// that meets a door of y's on the same partition closes a loop; a door or
// window that opens onto y's plain wall cannot be.
double OpeningsAgainstWalls(const RoomGeom& x, const RoomGeom& y, const PlacementOptions& o);

// Metres of partition the two rooms' walls share: anti-parallel faces, each
// outside the other room, at most max_wall_thickness_m apart.
double SharedFaces(const RoomGeom& x, const RoomGeom& y, const PlacementOptions& o);

// Whether the two rooms' boxes are at most `margin` apart.
bool BoxesNear(const RoomGeom& x, const RoomGeom& y, double margin);

// Grows the box [lo, hi] by a placed room's walls in the home's axes (the
// first room's frame turned by `axes`).
void GrowBox(const RoomGeom& g, const Eigen::Matrix2d& axes, Vec2& lo, Vec2& hi);
// The area of the box [lo, hi]; 0 while it is empty (lo above hi).
double BoxArea(const Vec2& lo, const Vec2& hi);

// The terms of room x placed beside placed room y; nullopt: refused (they
// share too much floor).
std::optional<double> PairScore(const RoomGeom& x, const RoomGeom& y, const PlacementOptions& o);

}  // namespace asbuilt::placement

#endif  // ASBUILT_HOME_PLACEMENT_GEOMETRY_H_
