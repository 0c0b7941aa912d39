#ifndef ASBUILT_RENDER_CAPTURE_RENDER_H_
#define ASBUILT_RENDER_CAPTURE_RENDER_H_

// `asbuilt render`: a scene's stereo views written as a synthetic capture
// (DESIGN.md capture.json), laid out like ../shared/data/blender-rooms-public:
//
//   out/capture.json   camera, baseline, frames (with labels and depth keys)
//   out/truth.json     SceneTruth (plan.json format)
//   out/left/NNN.png  out/right/NNN.png   8-bit RGB
//   out/labels/NNN.png  8-bit label ids      out/idmap/NNN.png  ID-map colours
//   out/depth/NNN.png   uint16 mm (z)        [out/normals/, out/instances/ when asked]
//
// Resumable: a view whose files all exist is skipped; every file is written
// atomically, capture.json and truth.json last.

#include <filesystem>
#include <string>

#include "asbuilt/render/renderer.h"
#include "asbuilt/scene/scene.h"
#include "asbuilt/util/progress.h"
#include "asbuilt/util/fields.h"

namespace asbuilt {

struct CaptureRenderOptions {
  RenderOptions render = {.camera_effects = 0.5};  // Survey-like: mild camera effects.
  int views = 0;          // > 0: a turn-in-place of this many views replaces the scene's views.
  double step_deg = 0.0;  // > 0: turn step (default with `views`: 360 / views).
  int width_px = 0;       // 0: the scene rig's size.
  int height_px = 0;
  double fov_deg = 0.0;     // 0: the scene rig's intrinsics; else horizontal FOV, centred.
  double baseline_m = 0.0;  // 0: the scene rig's baseline.
  bool resume = true;       // Skip views whose files all exist.

  void Check() const;
};
// Its field list: the flags of `asbuilt render` and the arguments of the MCP
// tool render_capture (capture_render_options.cc). `resume` stays a CLI flag
// (a tool always renders a fresh folder); the tool caps views and image size
// by its limits.
const FieldList<CaptureRenderOptions>& CaptureRenderOptionFields();

struct CaptureRenderSummary {
  int views = 0;        // In the capture.
  int rendered = 0;     // Rendered in this run.
  int skipped = 0;      // Already complete (resume).
  double seconds = -1;  // Wall time of this run; −1 if not run.
  std::string out_dir;

  std::string BriefReport() const;
};

// The views and camera the capture will use (options applied to the scene).
struct CaptureViews {
  PinholeCamera camera;
  double baseline_m = 0.12;
  std::vector<Viewpoint> viewpoints;
};
CaptureViews ResolveCaptureViews(const Scene& scene, const CaptureRenderOptions& options);

// Renders and writes the capture. Throws InvalidArgument for bad options,
// InputError for scene problems (pitched views cannot go in a capture), Error
// on write failures.
CaptureRenderSummary RenderCapture(const Scene& scene, const std::filesystem::path& out_dir,
                                   const CaptureRenderOptions& options = {}, const ProgressCallback& progress = {});

}  // namespace asbuilt

#endif  // ASBUILT_RENDER_CAPTURE_RENDER_H_
