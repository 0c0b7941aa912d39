#ifndef ASBUILT_RENDER_SCENE_MESH_H_
#define ASBUILT_RENDER_SCENE_MESH_H_

// The scene model turned into triangles the ray tracer can intersect, each
// object carrying its label class, material and role. Pure geometry: no
// Embree here, so the construction is testable on its own.
//
// What is built (world metres, DESIGN.md frame):
//  - floor and ceiling slabs over each room's polygon offset outwards by the
//    wall thickness (floor top at z = 0, ceiling underside at z = height);
//  - walls as solid boxes: inner face on the polygon line, thickness outwards,
//    cut by their openings (jamb linings, casings, door leaf, window frame,
//    glass and sill board fill the cuts); skirting boards (label wall);
//  - furniture boxes (label 0; material "mirror": a mirror), area lights as
//    thin emissive panels;
//  - outside: ground, buildings and trees (label 0), sky on a miss;
//  - a small closed space behind each door that opens to the outside.
// Doors and windows also get a *label portal*: the rectangle on the wall's
// inner face covering the opening with its linings. A primary ray that
// crosses a portal before (or at) its first hit is labelled with the
// portal's class — so looking through an opening labels the opening
// (blender-rooms-public README, "labels").

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "asbuilt/geometry/label_class.h"
#include "asbuilt/geometry/polygon.h"
#include "asbuilt/scene/scene.h"

namespace asbuilt {

using Vec3f = Eigen::Vector3f;

// What an object is, for shading and statistics.
enum class SurfaceRole : std::uint8_t {
  kFloor,
  kCeiling,
  kWall,
  kSkirting,
  kDoorLeaf,
  kDoorLining,
  kCasing,
  kWindowFrame,
  kGlass,
  kWindowSill,
  kFurniture,
  kLight,
  kGround,
  kExterior,
  kCloset,
  kMirror,  // A furniture box of material "mirror": reflects like a mirror (label 0, as furniture).
};
const char* SurfaceRoleName(SurfaceRole role);

// One intersectable object: a triangle soup with one label and material.
struct MeshObject {
  std::string name;
  SurfaceRole role = SurfaceRole::kWall;
  std::uint8_t label = kLabelBackground;
  int material = 0;                // Index into SceneMesh::materials.
  Vec3f emission = Vec3f::Zero();  // Radiance of emitters (lights), linear RGB.
  std::vector<Vec3f> vertices;
  std::vector<Eigen::Vector3i> triangles;
};

// A rectangle origin + a·edge_u + b·edge_v, a, b ∈ [0, 1].
struct LabelPortal {
  Vec3 origin = Vec3::Zero();
  Vec3 edge_u = Vec3::UnitX();
  Vec3 edge_v = Vec3::UnitZ();
  std::uint8_t label = kLabelDoor;
};

// A rectangular emitter facing −Z (ceiling panel): sampled for direct light.
struct AreaLight {
  Vec3 centre = Vec3::Zero();
  Vec3 half_u = Vec3(0.5, 0, 0);  // Half edges in the world.
  Vec3 half_v = Vec3(0, 0.5, 0);
  Vec3 normal = Vec3(0, 0, -1);  // Emitting side.
  Vec3 radiance = Vec3::Ones();  // Linear RGB.
  double area_m2 = 1.0;
};

struct SunLight {
  Vec3 direction_to_sun = Vec3(0, 0, 1);  // Unit.
  Vec3 irradiance = Vec3::Zero();         // On a surface facing the sun.
  double angular_radius_rad = 0.01;       // Soft shadow size.
};

struct SceneMesh {
  std::vector<Material> materials;  // Resolved: scene materials, then built-ins.
  std::vector<MeshObject> objects;
  std::vector<LabelPortal> portals;
  std::vector<AreaLight> area_lights;
  std::vector<SunLight> suns;
  Environment environment;

  std::size_t TriangleCount() const;
  std::string ToString() const;
};

// Render-side defaults for the built-in material names ("wall", "floor",
// "ceiling", "door", "window_frame", "glass", "furniture", "skirting",
// "ground", "exterior"), used when the scene does not define them.
const std::vector<Material>& RenderDefaultMaterials();

// What is built beyond the scene model (dataset synth's realism levers; the
// defaults build exactly what the scene describes, as `asbuilt render` does).
struct SceneMeshOptions {
  // Behind a door that leads outside: 0 builds the small closed space (1.2 m
  // deep, unlit); > 0 builds a room this deep instead (metres), wider than
  // the door by next_room_side_m on each side, as high as the room, lit by a
  // ceiling panel — what an open door shows in a home. Seen only through the
  // doorway, so it is labelled door there (label portal), background nowhere.
  double next_room_depth_m = 0.0;
  double next_room_side_m = 1.5;
  double next_room_light = 1.0;          // Intensity of its ceiling panel (as Light::intensity).
  std::string next_room_wall_material;   // Empty: the room's wall material.
  std::string next_room_floor_material;  // Empty: the room's floor material.

  void Check() const;
};

// Builds the triangles. Throws InputError (file "scene") for a material name
// that resolves nowhere. Deterministic: exterior objects come from scene.seed.
SceneMesh BuildSceneMesh(const Scene& scene, const SceneMeshOptions& options = {});

// Ray–portal test: distance along the ray (unit dir) to the portal, or a
// negative number if it misses.
double IntersectPortal(const LabelPortal& portal, const Vec3& origin, const Vec3& dir);

}  // namespace asbuilt

#endif  // ASBUILT_RENDER_SCENE_MESH_H_
