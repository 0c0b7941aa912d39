#ifndef ASBUILT_FORMATS_ZIND_H_
#define ASBUILT_FORMATS_ZIND_H_

// Zillow Indoor Dataset (ZInD, Cruz et al. CVPR 2021) tours: a reader for a
// tour's `zind_data.json` (format: ../shared/data/zind_sample_tour/
// ZIND_FORMAT.md) that gives every panorama's annotated layout in metres, in
// asbuilt's conventions.
//
// LICENCE: ZInD is for academic, non-commercial use only. asbuilt reads it at
// run time as a test set for research measurement; nothing derived from it
// (views, labels, plans, models) is trained on, shipped or committed.
//
// The pano frame. ZInD stores each panorama's layout in a local frame, x and
// y scaled so that the camera is 1 unit above the floor, with y pointing the
// way an image's rows do (seen from above, ZInD's frames are mirror images of
// a right-handed one). The reader turns them into a *pano frame* that follows
// asbuilt's world conventions (DESIGN.md): right-handed, metres, +Z up, floor
// at z = 0, the camera at (0, 0, camera_height_m), and
//   pano_xy = (x_zind, −y_zind) · metres_per_unit.
// In this frame an equirectangular pixel column u of a W-pixel-wide panorama
// (OpenCV centres: the left edge is u = −0.5) looks along yaw
//   ψ = −2π·(u + 0.5)/W        (DESIGN.md yaw: ψ = 0 looks along +Y),
// i.e. the left edge looks along +Y, columns run clockwise seen from above
// and the middle column looks along −Y. Row v looks up at elevation
// π·(0.5 − (v + 0.5)/H). Checked on the sample tour: every door's segment
// projects onto the door in the picture (pano/ tests and overlays).
//
//   ZindTour tour = ReadZindTour("../shared/data/zind_sample_tour");
//   for (const ZindPanorama* p : tour.BenchmarkPanoramas()) {
//     Plan truth = ZindTruthPlan(*p);           // plan.json in the pano frame
//   }

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/geometry/rig.h"

namespace asbuilt {

// ZInD's three kinds of hole in a wall. kOpening is a passage without a door
// (ZInD "openings": an archway, the open side of an L-shaped room).
enum class ZindOpeningKind { kDoor, kWindow, kOpening };
const char* ZindOpeningKindName(ZindOpeningKind kind);  // "door", "window", "opening"

// A door, window or passage: a vertical rectangle on one wall.
struct ZindOpening {
  ZindOpeningKind kind = ZindOpeningKind::kDoor;
  Vec2 start_m = Vec2::Zero();  // Its ends on the floor, pano frame, metres (file order).
  Vec2 end_m = Vec2::Zero();
  double bottom_m = 0.0;  // Above the floor (a door's is about 0, a window's its sill).
  double top_m = 0.0;
  // The layout edge (vertices[wall], vertices[wall + 1]) it lies on: the edge
  // whose line both ends lie nearest to. -1 when no edge passes within
  // ZindReadOptions::max_opening_offset_m of both ends and overlaps it.
  int wall = -1;
  double offset_m = 0.0;  // The larger distance of its two ends from that edge's line.

  double Width() const { return (end_m - start_m).norm(); }
  double Height() const { return top_m - bottom_m; }
  std::string ToString() const;  // "door 0.81 m wide, 0.01–1.99 m on wall 3".
};

// One annotated layout of a panorama (ZInD layout_raw / _complete / _visible).
struct ZindLayout {
  // The room polygon (closed implicitly), pano frame, metres; the order of
  // the file (ZInD's mirror makes it turn the other way: use PolygonArea's
  // sign, not the order, where it matters).
  std::vector<Vec2> vertices_m;
  std::vector<ZindOpening> openings;  // Doors, then windows, then passages, each in file order.
  // ZInD "internal": polygons not joined to the walls (a kitchen island).
  std::vector<std::vector<Vec2>> internal_m;

  int Count(ZindOpeningKind kind) const;
  // The wall from vertex i to vertex i + 1 (mod n).
  Vec2 WallStart(int i) const { return vertices_m[static_cast<std::size_t>(i)]; }
  Vec2 WallEnd(int i) const { return vertices_m[(static_cast<std::size_t>(i) + 1) % vertices_m.size()]; }
};

enum class ZindLayoutKind { kRaw, kComplete, kVisible };
const char* ZindLayoutKindName(ZindLayoutKind kind);  // "raw", "complete", "visible"

struct ZindPanorama {
  // Where it sits in the file: merger.<floor>.<complete_room>.<partial_room>.<pano>.
  std::string floor_id;          // "floor_01"
  std::string complete_room_id;  // "complete_room_01"
  std::string partial_room_id;   // "partial_room_01"
  std::string pano_id;           // "pano_15"
  std::string label;             // Room type as annotated: "bedroom", "kitchen", …
  bool is_primary = false;       // The panorama the annotator drew the room from.
  bool is_inside = true;         // Taken inside its layout (false: looking into a closet from outside).
  bool is_ceiling_flat = true;
  std::filesystem::path image;  // The equirectangular JPEG, resolved against the tour folder.
  std::string image_path;       // As written in the file (relative to the tour folder).

  // Scale: metres per ZInD local unit = floor_plan_transformation.scale ×
  // scale_meters_per_coordinate[floor]. ZInD's units make the camera 1 unit
  // high, so camera_height_m equals it. When the tour has no metric scale
  // (scale_meters_per_coordinate null) `metric` is false and every length
  // below is in camera heights (metres_per_unit = 1).
  bool metric = true;
  double metres_per_unit = 1.0;
  double camera_height_m = 1.0;   // Above the floor.
  double ceiling_height_m = 0.0;  // Above the floor.

  ZindLayout layout_raw;  // What the annotator drew from this panorama (always present).
  std::optional<ZindLayout> layout_complete, layout_visible;

  // Pano frame → the floor's frame (rigid, in the pano frame's units,
  // mirrored like it): ZInD's floor_plan_transformation (global =
  // scale·R(θ)·local + translation, ZInD units) in asbuilt's conventions, so
  // the panoramas of one floor can be drawn together.
  Eigen::Isometry2d floor_from_pano = Eigen::Isometry2d::Identity();

  // "floor_01/complete_room_01/partial_room_01/pano_15".
  std::string Name() const;
  // One of the layouts; throws InvalidArgument naming the panorama when the
  // file has none of that kind.
  const ZindLayout& Layout(ZindLayoutKind kind) const;
  // "pano_15 (bonus room, primary, inside): camera 1.435 m, ceiling 2.34 m, 4 walls, 3 doors, 0 windows, 0 passages".
  std::string ToString() const;
};

struct ZindReadOptions {
  // An opening is placed on the layout edge whose line both its ends lie
  // within this distance of (ZInD's annotation tool puts them on the edge:
  // the sample tour's offsets are < 1 mm).
  double max_opening_offset_m = 0.05;
  void Check() const;
};

struct ZindTour {
  std::filesystem::path dir;            // The tour folder (zind_data.json's folder).
  std::filesystem::path file;           // zind_data.json.
  std::vector<ZindPanorama> panoramas;  // In file order.

  // Primary panoramas taken inside their layout: the ones whose raw layout
  // describes the room around the camera (the sample tour has 13).
  std::vector<const ZindPanorama*> BenchmarkPanoramas() const;
  // By pano id ("pano_15"), full Name(), or image path as in the file;
  // nullptr when none matches.
  const ZindPanorama* Find(const std::string& key) const;
  std::string ToString() const;  // "ZInD tour …/zind_sample_tour: 32 panoramas, 19 primary, 13 primary inside".
};

// Reads a ZInD tour: `path` is a tour folder or its zind_data.json. Throws
// InputError naming the file and the field path of every problem
// (`zind_data.json: merger.floor_01.complete_room_01.partial_room_01.pano_15.
// layout_raw.doors: expected a multiple of 3 points, got 8`); a panorama
// image that does not exist is an error too.
ZindTour ReadZindTour(const std::filesystem::path& path, const ZindReadOptions& options = {});

// The panorama's room as an asbuilt plan (plan.json) in its pano frame:
// one wall per layout edge (the inner face; height = ceiling), each door and
// window on its wall (width, height, sill = bottom), the room polygon
// counter-clockwise with its area. ZInD passages (kOpening) have no plan.json
// kind and are left out; openings on no wall (wall = -1) too. Throws
// InvalidArgument when the layout has fewer than 3 vertices.
Plan ZindTruthPlan(const ZindPanorama& pano, ZindLayoutKind layout = ZindLayoutKind::kRaw);

// The ZInD licence line every output derived from ZInD carries.
inline constexpr const char* kZindNotice = "ZInD: academic use only; research measurement only, never training data";

}  // namespace asbuilt

#endif  // ASBUILT_FORMATS_ZIND_H_
