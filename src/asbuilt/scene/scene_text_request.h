#ifndef ASBUILT_SCENE_SCENE_TEXT_REQUEST_H_
#define ASBUILT_SCENE_SCENE_TEXT_REQUEST_H_

// What the text → scene parser read from a description (internal to
// scene/): the room, its openings, materials, furniture, lights and rig,
// each field unset when the text did not say. The parser fills it
// (scene_text_parser.h); the layout and SceneFromText turn it into a scene.

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "asbuilt/scene/furnish.h"
#include "asbuilt/scene/scene.h"
#include "asbuilt/scene/scene_text_vocabulary.h"

namespace asbuilt::scene_text {

// Where along its wall an opening goes.
enum class Placement { kAuto, kCentre, kCorner, kEnd, kFromEnd, kLeft, kRight };

struct OpeningRequest {
  OpeningKind kind = OpeningKind::kDoor;
  int count = 1;
  bool count_given = false;
  bool each_wall = false;
  bool all_walls = false;
  bool french = false;
  std::optional<double> width, height, sill, open_deg;
  double width_scale = 1.0;
  std::optional<HingeSide> hinge;
  std::optional<bool> glass;
  std::vector<std::string> walls;  // Compass names.
  Placement placement = Placement::kAuto;
  std::string placement_compass;  // For corner / end / from-end.
  double from_end_m = 0.0;
  bool joined_to_next_by_and = false;
  std::string text;  // The clause, for messages.
};

struct SurfaceStyle {
  std::optional<Vec3> color;
  std::optional<TextureKind> texture;
};

struct Request {
  const RoomKind* kind = nullptr;
  std::optional<double> width, depth, height, thickness, area, side;
  bool square = false;
  bool l_shape = false;
  std::optional<double> cut_width, cut_depth;
  std::string cut_corner = "north-east";
  double rotation_deg = 0.0;
  std::vector<OpeningRequest> openings;
  std::vector<std::pair<FurnitureSpec, int>> furniture;
  bool no_furniture = false;
  std::map<std::string, SurfaceStyle> surfaces;  // "wall", "floor", "ceiling".
  std::optional<int> light_count;
  double light_intensity = 1.0;
  bool night = false;
  std::optional<bool> sun;
  std::optional<double> rig_height, rig_step, baseline;
};

}  // namespace asbuilt::scene_text

#endif  // ASBUILT_SCENE_SCENE_TEXT_REQUEST_H_
