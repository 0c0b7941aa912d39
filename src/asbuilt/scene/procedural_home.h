#ifndef ASBUILT_SCENE_PROCEDURAL_HOME_H_
#define ASBUILT_SCENE_PROCEDURAL_HOME_H_

// Procedural homes (issue 40): a rectangular floor cut into rectangular
// rooms by guillotine cuts, partitions `wall_thickness_m` thick, a door in
// the partitions of a spanning tree of the rooms (and in some more), a
// window on some exterior walls; as a layout (home/synthetic_home.h jitters
// it into surveyed plans) or as a Scene of several rooms that renders with
// exact truth (render/home_render.h). Deterministic (SceneRng).

#include <cstdint>
#include <vector>

#include "asbuilt/scene/furnish.h"
#include "asbuilt/scene/scene.h"

namespace asbuilt {

struct HomeLayoutOptions {
  int min_rooms = 5, max_rooms = 10;
  double min_width_m = 9.0, max_width_m = 14.0;  // The floor's sides.
  double min_depth_m = 7.0, max_depth_m = 11.0;
  double min_room_m = 1.8;         // Smallest room side.
  double wall_thickness_m = 0.10;  // Partitions.
  double extra_door = 0.3;         // Chance of a door where two rooms already connect another way.
  double window = 0.7;             // Chance of a window per exterior wall of 2 m or more.
  // Chance of a door to the outside per exterior wall of 1.5 m or more (in
  // place of its window; a quarter of them 1.5–2.4 m wide).
  double exterior_door = 0.0;
  void Check() const;
};

// An opening of a layout room: on wall `wall` (polygon[wall] → polygon[wall
// + 1]), `offset_m` from its start to the clear opening's near edge.
struct HomeLayoutOpening {
  int room = 0, wall = 0;
  OpeningKind kind = OpeningKind::kDoor;
  double offset_m = 0.0, width_m = 0.8;
};

struct HomeLayout {
  std::vector<std::vector<Vec2>> rooms;  // Rectangles, counter-clockwise, home frame, metres.
  std::vector<HomeLayoutOpening> openings;
  int doors = 0;  // Each counted once (two openings).
  double wall_thickness_m = 0.10;
};

HomeLayout MakeHomeLayout(SceneRng& rng, const HomeLayoutOptions& options = {});

// The home as one scene: a Room per layout room ("room 1", …), its
// partitions the layout's thickness, closed doors 2.0 m high, windows from
// 0.9 m to 2.1 m, a ceiling light per room; no viewpoints.
Scene HomeScene(const HomeLayout& layout, std::uint64_t seed, double height_m = 2.6);

}  // namespace asbuilt

#endif  // ASBUILT_SCENE_PROCEDURAL_HOME_H_
