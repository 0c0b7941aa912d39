#ifndef ASBUILT_SCENE_PROCEDURAL_H_
#define ASBUILT_SCENE_PROCEDURAL_H_

// Procedural rooms for synthetic training data: rectangular, L-shaped and
// rotated rooms with 1–4 doors and windows on varied walls (several on one
// wall, doors tight in corners), furniture that occludes walls, randomised
// materials, lights and environment, and a turn-in-place rig (anywhere in
// the room for training views, or where a surveyor would stand). Every scene
// passes ValidateScene. Deterministic: the same options and seed give the
// same scene on any platform (own RNG, no std:: distributions).

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "asbuilt/scene/scene.h"
#include "asbuilt/util/progress.h"
#include "asbuilt/util/fields.h"

namespace asbuilt {

// Where the turn-in-place rig stands.
enum class RigSpot {
  kRandom,  // Anywhere at least 0.8 m from the walls: varied training views.
  kSurvey,  // Where a surveyor sets the tripod: SurveySpot (scene.h), seeing every wall.
};
const char* RigSpotName(RigSpot spot);  // "random" / "survey"
// Parses a RigSpotName; throws InvalidArgument naming the value otherwise.
RigSpot ParseRigSpot(std::string_view name);

struct RandomSceneOptions {
  double min_side_m = 2.5;  // Bounding-box sides of the room, metres.
  double max_side_m = 9.0;
  double min_height_m = 2.4;  // Floor to ceiling, metres.
  double max_height_m = 3.5;
  double l_shape_probability = 0.3;  // Share of L-shaped rooms.
  double rotated_probability = 0.3;  // Share of rooms turned by a random angle (not axis-aligned).
  int min_openings = 1;              // Doors + windows per room; the first is always a door.
  int max_openings = 4;
  double same_wall_probability = 0.35;   // Chance an opening joins a wall that already has one.
  double corner_door_probability = 0.4;  // Chance a door sits tight in a corner.
  int min_furniture = 2;                 // Pieces tried per room (some may not fit).
  int max_furniture = 8;
  double turn_step_deg = 30.0;          // Rig yaw step; 360 / step views.
  RigSpot rig_spot = RigSpot::kRandom;  // The same seed gives the same room either way.
  StereoRigSpec rig;                    // Image size, FOV, baseline of every scene.

  // Realism levers (issue 21; docs/render.md "Realism levers"). All 0 by
  // default: the scene of a seed is then exactly what it always was. They
  // draw from their own random stream after the room is complete, so turning
  // one on adds to the same room rather than making another one.
  double styled_door_probability = 0.0;   // Per door: a white-painted or a wooden (oak, pine, walnut) leaf and casing.
  double open_door_probability = 0.0;     // Per closed door: swung wide open (60–110°).
  double neutral_wall_probability = 0.0;  // White or off-white walls and ceiling (most homes).
  double window_sun_probability = 0.0;    // A low, strong sun shining in through a window (sunlit patches).
  double kitchen_probability = 0.0;       // Kitchen units with worktop and wall units, white appliances (label 0).
  double wall_details_probability = 0.0;  // Radiators under windows, sockets, light switches by doors (label 0).
  double window_dressing_probability = 0.0;  // Per window: curtains (label 0) or a blind in the opening (window).
  double glazed_door_probability = 0.0;      // Per door: glazed (patio / French door, Opening::glazed), often widened.
  double ceiling_like_walls_probability = 0.0;  // Ceiling painted with the walls' paint, soft ambient light.
  double wall_art_probability = 0.0;            // Framed pictures, mirrors, a TV on the walls (label 0).

  void Check() const;
};
// Its field list: the flags of `asbuilt scene random` and the arguments of the
// MCP tool random_scene (random_scene_options.cc). The realism levers and
// `rig` are not in it. The scene's seed is RandomScene's argument, not an
// option: both front ends add RandomSceneSeedField() before the list.
const FieldList<RandomSceneOptions>& RandomSceneOptionFields();
Field RandomSceneSeedField();

// One random scene. Throws InvalidArgument for bad options.
Scene RandomScene(const RandomSceneOptions& options, std::uint64_t seed);

struct RandomScenesSummary {
  int written = 0;
  int rectangular = 0;
  int l_shaped = 0;
  int rotated = 0;
  int doors = 0;
  int windows = 0;
  std::filesystem::path dir;

  // "10 scenes in out/ (7 rectangular, 3 L-shaped, 4 rotated; 12 doors, 15 windows)".
  std::string BriefReport() const;
};

// Writes scenes seed, seed + 1, …, seed + count − 1 as DIR/scene_NNNN.json
// (atomically, one file each; NNNN = index). Throws InvalidArgument for
// count < 1.
RandomScenesSummary WriteRandomScenes(const RandomSceneOptions& options, std::uint64_t seed, int count,
                                      const std::filesystem::path& dir, const ProgressCallback& progress = {});

}  // namespace asbuilt

#endif  // ASBUILT_SCENE_PROCEDURAL_H_
