#include "asbuilt/render/scene_mesh.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <random>

#include <fmt/format.h>

#include "asbuilt/geometry/polygon.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// Fixed architectural detail sizes (metres), as in blender-rooms-public.
constexpr double kLiningM = 0.02;  // Jamb lining board thickness.
constexpr double kLeafThicknessM = 0.04;
constexpr double kLeafRecessM = 0.03;        // A closed leaf sits this far into the opening.
constexpr double kFrameDepthM = 0.06;        // Window frame depth (across the wall).
constexpr double kClosetDepthM = 1.2;        // The closed space behind exterior doors.
constexpr double kGlazedStileM = 0.07;       // Glazed door leaf: side stiles…
constexpr double kGlazedTopRailM = 0.09;     // …top rail…
constexpr double kGlazedBottomRailM = 0.14;  // …and bottom rail around the pane.

Vec3f F(const Vec3& v) { return v.cast<float>(); }

// Appends the box origin + a·ea + b·eb + c·ec, a, b, c ∈ [0, 1].
void AddBox(MeshObject& o, const Vec3& origin, const Vec3& ea, const Vec3& eb, const Vec3& ec) {
  int base = static_cast<int>(o.vertices.size());
  for (int i = 0; i < 8; ++i) {
    Vec3 p = origin + ((i & 1) ? ea : Vec3::Zero()) + ((i & 2) ? eb : Vec3::Zero()) + ((i & 4) ? ec : Vec3::Zero());
    o.vertices.push_back(F(p));
  }
  static const int kQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : kQuads) {
    o.triangles.emplace_back(base + q[0], base + q[1], base + q[2]);
    o.triangles.emplace_back(base + q[0], base + q[2], base + q[3]);
  }
}

void AddQuad(MeshObject& o, const Vec3& origin, const Vec3& eu, const Vec3& ev) {
  int base = static_cast<int>(o.vertices.size());
  o.vertices.push_back(F(origin));
  o.vertices.push_back(F(origin + eu));
  o.vertices.push_back(F(origin + eu + ev));
  o.vertices.push_back(F(origin + ev));
  o.triangles.emplace_back(base, base + 1, base + 2);
  o.triangles.emplace_back(base, base + 2, base + 3);
}

// A prism: polygon (ccw) from z0 to z1, with caps and sides.
void AddPrism(MeshObject& o, const std::vector<Vec2>& poly, double z0, double z1) {
  auto tris = TriangulatePolygon(poly);
  int n = static_cast<int>(poly.size());
  int base = static_cast<int>(o.vertices.size());
  for (const Vec2& p : poly) o.vertices.push_back(F(Vec3(p.x(), p.y(), z0)));
  for (const Vec2& p : poly) o.vertices.push_back(F(Vec3(p.x(), p.y(), z1)));
  for (const auto& t : tris) {
    o.triangles.emplace_back(base + t[0], base + t[2], base + t[1]);
    o.triangles.emplace_back(base + n + t[0], base + n + t[1], base + n + t[2]);
  }
  for (int i = 0; i < n; ++i) {
    int j = (i + 1) % n;
    o.triangles.emplace_back(base + i, base + j, base + n + j);
    o.triangles.emplace_back(base + i, base + n + j, base + n + i);
  }
}

class MeshBuilder {
 public:
  MeshBuilder(const Scene& scene, const SceneMeshOptions& options) : scene_(scene), options_(options) {
    for (const Material& m : scene.materials) AddMaterial(m);
    for (const Material& m : RenderDefaultMaterials()) {
      if (!index_.contains(m.name)) AddMaterial(m);
    }
  }

  SceneMesh Build() {
    mesh_.environment = scene_.environment;
    for (std::size_t r = 0; r < scene_.rooms.size(); ++r) BuildRoom(static_cast<int>(r));
    for (std::size_t f = 0; f < scene_.furniture.size(); ++f) BuildFurniture(static_cast<int>(f));
    for (std::size_t l = 0; l < scene_.lights.size(); ++l) BuildLight(static_cast<int>(l));
    BuildExterior();
    mesh_.materials = materials_;
    mesh_.objects.assign(std::make_move_iterator(objects_.begin()), std::make_move_iterator(objects_.end()));
    return std::move(mesh_);
  }

 private:
  void AddMaterial(const Material& m) {
    index_[m.name] = static_cast<int>(materials_.size());
    materials_.push_back(m);
  }

  int MaterialIndex(const std::string& name, const std::string& field) {
    auto it = index_.find(name);
    if (it == index_.end()) {
      throw InputError("scene", field, fmt::format("unknown material '{}'", name));
    }
    return it->second;
  }

  MeshObject& NewObject(std::string name, SurfaceRole role, std::uint8_t label, int material) {
    MeshObject& o = objects_.emplace_back();  // deque: references stay valid.
    o.name = std::move(name);
    o.role = role;
    o.label = label;
    o.material = material;
    return o;
  }

  void BuildRoom(int r) {
    const Room& room = scene_.rooms[r];
    const std::string field = fmt::format("rooms[{}]", r);
    const int n = static_cast<int>(room.polygon.size());
    if (n < 3) return;
    const double t = room.wall_thickness_m;
    const double h = room.height_m;
    int wall_mat = MaterialIndex(room.wall_material, field + ".wall_material");
    int floor_mat = MaterialIndex(room.floor_material, field + ".floor_material");
    int ceiling_mat = MaterialIndex(room.ceiling_material, field + ".ceiling_material");
    int skirting_mat = MaterialIndex("skirting", field);

    // Slabs over the outer outline, so nothing is open at the edges.
    std::vector<Vec2> outer = OffsetPolygonOutwards(room.polygon, t);
    AddPrism(NewObject(room.name + "/floor", SurfaceRole::kFloor, kLabelBackground, floor_mat), outer, -0.25, 0.0);
    AddPrism(NewObject(room.name + "/ceiling", SurfaceRole::kCeiling, kLabelBackground, ceiling_mat), outer, h,
             h + 0.25);

    MeshObject& walls = NewObject(room.name + "/walls", SurfaceRole::kWall, kLabelWall, wall_mat);
    MeshObject& skirting = NewObject(room.name + "/skirting", SurfaceRole::kSkirting, kLabelWall, skirting_mat);
    for (int i = 0; i < n; ++i) {
      const Vec2 p0 = room.polygon[i];
      const Vec2 p1 = room.polygon[(i + 1) % n];
      const Vec2 prev = room.polygon[(i + n - 1) % n];
      const Vec2 next = room.polygon[(i + 2) % n];
      const double len = (p1 - p0).norm();
      if (len < 1e-9) continue;
      const Vec2 d2 = (p1 - p0) / len;
      const Vec2 out2(d2.y(), -d2.x());
      // Extend the box past convex corners so the outer corner is filled.
      const bool convex_start = Cross(p0 - prev, p1 - p0) > 0;
      const bool convex_end = Cross(p1 - p0, next - p1) > 0;
      const double s_begin = convex_start ? -t : 0.0;
      const double s_end = len + (convex_end ? t : 0.0);
      WallFrame w{Vec3(p0.x(), p0.y(), 0), Vec3(d2.x(), d2.y(), 0), Vec3(out2.x(), out2.y(), 0), t, h};

      // Cut intervals along the wall: [s0, s1] × [z0, z1] per opening, with
      // room for linings (and the window sill board).
      struct Cut {
        double s0, s1, z0, z1;
        const Opening* op;
        int index;
      };
      std::vector<Cut> cuts;
      for (std::size_t k = 0; k < room.openings.size(); ++k) {
        const Opening& op = room.openings[k];
        if (op.wall != i) continue;
        const bool door = op.kind == OpeningKind::kDoor;
        double z0 = door ? 0.0 : std::max(0.0, op.sill_m - kSillBoardM);
        cuts.push_back({op.offset_m - kLiningM, op.offset_m + op.width_m + kLiningM, z0,
                        std::min(h, op.sill_m + op.height_m + kLiningM), &op, static_cast<int>(k)});
      }
      std::sort(cuts.begin(), cuts.end(), [](const Cut& a, const Cut& b) { return a.s0 < b.s0; });

      // Solid pieces: full height between cuts, below and above each cut.
      double s = s_begin;
      for (const Cut& c : cuts) {
        if (c.s0 > s) w.Box(walls, s, c.s0, 0, t, 0, h);
        if (c.z0 > 0) w.Box(walls, c.s0, c.s1, 0, t, 0, c.z0);
        if (c.z1 < h) w.Box(walls, c.s0, c.s1, 0, t, c.z1, h);
        s = std::max(s, c.s1);
      }
      if (s_end > s) w.Box(walls, s, s_end, 0, t, 0, h);

      // Skirting boards along the wall, interrupted by doors.
      if (room.skirting) {
        double a = 0.0;
        for (const Cut& c : cuts) {
          if (c.op->kind != OpeningKind::kDoor) continue;
          double b = c.s0 - kDoorCasingM + kLiningM;
          if (b > a) w.Box(skirting, a, b, -kSkirtingDepthM, 0, 0, kSkirtingHeightM);
          a = c.s1 + kDoorCasingM - kLiningM;
        }
        if (len > a) w.Box(skirting, a, len, -kSkirtingDepthM, 0, 0, kSkirtingHeightM);
      }

      for (const Cut& c : cuts) {
        std::string name = fmt::format("{}/{}{}", room.name, OpeningKindName(c.op->kind), c.index);
        std::string op_field = fmt::format("{}.openings[{}]", field, c.index);
        if (c.op->kind == OpeningKind::kDoor) {
          BuildDoor(w, *c.op, name, op_field, room);
        } else {
          BuildWindow(w, *c.op, name, op_field);
        }
      }
    }
  }

  // Wall-local frame: s along the wall, n outwards (0 = inner face), z up.
  struct WallFrame {
    Vec3 origin, along, out;
    double thickness, height;
    Vec3 At(double s, double n, double z) const { return origin + s * along + n * out + Vec3(0, 0, z); }
    void Box(MeshObject& o, double s0, double s1, double n0, double n1, double z0, double z1) const {
      if (s1 - s0 < 1e-6 || n1 - n0 < 1e-6 || z1 - z0 < 1e-6) return;
      AddBox(o, At(s0, n0, z0), (s1 - s0) * along, (n1 - n0) * out, Vec3(0, 0, z1 - z0));
    }
  };

  void AddPortal(const WallFrame& w, const Opening& op, double s0, double s1, double z0, double z1) {
    mesh_.portals.push_back({w.At(s0, 0, z0), (s1 - s0) * w.along, Vec3(0, 0, z1 - z0),
                             op.kind == OpeningKind::kDoor ? kLabelDoor : kLabelWindow});
  }

  bool InsideAnyRoom(const Vec2& p) const {
    for (const Room& room : scene_.rooms) {
      if (room.polygon.size() >= 3 && PointInPolygon(room.polygon, p)) return true;
    }
    return false;
  }

  void BuildDoor(const WallFrame& w, const Opening& op, const std::string& name, const std::string& field,
                 const Room& room) {
    int mat = MaterialIndex(op.material.empty() ? "door" : op.material, field + ".material");
    const double a = op.offset_m;
    const double b = op.offset_m + op.width_m;
    const double top = op.sill_m + op.height_m;
    const double t = w.thickness;
    MeshObject& lining = NewObject(name + "/lining", SurfaceRole::kDoorLining, kLabelDoor, mat);
    w.Box(lining, a - kLiningM, a, 0, t, 0, top + kLiningM);
    w.Box(lining, b, b + kLiningM, 0, t, 0, top + kLiningM);
    w.Box(lining, a, b, 0, t, top, top + kLiningM);
    MeshObject& casing = NewObject(name + "/casing", SurfaceRole::kCasing, kLabelDoor, mat);
    const double ca = a - kLiningM - kDoorCasingM + kLiningM;
    const double cb = b + kLiningM + kDoorCasingM - kLiningM;
    w.Box(casing, ca, a, -kCasingDepthM, 0, 0, top + kDoorCasingM);
    w.Box(casing, b, cb, -kCasingDepthM, 0, 0, top + kDoorCasingM);
    w.Box(casing, a, b, -kCasingDepthM, 0, top, top + kDoorCasingM);
    AddPortal(w, op, a - kLiningM, b + kLiningM, 0, top + kLiningM);

    // Leaf: hinged at one jamb (left/right as seen from inside: s grows to
    // the viewer's left), swinging into the room (−out). A wide glazed door
    // has two leaves, one hinged at each jamb (French doors).
    MeshObject& leaf = NewObject(name + "/leaf", SurfaceRole::kDoorLeaf, kLabelDoor, mat);
    MeshObject* glass =
        op.glazed ? &NewObject(name + "/glass", SurfaceRole::kGlass, kLabelDoor, MaterialIndex("glass", field))
                  : nullptr;
    const double height = op.height_m - 0.006;
    const double angle = DegToRad(std::clamp(op.open_deg, 0.0, 180.0));
    const bool pair = op.glazed && op.width_m > 1.3;
    for (int k = 0; k < (pair ? 2 : 1); ++k) {
      const bool hinge_at_a = pair ? k == 0 : op.hinge == HingeSide::kRight;
      const double width = (pair ? 0.5 * op.width_m : op.width_m) - 0.006;
      const Vec3 e_closed = hinge_at_a ? w.along : Vec3(-w.along);
      const Vec3 hinge = w.At(hinge_at_a ? a + 0.003 : b - 0.003, 0, 0);
      const Vec3 e = std::cos(angle) * e_closed - std::sin(angle) * w.out;
      const Vec3 thick = std::cos(angle) * w.out + std::sin(angle) * e_closed;
      const Vec3 o = angle < 1e-6 ? Vec3(hinge + kLeafRecessM * w.out) : hinge;
      AddLeaf(leaf, glass, o, e, thick, width, height);
      AddBox(leaf, o + (width - 0.1) * e + Vec3(0, 0, 1.0) - 0.06 * thick, 0.12 * e, 0.06 * thick, Vec3(0, 0, 0.025));
    }

    // A small closed space behind a door that leads outside.
    Vec3 behind = w.At(0.5 * (a + b), t + 0.5, 0);
    if (op.glazed) {
      // Glazed: the outside shows through the panes, as through a window.
    } else if (!InsideAnyRoom(behind.head<2>()) && options_.next_room_depth_m > 0) {
      BuildNextRoom(w, a, b, top, field, room);
    } else if (!InsideAnyRoom(behind.head<2>())) {
      int wall_mat = MaterialIndex(room.wall_material, field);
      int floor_mat = MaterialIndex(room.floor_material, field);
      MeshObject& closet = NewObject(name + "/closet", SurfaceRole::kCloset, kLabelBackground, wall_mat);
      const double s0 = a - 0.5, s1 = b + 0.5, n0 = t, n1 = t + kClosetDepthM, z1 = top + 0.4;
      AddQuad(closet, w.At(s0, n1, 0), (s1 - s0) * w.along, Vec3(0, 0, z1));  // Back.
      AddQuad(closet, w.At(s0, n0, 0), (n1 - n0) * w.out, Vec3(0, 0, z1));    // Sides.
      AddQuad(closet, w.At(s1, n0, 0), (n1 - n0) * w.out, Vec3(0, 0, z1));
      AddQuad(closet, w.At(s0, n0, z1), (s1 - s0) * w.along, (n1 - n0) * w.out);  // Ceiling.
      MeshObject& cfloor = NewObject(name + "/closet_floor", SurfaceRole::kCloset, kLabelBackground, floor_mat);
      AddQuad(cfloor, w.At(s0, n0, 0), (s1 - s0) * w.along, (n1 - n0) * w.out);
      // Close the wall face around the closet opening.
      AddQuad(closet, w.At(s0, n0 + 1e-3, top + kLiningM), (s1 - s0) * w.along, Vec3(0, 0, z1 - top));
      AddQuad(closet, w.At(s0, n0 + 1e-3, 0), (a - kLiningM - s0) * w.along, Vec3(0, 0, z1));
      AddQuad(closet, w.At(b + kLiningM, n0 + 1e-3, 0), (s1 - b - kLiningM) * w.along, Vec3(0, 0, z1));
    }
  }

  // One door leaf: origin o (bottom corner at the hinge), e along its width,
  // `thick` across it, up +Z. Solid, or with `glass` a frame of stiles and
  // rails around a pane at mid-thickness (and a glazing bar on wide leaves).
  static void AddLeaf(MeshObject& leaf, MeshObject* glass, const Vec3& o, const Vec3& e, const Vec3& thick,
                      double width, double height) {
    const Vec3 up(0, 0, 1);
    auto part = [&](double u0, double u1, double z0, double z1) {
      AddBox(leaf, o + u0 * e + z0 * up, (u1 - u0) * e, kLeafThicknessM * thick, (z1 - z0) * up);
    };
    if (glass == nullptr) {
      part(0, width, 0, height);
      return;
    }
    const double stile = std::min(kGlazedStileM, 0.2 * width), top = kGlazedTopRailM, bottom = kGlazedBottomRailM;
    part(0, stile, 0, height);
    part(width - stile, width, 0, height);
    part(stile, width - stile, 0, bottom);
    part(stile, width - stile, height - top, height);
    if (width > 0.7) part(0.5 * width - 0.015, 0.5 * width + 0.015, bottom, height - top);
    AddQuad(*glass, o + stile * e + 0.5 * kLeafThicknessM * thick + bottom * up, (width - 2 * stile) * e,
            (height - top - bottom) * up);
  }

  // A lit room behind a door (SceneMeshOptions::next_room_depth_m): floor,
  // ceiling, three walls and the wall face around the doorway, facing in.
  void BuildNextRoom(const WallFrame& w, double a, double b, double top, const std::string& field, const Room& room) {
    const std::string& wall_name =
        options_.next_room_wall_material.empty() ? room.wall_material : options_.next_room_wall_material;
    const std::string& floor_name =
        options_.next_room_floor_material.empty() ? room.floor_material : options_.next_room_floor_material;
    int wall_mat = MaterialIndex(wall_name, field + ".next_room_wall_material");
    int floor_mat = MaterialIndex(floor_name, field + ".next_room_floor_material");
    int ceiling_mat = MaterialIndex(room.ceiling_material, field);
    const double t = w.thickness;
    const double s0 = a - options_.next_room_side_m, s1 = b + options_.next_room_side_m;
    const double n0 = t, n1 = t + options_.next_room_depth_m, z1 = std::max(room.height_m, top + 0.3);
    MeshObject& walls = NewObject("next_room/walls", SurfaceRole::kCloset, kLabelBackground, wall_mat);
    AddQuad(walls, w.At(s0, n1, 0), (s1 - s0) * w.along, Vec3(0, 0, z1));  // Far wall.
    AddQuad(walls, w.At(s0, n0, 0), (n1 - n0) * w.out, Vec3(0, 0, z1));    // Sides.
    AddQuad(walls, w.At(s1, n0, 0), (n1 - n0) * w.out, Vec3(0, 0, z1));
    AddQuad(walls, w.At(s0, n0 + 1e-3, top + kLiningM), (s1 - s0) * w.along, Vec3(0, 0, z1 - top));
    AddQuad(walls, w.At(s0, n0 + 1e-3, 0), (a - kLiningM - s0) * w.along, Vec3(0, 0, z1));
    AddQuad(walls, w.At(b + kLiningM, n0 + 1e-3, 0), (s1 - b - kLiningM) * w.along, Vec3(0, 0, z1));
    MeshObject& floor = NewObject("next_room/floor", SurfaceRole::kCloset, kLabelBackground, floor_mat);
    AddQuad(floor, w.At(s0, n0, 0), (s1 - s0) * w.along, (n1 - n0) * w.out);
    MeshObject& ceiling = NewObject("next_room/ceiling", SurfaceRole::kCloset, kLabelBackground, ceiling_mat);
    AddQuad(ceiling, w.At(s0, n0, z1), (s1 - s0) * w.along, (n1 - n0) * w.out);
    // A door-sized darker rectangle on the far wall: another doorway.
    MeshObject& far_door =
        NewObject("next_room/far_door", SurfaceRole::kCloset, kLabelBackground, MaterialIndex("door", field));
    const double c = 0.5 * (s0 + s1) + 0.25 * (s1 - s0) * std::sin(7.0 * a + 3.0 * n1);
    AddQuad(far_door, w.At(c - 0.42, n1 - 2e-3, 0), 0.84 * w.along, Vec3(0, 0, std::min(2.05, z1 - 0.1)));
    if (options_.next_room_light > 0) {
      AreaLight light;
      light.centre = w.At(0.5 * (s0 + s1), 0.5 * (n0 + n1), z1 - 0.031);
      light.half_u = 0.25 * w.along;
      light.half_v = 0.25 * w.out;
      light.area_m2 = 0.25;
      light.radiance = Vec3(1.0, 0.93, 0.85) * (options_.next_room_light * 8.0 * 0.36 / light.area_m2);
      mesh_.area_lights.push_back(light);
      MeshObject& o = NewObject("next_room/light", SurfaceRole::kLight, kLabelBackground, ceiling_mat);
      o.emission = F(light.radiance);
      AddBox(o, light.centre - light.half_u - light.half_v + Vec3(0, 0, 0.001), 2 * light.half_u, 2 * light.half_v,
             Vec3(0, 0, 0.03));
    }
  }

  void BuildWindow(const WallFrame& w, const Opening& op, const std::string& name, const std::string& field) {
    int frame_mat = MaterialIndex(op.material.empty() ? "window_frame" : op.material, field + ".material");
    int glass_mat = MaterialIndex("glass", field);
    const double a = op.offset_m;
    const double b = op.offset_m + op.width_m;
    const double sill = op.sill_m;
    const double top = op.sill_m + op.height_m;
    const double t = w.thickness;
    const double mid = 0.5 * t;
    MeshObject& lining = NewObject(name + "/lining", SurfaceRole::kDoorLining, kLabelWindow, frame_mat);
    w.Box(lining, a - kLiningM, a, 0, t, sill, top + kLiningM);
    w.Box(lining, b, b + kLiningM, 0, t, sill, top + kLiningM);
    w.Box(lining, a, b, 0, t, top, top + kLiningM);
    MeshObject& sill_board = NewObject(name + "/sill", SurfaceRole::kWindowSill, kLabelWindow, frame_mat);
    w.Box(sill_board, a - kLiningM - kSillOverhangM, b + kLiningM + kSillOverhangM, -kSillOverhangM, t,
          std::max(0.0, sill - kSillBoardM), sill);
    MeshObject& casing = NewObject(name + "/casing", SurfaceRole::kCasing, kLabelWindow, frame_mat);
    const double ca = a - kWindowCasingM, cb = b + kWindowCasingM;
    w.Box(casing, ca, a - kLiningM + 1e-4, -kCasingDepthM, 0, std::max(0.0, sill - kSillBoardM - kWindowCasingM),
          top + kLiningM + kWindowCasingM);
    w.Box(casing, b + kLiningM - 1e-4, cb, -kCasingDepthM, 0, std::max(0.0, sill - kSillBoardM - kWindowCasingM),
          top + kLiningM + kWindowCasingM);
    w.Box(casing, a - kLiningM, b + kLiningM, -kCasingDepthM, 0, top + kLiningM, top + kLiningM + kWindowCasingM);
    if (sill - kSillBoardM > 0) {
      w.Box(casing, a - kLiningM, b + kLiningM, -kCasingDepthM, 0, std::max(0.0, sill - kSillBoardM - kWindowCasingM),
            sill - kSillBoardM);
    }
    AddPortal(w, op, a - kLiningM, b + kLiningM, std::max(0.0, sill - kSillBoardM), top + kLiningM);

    // Frame at mid-wall, a mullion for wide windows, glass in the middle.
    MeshObject& frame = NewObject(name + "/frame", SurfaceRole::kWindowFrame, kLabelWindow, frame_mat);
    const double fw = std::clamp(op.frame_width_m, 0.0, 0.45 * std::min(op.width_m, op.height_m));
    const double n0 = mid - 0.5 * kFrameDepthM, n1 = mid + 0.5 * kFrameDepthM;
    w.Box(frame, a, a + fw, n0, n1, sill, top);
    w.Box(frame, b - fw, b, n0, n1, sill, top);
    w.Box(frame, a + fw, b - fw, n0, n1, sill, sill + fw);
    w.Box(frame, a + fw, b - fw, n0, n1, top - fw, top);
    if (op.width_m > 1.2) {
      double c = 0.5 * (a + b);
      w.Box(frame, c - 0.5 * fw, c + 0.5 * fw, n0, n1, sill + fw, top - fw);
    }
    if (op.glass) {
      MeshObject& glass = NewObject(name + "/glass", SurfaceRole::kGlass, kLabelWindow, glass_mat);
      AddQuad(glass, w.At(a + fw, mid, sill + fw), (b - a - 2 * fw) * w.along, Vec3(0, 0, op.height_m - 2 * fw));
    }
  }

  void BuildFurniture(int f) {
    const Furniture& fu = scene_.furniture[f];
    int mat = MaterialIndex(fu.material, fmt::format("furniture[{}].material", f));
    MeshObject& o =
        NewObject(fu.name.empty() ? fmt::format("furniture{}", f) : fu.name,
                  fu.material == "mirror" ? SurfaceRole::kMirror : SurfaceRole::kFurniture, kLabelBackground, mat);
    double y = DegToRad(fu.yaw_deg);
    Vec3 ex(std::cos(y), std::sin(y), 0), ey(-std::sin(y), std::cos(y), 0);
    Vec3 c(fu.centre_m.x(), fu.centre_m.y(), fu.elevation_m);
    AddBox(o, c - 0.5 * fu.size_m.x() * ex - 0.5 * fu.size_m.y() * ey, fu.size_m.x() * ex, fu.size_m.y() * ey,
           Vec3(0, 0, fu.size_m.z()));
  }

  void BuildLight(int l) {
    const Light& light = scene_.lights[l];
    Vec3 radiance = light.color * light.intensity;
    if (light.kind == LightKind::kSun) {
      double az = DegToRad(light.azimuth_deg), el = DegToRad(light.elevation_deg);
      mesh_.suns.push_back(
          {Vec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)), 3.0 * radiance, 0.01});
      return;
    }
    Vec2 size = light.kind == LightKind::kPoint ? Vec2(0.12, 0.12) : light.size_m;
    AreaLight a;
    // The panel hangs below its position; light leaves its underside.
    a.centre = light.position_m - Vec3(0, 0, 0.031);
    a.half_u = Vec3(0.5 * size.x(), 0, 0);
    a.half_v = Vec3(0, 0.5 * size.y(), 0);
    a.area_m2 = size.x() * size.y();
    // Same power for any panel size: radiance ∝ 1 / area (a 1.2 × 0.3 m panel has 8).
    a.radiance = radiance * (8.0 * 0.36 / std::max(a.area_m2, 1e-3));
    mesh_.area_lights.push_back(a);
    MeshObject& o =
        NewObject(fmt::format("light{}", l), SurfaceRole::kLight, kLabelBackground, MaterialIndex("ceiling", "lights"));
    o.emission = F(a.radiance);
    AddBox(o, a.centre - a.half_u - a.half_v + Vec3(0, 0, 0.001), 2 * a.half_u, 2 * a.half_v, Vec3(0, 0, 0.03));
  }

  void BuildExterior() {
    if (scene_.rooms.empty()) return;
    Vec2 lo(1e9, 1e9), hi(-1e9, -1e9);
    for (const Room& r : scene_.rooms) {
      for (const Vec2& p : r.polygon) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    }
    Vec2 centre = 0.5 * (lo + hi);
    double radius = 0.5 * (hi - lo).norm() + 1.0;
    MeshObject& ground =
        NewObject("ground", SurfaceRole::kGround, kLabelBackground, MaterialIndex("ground", "environment"));
    const double g = 400.0;
    AddQuad(ground, Vec3(centre.x() - g, centre.y() - g, -0.3), Vec3(2 * g, 0, 0), Vec3(0, 2 * g, 0));
    if (!scene_.environment.exterior_objects) return;

    std::mt19937_64 rng(scene_.seed * 0x9E3779B97F4A7C15ULL + 17);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    MeshObject& buildings =
        NewObject("buildings", SurfaceRole::kExterior, kLabelBackground, MaterialIndex("exterior", "environment"));
    int nb = 10 + static_cast<int>(u01(rng) * 8);
    for (int i = 0; i < nb; ++i) {
      double ang = 2 * kPi * (i + u01(rng)) / nb;
      double dist = radius + 14.0 + 25.0 * u01(rng);
      double w = 6 + 14 * u01(rng), dpt = 6 + 10 * u01(rng), h = 4 + 16 * u01(rng);
      Vec3 c(centre.x() + dist * std::cos(ang), centre.y() + dist * std::sin(ang), -0.3);
      double yaw = u01(rng) * kPi;
      Vec3 ex(std::cos(yaw), std::sin(yaw), 0), ey(-std::sin(yaw), std::cos(yaw), 0);
      AddBox(buildings, c - 0.5 * w * ex - 0.5 * dpt * ey, w * ex, dpt * ey, Vec3(0, 0, h));
    }
    MeshObject& trunks =
        NewObject("tree_trunks", SurfaceRole::kExterior, kLabelBackground, MaterialIndex("exterior", "environment"));
    MeshObject& crowns =
        NewObject("tree_crowns", SurfaceRole::kGround, kLabelBackground, MaterialIndex("ground", "environment"));
    int nt = 8 + static_cast<int>(u01(rng) * 10);
    for (int i = 0; i < nt; ++i) {
      double ang = 2 * kPi * u01(rng);
      double dist = radius + 4.0 + 10.0 * u01(rng);
      Vec3 base(centre.x() + dist * std::cos(ang), centre.y() + dist * std::sin(ang), -0.3);
      double th = 1.5 + 2.0 * u01(rng), cr = 1.2 + 1.8 * u01(rng);
      AddBox(trunks, base - Vec3(0.12, 0.12, 0), Vec3(0.24, 0, 0), Vec3(0, 0.24, 0), Vec3(0, 0, th + cr));
      // Crown: an octahedron.
      Vec3 c = base + Vec3(0, 0, th + cr);
      int b0 = static_cast<int>(crowns.vertices.size());
      double rz = cr * (1.0 + 0.4 * u01(rng));
      const Vec3 pts[6] = {c + Vec3(cr, 0, 0),  c + Vec3(0, cr, 0), c + Vec3(-cr, 0, 0),
                           c + Vec3(0, -cr, 0), c + Vec3(0, 0, rz), c + Vec3(0, 0, -0.8 * rz)};
      for (const Vec3& p : pts) crowns.vertices.push_back(F(p));
      for (int k = 0; k < 4; ++k) {
        crowns.triangles.emplace_back(b0 + k, b0 + (k + 1) % 4, b0 + 4);
        crowns.triangles.emplace_back(b0 + (k + 1) % 4, b0 + k, b0 + 5);
      }
    }
  }

  const Scene& scene_;
  const SceneMeshOptions& options_;
  SceneMesh mesh_;
  std::deque<MeshObject> objects_;
  std::vector<Material> materials_;
  std::map<std::string, int> index_;
};

}  // namespace

const char* SurfaceRoleName(SurfaceRole role) {
  switch (role) {
    case SurfaceRole::kFloor:
      return "floor";
    case SurfaceRole::kCeiling:
      return "ceiling";
    case SurfaceRole::kWall:
      return "wall";
    case SurfaceRole::kSkirting:
      return "skirting";
    case SurfaceRole::kDoorLeaf:
      return "door_leaf";
    case SurfaceRole::kDoorLining:
      return "lining";
    case SurfaceRole::kCasing:
      return "casing";
    case SurfaceRole::kWindowFrame:
      return "window_frame";
    case SurfaceRole::kGlass:
      return "glass";
    case SurfaceRole::kWindowSill:
      return "window_sill";
    case SurfaceRole::kFurniture:
      return "furniture";
    case SurfaceRole::kLight:
      return "light";
    case SurfaceRole::kGround:
      return "ground";
    case SurfaceRole::kExterior:
      return "exterior";
    case SurfaceRole::kCloset:
      return "closet";
    case SurfaceRole::kMirror:
      return "mirror";
  }
  return "?";
}

std::size_t SceneMesh::TriangleCount() const {
  std::size_t n = 0;
  for (const MeshObject& o : objects) n += o.triangles.size();
  return n;
}

std::string SceneMesh::ToString() const {
  return fmt::format("SceneMesh({} objects, {} triangles, {} portals, {} area lights, {} suns)", objects.size(),
                     TriangleCount(), portals.size(), area_lights.size(), suns.size());
}

const std::vector<Material>& RenderDefaultMaterials() {
  static const std::vector<Material> kMaterials = {
      {"wall", Vec3(0.78, 0.76, 0.72), 0.9, TextureKind::kPlaster, 0.4, Vec3(0.7, 0.68, 0.64)},
      {"floor", Vec3(0.45, 0.30, 0.18), 0.45, TextureKind::kWood, 0.18, Vec3(0.32, 0.2, 0.11)},
      {"ceiling", Vec3(0.9, 0.9, 0.88), 0.95, TextureKind::kPaint, 0.5, Vec3(0.85, 0.85, 0.83)},
      {"door", Vec3(0.85, 0.84, 0.8), 0.5, TextureKind::kPaint, 0.3, Vec3(0.8, 0.8, 0.76)},
      {"window_frame", Vec3(0.92, 0.92, 0.9), 0.4, TextureKind::kPaint, 0.3, Vec3(0.9, 0.9, 0.88)},
      {"glass", Vec3(0.9, 0.95, 0.95), 0.05, TextureKind::kNone, 1.0, Vec3(0.9, 0.95, 0.95)},
      {"furniture", Vec3(0.5, 0.36, 0.24), 0.6, TextureKind::kWood, 0.25, Vec3(0.4, 0.28, 0.18)},
      {"skirting", Vec3(0.9, 0.9, 0.88), 0.5, TextureKind::kPaint, 0.3, Vec3(0.88, 0.88, 0.86)},
      {"ground", Vec3(0.3, 0.38, 0.22), 1.0, TextureKind::kConcrete, 2.0, Vec3(0.25, 0.3, 0.18)},
      {"exterior", Vec3(0.6, 0.56, 0.5), 0.9, TextureKind::kConcrete, 1.5, Vec3(0.5, 0.46, 0.42)},
  };
  return kMaterials;
}

void SceneMeshOptions::Check() const {
  CheckArgument(std::isfinite(next_room_depth_m) && next_room_depth_m >= 0 && next_room_depth_m <= 50,
                fmt::format("SceneMeshOptions.next_room_depth_m = {}, must be in [0, 50]", next_room_depth_m));
  CheckArgument(std::isfinite(next_room_side_m) && next_room_side_m >= 0 && next_room_side_m <= 20,
                fmt::format("SceneMeshOptions.next_room_side_m = {}, must be in [0, 20]", next_room_side_m));
  CheckArgument(std::isfinite(next_room_light) && next_room_light >= 0,
                fmt::format("SceneMeshOptions.next_room_light = {}, must be >= 0", next_room_light));
}

SceneMesh BuildSceneMesh(const Scene& scene, const SceneMeshOptions& options) {
  options.Check();
  return MeshBuilder(scene, options).Build();
}

double IntersectPortal(const LabelPortal& portal, const Vec3& origin, const Vec3& dir) {
  Vec3 normal = portal.edge_u.cross(portal.edge_v);
  double denom = normal.dot(dir);
  if (std::abs(denom) < 1e-12) return -1.0;
  double t = normal.dot(portal.origin - origin) / denom;
  if (t <= 0) return -1.0;
  Vec3 q = origin + t * dir - portal.origin;
  double a = q.dot(portal.edge_u) / portal.edge_u.squaredNorm();
  double b = q.dot(portal.edge_v) / portal.edge_v.squaredNorm();
  if (a < 0 || a > 1 || b < 0 || b > 1) return -1.0;
  return t;
}

}  // namespace asbuilt
