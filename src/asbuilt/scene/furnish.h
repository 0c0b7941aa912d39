#ifndef ASBUILT_SCENE_FURNISH_H_
#define ASBUILT_SCENE_FURNISH_H_

// Furnishing and lighting a room: places furniture boxes inside a room's
// polygon, against walls or free-standing, clear of door swings, window
// openings (when taller than the sill), the rig and each other; adds ceiling
// lights. Used by the text parser and the procedural generator. Deterministic
// for a given seed (own integer RNG; no std:: distributions, whose output
// differs between standard libraries).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "asbuilt/scene/scene.h"

namespace asbuilt {

// A piece of furniture before it has a place.
struct FurnitureSpec {
  std::string name;
  Vec3 size_m = Vec3(1.0, 0.6, 0.75);  // Width (along the wall), depth, height.
  bool against_wall = true;            // Back against a wall, else free-standing.
  std::string material = "furniture";
};

// The catalogue entry for a furniture word ("desk", "bed", "sofa", …; plural
// or singular), or nullopt. `FurnitureNames()` lists the known words.
std::optional<FurnitureSpec> FurnitureByName(const std::string& word);
const std::vector<std::string>& FurnitureNames();

// Small deterministic RNG (SplitMix64).
class SceneRng {
 public:
  explicit SceneRng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t Next();
  double Uniform(double lo, double hi);  // [lo, hi)
  int UniformInt(int lo, int hi);        // [lo, hi]
  bool Chance(double p);

 private:
  std::uint64_t state_;
};

struct PlaceFurnitureOptions {
  double wall_gap_m = 0.02;       // Gap between a piece's back and the wall.
  double door_clearance_m = 1.0;  // Depth kept free in front of every door.
  double rig_clearance_m = 0.6;   // Radius kept free around every rig position.
  double piece_gap_m = 0.1;       // Minimum gap between pieces.
  int attempts_per_piece = 300;   // Random tries before a piece is given up.

  void Check() const;
};

// Places `pieces` in scene.rooms[room] (appending to scene.furniture), each at
// the first random spot that satisfies every clearance. Returns the names of
// pieces that found no spot (the room is too full); never throws for that.
std::vector<std::string> PlaceFurniture(Scene& scene, int room, const std::vector<FurnitureSpec>& pieces,
                                        std::uint64_t seed, const PlaceFurnitureOptions& options = {});

// Places up to `count` copies of `piece` free-standing in rows (classroom
// desks): a grid aligned with wall 0, `aisle_m` between pieces, subject to
// the same clearances. Returns how many did not fit.
int PlaceInRows(Scene& scene, int room, const FurnitureSpec& piece, int count, double aisle_m = 0.6,
                const PlaceFurnitureOptions& options = {});

// Adds `count` ceiling area lights (count 0: one per ~8 m² of floor) on a
// grid inside the room, just under the ceiling.
void AddCeilingLights(Scene& scene, int room, int count = 0, double intensity = 1.0);

}  // namespace asbuilt

#endif  // ASBUILT_SCENE_FURNISH_H_
