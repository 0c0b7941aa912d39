#ifndef ASBUILT_SCENE_BLENDER_EXPORT_H_
#define ASBUILT_SCENE_BLENDER_EXPORT_H_

// Blender export: a self-contained Python script for Blender 3.x/4.x that
// builds the same scene (walls with real holes for doors and windows, door
// leaves, window frames and glass, floor, ceiling, skirting, furniture,
// materials with procedural textures, lights, sky) and a Parallel-mode
// stereo camera with the rig's baseline and intrinsics, one animation frame
// per viewpoint (ResolveViewpoints order; frame 1 = view 0), Cycles settings.
//
//   blender -b -P build.py -o OUT/ -a     renders every view: OUT/0001_L.png, OUT/0001_R.png, …
//   blender -b -P build.py -o OUT/ -f 3   renders view 2 only
//
// Every object's pass index is its label id (DESIGN.md: 0 other, 1 wall,
// 2 door, 3 window) and so is its materials' pass index; the script writes
// the object-index pass as OpenEXR beside the images (OUT/index/). Geometry
// is in world metres exactly as in the scene, so truth.json applies.

#include <filesystem>
#include <string>

#include "asbuilt/scene/scene.h"

namespace asbuilt {

struct BlenderExportOptions {
  int samples = 64;  // Cycles samples per pixel; more = less noise, slower.
  // Cycles denoiser (OpenImageDenoise on CPU). The script checks at run time
  // whether the Blender build has it and, when not, renders without and
  // prints a note (Debian's Blender 3.4 has none).
  bool denoise = true;
  bool index_pass = true;         // Write the object-index (label id) pass as EXR.
  double sensor_width_mm = 36.0;  // Blender sensor width; focal length follows from fx.
  // > 0: instead of the stereo pairs, one equirectangular 360° frame of this
  // width (height half of it) from the first view's position, level, in the
  // pano frame of pano/perspective.h (left edge along +Y, columns clockwise
  // seen from above): OUT/0001.png, the photo of a panorama capture.
  int panorama_width_px = 0;
  // The label pass: 1 sample per pixel at its centre (0.01 px filter), no
  // bounces, no denoising; only the index EXR is of use. Rendered apart from
  // the photo, so that each label pixel is exactly the surface its centre sees.
  bool labels_pass = false;

  void Check() const;
};

struct BlenderExportSummary {
  int objects = 0;  // Meshes the script creates (walls, openings, floor/ceiling, furniture, outside).
  int lights = 0;
  int frames = 0;  // One per viewpoint; one for a panorama.
  bool panorama = false;

  // "14 objects, 5 lights, 12 frames (stereo pairs)" or "…, 1 frame (360° panorama)".
  std::string BriefReport() const;
};

// The script's text. The scene should be valid (CheckScene); throws
// InvalidArgument for bad options.
std::string BlenderScript(const Scene& scene, const BlenderExportOptions& options = {},
                          BlenderExportSummary* summary = nullptr);

// Writes BlenderScript() atomically.
BlenderExportSummary WriteBlenderScript(const Scene& scene, const BlenderExportOptions& options,
                                        const std::filesystem::path& path);

}  // namespace asbuilt

#endif  // ASBUILT_SCENE_BLENDER_EXPORT_H_
