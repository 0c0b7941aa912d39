#include "asbuilt/render/scene_mesh.h"

#include <gtest/gtest.h>

namespace asbuilt {
namespace {

TEST(IntersectPortal, HitsInsideAndMissesOutside) {
  LabelPortal p{Vec3(0, 2, 0), Vec3(1, 0, 0), Vec3(0, 0, 2), kLabelDoor};
  EXPECT_NEAR(IntersectPortal(p, Vec3(0.5, 0, 1), Vec3(0, 1, 0)), 2.0, 1e-12);
  EXPECT_LT(IntersectPortal(p, Vec3(1.5, 0, 1), Vec3(0, 1, 0)), 0);
  EXPECT_LT(IntersectPortal(p, Vec3(0.5, 0, 1), Vec3(0, -1, 0)), 0);
}

Scene BoxRoom() {
  Scene s;
  Room r;
  r.name = "r";
  r.polygon = {{0, 0}, {4, 0}, {4, 3}, {0, 3}};
  r.height_m = 2.5;
  r.openings.push_back({.kind = OpeningKind::kDoor, .wall = 0, .offset_m = 1.0, .width_m = 0.9, .height_m = 2.0});
  r.openings.push_back(
      {.kind = OpeningKind::kWindow, .wall = 2, .offset_m = 1.0, .width_m = 1.5, .height_m = 1.2, .sill_m = 0.9});
  s.rooms.push_back(r);
  s.lights.push_back({});
  return s;
}

TEST(BuildSceneMesh, MakesPortalsLightsAndLabelledObjects) {
  SceneMesh mesh = BuildSceneMesh(BoxRoom());
  EXPECT_EQ(mesh.portals.size(), 2u);
  EXPECT_EQ(mesh.area_lights.size(), 1u);
  bool glass = false, leaf = false, wall = false;
  for (const MeshObject& o : mesh.objects) {
    if (o.role == SurfaceRole::kGlass) glass = o.label == kLabelWindow;
    if (o.role == SurfaceRole::kDoorLeaf) leaf = o.label == kLabelDoor;
    if (o.role == SurfaceRole::kWall) wall = o.label == kLabelWall;
  }
  EXPECT_TRUE(glass);
  EXPECT_TRUE(leaf);
  EXPECT_TRUE(wall);
  EXPECT_NE(mesh.ToString().find("2 portals"), std::string::npos);
}

TEST(BuildSceneMesh, RejectsAnUnknownMaterialNamingTheField) {
  Scene s = BoxRoom();
  s.rooms[0].wall_material = "unobtainium";
  try {
    BuildSceneMesh(s);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems()[0].field_path, "rooms[0].wall_material");
  }
}

}  // namespace
}  // namespace asbuilt
