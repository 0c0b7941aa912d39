#ifndef ASBUILT_SCENE_SCENE_H_
#define ASBUILT_SCENE_SCENE_H_

// The scene model: what asbuilt renders and what its truth plans come from.
// A plain value type (aggregates, designated-initialiser friendly) with a JSON
// form that round-trips exactly (scene_json.h) and semantic validation.
//
// Geometry conventions are DESIGN.md's (geometry/rig.h): world metres, +Z up,
// floor at z = 0, yaw 0 looks along +Y, counter-clockwise positive.

#include <cstdint>
#include <optional>
#include <string>
#include <span>
#include <string_view>
#include <vector>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/geometry/polygon.h"
#include "asbuilt/geometry/rig.h"

namespace asbuilt {

// Procedural texture applied on top of a material's base colour.
enum class TextureKind { kNone, kPlaster, kPaint, kWallpaper, kWood, kTiles, kCarpet, kConcrete };

struct Material {
  std::string name;                       // Referenced by surfaces; unique.
  Vec3 base_color = Vec3(0.8, 0.8, 0.8);  // Linear RGB in [0, 1].
  double roughness = 0.8;                 // [0, 1]; low = glossy highlights.
  TextureKind texture = TextureKind::kNone;
  double texture_scale_m = 0.5;                // Feature size of the texture, > 0.
  Vec3 secondary_color = Vec3(0.6, 0.6, 0.6);  // Second colour (tiles' grout, wood grain…).
};

enum class HingeSide { kLeft, kRight };  // Seen from inside the room.

// A door or window in wall `wall` of its room. The wall runs from
// polygon[wall] to polygon[wall + 1]; `offset_m` is the distance along it
// from the wall's start to the near edge of the clear opening.
struct Opening {
  OpeningKind kind = OpeningKind::kDoor;
  int wall = 0;
  double offset_m = 0.5;
  double width_m = 0.9;   // Clear opening width.
  double height_m = 2.1;  // Clear opening height.
  double sill_m = 0.0;    // Bottom of the clear opening above the floor (0 for doors).
  // Doors.
  double open_deg = 0.0;  // Leaf angle, 0 = closed, up to 180; swings into the room.
  HingeSide hinge = HingeSide::kLeft;
  // Doors: a glazed leaf (patio or French door): a frame of stiles and rails
  // around glass panes to the floor, two leaves when wider than 1.3 m. The
  // outside is seen through it, as through a window; labelled door all the same.
  bool glazed = false;
  // Windows.
  double frame_width_m = 0.05;
  bool glass = true;
  std::string material;  // Empty: the built-in door / window material.
};

struct Room {
  std::string name;
  // Inner wall faces, counter-clockwise seen from above (interior on the
  // left of each wall), not repeating the first point. Wall i runs from
  // polygon[i] to polygon[(i + 1) % n]. Any angles; must not self-intersect.
  std::vector<Vec2> polygon;
  double height_m = 2.7;          // Floor to ceiling.
  double wall_thickness_m = 0.2;  // Outwards from the inner face.
  std::vector<Opening> openings;
  std::string wall_material = "wall";
  std::string floor_material = "floor";
  std::string ceiling_material = "ceiling";
  bool skirting = true;  // Skirting boards (labelled wall), kSkirtingHeightM × kSkirtingDepthM.
};

// Details every renderer of a scene draws (metres; render/scene_mesh.cc,
// scene/blender_export.cc), as in blender-rooms-public. Labels count the
// casings with their opening, the skirting with its wall.
constexpr double kSkirtingHeightM = 0.08;
constexpr double kSkirtingDepthM = 0.012;
constexpr double kDoorCasingM = 0.07;    // Casing (architrave) width around doors…
constexpr double kWindowCasingM = 0.05;  // …around windows…
constexpr double kCasingDepthM = 0.015;  // …and its protrusion from the wall.
constexpr double kSillBoardM = 0.03;     // Inner window sill board thickness…
constexpr double kSillOverhangM = 0.04;  // …and how far it protrudes into the room.

// A furniture box standing in the room (occludes walls; label background).
struct Furniture {
  std::string name;
  Vec2 centre_m = Vec2::Zero();        // Centre of the footprint on the floor.
  double yaw_deg = 0.0;                // Rotation of the footprint about +Z.
  Vec3 size_m = Vec3(1.0, 0.6, 0.75);  // Width (local x), depth (local y), height.
  double elevation_m = 0.0;            // Bottom above the floor (shelves).
  std::string material = "furniture";
};

enum class LightKind { kArea, kPoint, kSun };

struct Light {
  LightKind kind = LightKind::kArea;
  Vec3 position_m = Vec3(0, 0, 2.6);  // Area: centre, facing down. Point: position.
  Vec2 size_m = Vec2(1.2, 0.3);       // Area lights only.
  Vec3 color = Vec3(1.0, 0.95, 0.9);  // Linear RGB.
  double intensity = 1.0;             // Relative radiance / power scale, > 0.
  // Sun only: direction the light comes from.
  double azimuth_deg = 135.0;   // From +X towards +Y.
  double elevation_deg = 35.0;  // Above the horizon.
};

// What is seen through windows and lights the room from outside.
struct Environment {
  bool sky = true;
  Vec3 sky_color = Vec3(0.55, 0.7, 0.95);
  Vec3 ground_color = Vec3(0.35, 0.4, 0.3);
  bool exterior_objects = true;  // Trees and buildings outside windows.
  double ambient = 0.15;         // Ambient fill, [0, 1].
};

// The stereo rig: two identical level cameras, parallel axes (DESIGN.md).
struct StereoRigSpec {
  int width_px = 640;
  int height_px = 480;
  double hfov_deg = 80.0;                // Used when fx is not given.
  std::optional<double> fx, fy, cx, cy;  // Explicit intrinsics override the FOV.
  double baseline_m = 0.12;

  PinholeCamera Camera() const;
};

// One rig pose. pitch_deg tilts the view (dataset single views); survey
// captures are level (pitch 0).
struct Viewpoint {
  Vec3 position_m = Vec3(0, 0, 1.5);
  double yaw_deg = 0.0;
  double pitch_deg = 0.0;  // Positive looks up.
};

// Turn-in-place: the rig stays at one spot and turns by step_deg, `count`
// times (count 0: a full turn, 360 / step_deg views).
struct TurnInPlace {
  Vec3 position_m = Vec3(0, 0, 1.5);
  double start_deg = 0.0;
  double step_deg = 30.0;
  int count = 0;
};

struct Scene {
  int version = 1;
  std::string name = "room";
  std::uint64_t seed = 0;  // For procedural textures and randomisation.
  std::vector<Material> materials;
  std::vector<Room> rooms;
  std::vector<Furniture> furniture;
  std::vector<Light> lights;
  Environment environment;
  StereoRigSpec rig;
  std::vector<Viewpoint> viewpoints;  // Listed poses, used in order…
  std::optional<TurnInPlace> turn;    // …followed by the turn-in-place views.

  std::string ToString() const;
};

// Materials every scene can name without defining them ("wall", "floor",
// "ceiling", "door", "window_frame", "glass", "furniture", "skirting"). A
// scene's own materials override these by name.
const std::vector<Material>& BuiltinMaterials();
// The material a name resolves to in this scene, or nullptr.
const Material* FindMaterial(const Scene& scene, const std::string& name);

// Every semantic problem, with field paths as in the JSON
// ("rooms[0].openings[1]: overlaps openings[0] on wall 2"): open or
// self-intersecting polygons (fewer than 3 points, repeated points, crossing
// edges, clockwise order), openings outside their wall or overlapping,
// sill + height above the wall, non-positive sizes, unknown material names,
// viewpoints outside every room. `file` names the file in the problems.
std::vector<Problem> ValidateScene(const Scene& scene, const std::string& file = "scene");
// Throws InputError with every problem, if any.
void CheckScene(const Scene& scene, const std::string& file = "scene");

// All views of the scene, in order: listed viewpoints, then the turn.
std::vector<Viewpoint> ResolveViewpoints(const Scene& scene);

// The exact floor plan (DESIGN.md plan.json): inner-face walls of every room
// in order, openings with clear width/height/sill on their wall's line, room
// polygons and areas.
Plan SceneTruth(const Scene& scene);

// A plain-language summary ("6.00 × 8.00 m room, 3.00 m high, 1 door, …").
std::string DescribeScene(const Scene& scene);

const char* TextureKindName(TextureKind kind);
const char* LightKindName(LightKind kind);
const char* HingeSideName(HingeSide side);  // "left" / "right"
// Inverse of the names above; nullopt for an unknown name.
std::optional<TextureKind> TextureKindFromName(const std::string& name);
std::optional<LightKind> LightKindFromName(const std::string& name);
std::optional<HingeSide> HingeSideFromName(const std::string& name);

// Geometry helpers shared by validation, truth, the text parser and the MCP
// server. Wall i of a room runs from polygon[i] to polygon[(i + 1) % n].
int WallCount(const Room& room);
Vec2 WallStart(const Room& room, int wall);
Vec2 WallEnd(const Room& room, int wall);
double WallLength(const Room& room, int wall);
// Unit vector pointing out of the room (to the right of the wall direction).
Vec2 WallOutwardNormal(const Room& room, int wall);
// Compass name of the way a wall faces outwards, north = +Y, east = +X:
// "north", "north-east", "east", … (nearest of eight).
std::string WallCompassName(const Room& room, int wall);
// The eight compass names, north first, clockwise.
const std::vector<std::string_view>& CompassNames();
// Unit vector of a compass name (north = +Y, east = +X); nullopt for a word
// that is not one of CompassNames().
std::optional<Vec2> CompassVector(std::string_view name);
// The walls a compass name means, one rule for the text parser and the MCP
// tools: every wall whose WallCompassName it is (in wall order), else the
// one wall whose outward normal is nearest its direction (the longest of
// equals) when that is within `max_off_deg`; empty otherwise, or for a word
// that is not a compass name.
std::vector<int> WallsFacing(const Room& room, std::string_view compass, double max_off_deg = 180.0);
// The wall a compass name means where one is wanted: the longest of
// WallsFacing (the first of equals).
std::optional<int> WallFacing(const Room& room, std::string_view compass, double max_off_deg = 180.0);

// Where openings of these widths go when spread evenly along a wall
// `length_m` long: each centred in one of equal bays, at (i + ½)·L/k for k
// openings; the offsets of their starts (Opening::offset_m). The rule of the
// text parser ("two windows") and of the MCP tools (`count`). Whether they
// fit is the caller's to check.
std::vector<double> EvenlySpacedOffsets(double length_m, std::span<const double> widths_m);
// Centroid of the polygon's area (vertex mean for degenerate polygons).
Vec2 PolygonCentroid(const std::vector<Vec2>& polygon);
// Where a surveyor sets the tripod in a counter-clockwise room polygon: a
// spot from which a turn sees every wall, as far from the walls as that
// allows. It is the point of the polygon's kernel (the intersection of the
// inner sides of all its walls' lines) farthest from the nearest of those
// lines, searched on a grid of 1/200 of the room's extent (so within 0.4 %
// of the extent), or the centroid when that is as far (every convex room).
// So: a rectangle's centre; the middle of the square where an L's wings
// meet. From there no wall is seen edge-on, and the far walls' floor and
// ceiling edges are in view. std::nullopt when the kernel is empty: no one
// spot sees every wall, so shoot from several.
std::optional<Vec2> SurveySpot(const std::vector<Vec2>& polygon);

}  // namespace asbuilt

#endif  // ASBUILT_SCENE_SCENE_H_
