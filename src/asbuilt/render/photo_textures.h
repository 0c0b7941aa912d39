#ifndef ASBUILT_RENDER_PHOTO_TEXTURES_H_
#define ASBUILT_RENDER_PHOTO_TEXTURES_H_

// Photographs as albedo maps and as the view outside, read at run time from
// image collections that Debian packages install (docs/render.md, "Photo
// textures": GIMP's patterns, Blender's studio-light HDR panoramas). No image
// is ever copied into the repository; a folder that is absent is skipped, so
// everything works (with procedural textures only) where none is installed.
//
// What a file is used for comes from its path (ClassifyPhoto): wood, stone,
// fabric and paper textures (tileable, sRGB), and outdoor environments
// (equirectangular HDR panoramas, linear radiance) or flat outdoor photos.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "asbuilt/imageio/image.h"
#include "asbuilt/render/scene_mesh.h"

namespace asbuilt {

enum class PhotoKind {
  kWood,         // Planks, parquet, veneer: floors, doors, cabinets.
  kStone,        // Marble, granite, slate, brick: floors, worktops.
  kFabric,       // Burlap, leather: carpets, curtains, upholstery.
  kPaper,        // Paper, cork: fine relief for painted walls and ceilings.
  kEnvironment,  // Equirectangular outdoor panorama (linear HDR): the view outside.
  kView,         // A flat outdoor photo (a desktop wallpaper): the view outside.
};
const char* PhotoKindName(PhotoKind kind);  // "wood", "stone", …

struct Photo {
  std::string path;  // The file it came from (provenance; written to item meta).
  PhotoKind kind = PhotoKind::kWood;
  Image linear_rgb;            // 3 × 32-bit float, channels R, G, B, linear (sRGB decoded; HDR as stored).
  Vec3f mean = Vec3f::Zero();  // Mean linear RGB.
  float mean_luminance = 0.0f;

  // Bilinear sample at texture coordinates (u, v) in image widths/heights,
  // wrapping (textures tile); `clamp_v` clamps rows instead (panoramas).
  // Linear RGB.
  Vec3f Sample(float u, float v, bool clamp_v = false) const;
  // The environment's radiance towards world direction `dir` (unit, +Z up),
  // the panorama turned by `yaw_rad` about +Z. kEnvironment: equirectangular;
  // kView: the photo spread over 120° of azimuth and −25°…+45° of elevation,
  // mirrored to fill the circle, its bottom row below. Linear RGB.
  Vec3f Outside(const Vec3f& dir, float yaw_rad) const;
};

// Where Debian installs the collections (absent ones are skipped):
// /usr/share/gimp/2.0/patterns (gimp-data), /usr/share/blender/datafiles/
// studiolights/world and /usr/share/blender/<version>/datafiles/studiolights/
// world (blender).
std::vector<std::filesystem::path> DefaultPhotoDirs();

struct PhotoLibraryOptions {
  std::vector<std::filesystem::path> dirs = DefaultPhotoDirs();  // Searched recursively; absent ones skipped.
  int max_side_px = 1024;  // Larger images are shrunk to this (memory; textures are small anyway).

  void Check() const;
};

// What a file is for, from its path, or nullopt to skip it: GIMP .pat files
// by folder (Wood, Stone, Fabric, Animal/leather, Paper; not Legacy, Food,
// Water, Sky, Plant, nor bark, craters, moon, amethyst); .exr/.hdr files as
// environments unless they are indoor, studio or matcap lights; other images
// by keywords in their path (wood/parquet, marble/stone/granite/tile/brick,
// fabric/carpet/leather, paper/plaster), else as flat views when in a folder
// named backgrounds or wallpapers.
std::optional<PhotoKind> ClassifyPhoto(const std::filesystem::path& path);

// A GIMP pattern (.pat, version 1: header, name, 8-bit pixels of 1–4
// channels) as 3 × 8-bit BGR. Throws InputError naming the file and field.
Image ReadGimpPattern(const std::filesystem::path& path);

struct PhotoLibrary {
  std::vector<std::shared_ptr<const Photo>> photos;  // In path order (deterministic).

  std::vector<std::shared_ptr<const Photo>> OfKind(PhotoKind kind) const;
  bool empty() const { return photos.empty(); }
  // "PhotoLibrary(13 wood, 9 stone, 2 fabric, 2 paper, 6 environment, 0 view)".
  std::string ToString() const;
};

// Reads every classified image under options.dirs. Unreadable files are
// skipped with a warning on stderr; never throws for missing folders.
PhotoLibrary LoadPhotoLibrary(const PhotoLibraryOptions& options);

}  // namespace asbuilt

#endif  // ASBUILT_RENDER_PHOTO_TEXTURES_H_
