#ifndef ASBUILT_RENDER_RENDERER_H_
#define ASBUILT_RENDER_RENDERER_H_

// Renders one stereo view of a scene in one pass: left and right RGB, the
// material-ID map, exact labels, depth, and optionally normals and instance
// ids. CPU ray tracing on Embree, tile-parallel with oneTBB, deterministic
// (same scene, options, seed and view key → bit-identical images).
//
// Cameras follow DESIGN.md through geometry/rig.h: the rig centre is the
// viewpoint's position, the left eye sits at −B/2 along the rig's right axis,
// pixel (i, j) is the ray through (i, j) exactly (OpenCV centres); a pitch
// tilts both cameras about the rig's right axis (positive looks up).
//
// RGB: area lights and sun with soft shadows, sky light through windows, one
// diffuse bounce, glossy highlights, procedural textures, glass that shows the
// exterior; the lighting is denoised (edge-aware, albedo kept) and developed
// with randomised camera effects (camera_effects.h). Labels, depth, normals
// and instance ids come from the ray through the pixel centre.

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "asbuilt/imageio/image.h"
#include "asbuilt/render/camera_effects.h"
#include "asbuilt/render/photo_textures.h"
#include "asbuilt/render/scene_mesh.h"
#include "asbuilt/scene/scene.h"
#include "asbuilt/util/fields.h"

namespace asbuilt {

// Nominal annotation colours of the ID map, per label id (RGB). A real
// renderer's ID pass drifts around these with the light (RenderOptions
// id_drift); labels/ turns them back into ids (PAPER.md §3).
inline constexpr std::array<std::array<std::uint8_t, 3>, 4> kIdMapColors = {{
    {0, 0, 0},      // 0 background / other
    {200, 40, 40},  // 1 wall
    {40, 180, 60},  // 2 door
    {40, 80, 200},  // 3 window
}};

struct RenderOptions {
  int samples_per_pixel = 4;    // RGB samples per pixel (jittered: antialiasing, soft light).
                                // More = less noise before denoising, linear cost.
  bool indirect_light = true;   // One diffuse bounce (off: direct light + ambient only, ~2× faster).
  int denoise_passes = 3;       // Edge-aware à-trous passes over the lighting; 0 = raw.
  double id_drift = 0.15;       // [0, 1]: how much ID-map colours follow the light (0 = flat colours).
  double camera_effects = 1.0;  // [0, 1]: strength of the randomised camera effects (0 = clean).
  bool phone_camera = false;    // Also a phone's processing (camera_effects.h RandomViewEffects):
                                // wider exposure, noise and JPEG ranges, chromatic aberration,
                                // sharpening, saturation. Off: the plain camera's effects.
  bool normals = false;         // Also produce camera-frame normals.
  bool instance_ids = false;    // Also produce per-object instance ids.
  bool layout_labels = false;   // Labels by the layout rule (docs/seg.md, as ZInD's and a review's):
                                // furniture, mirrors, lights and door leaves are looked through, so
                                // the wall behind them is labelled wall.
  std::uint64_t seed = 0;       // Sampling and effects; same seed → identical images.

  void Check() const;
};

// The field list (util/fields.h) of every option but the seed, which each
// caller binds with its own range (a JSON seed stays below 2^32).
const FieldList<RenderOptions>& RenderOptionFields();

// Where the rig is and what it sees.
struct StereoCamera {
  PinholeCamera camera;
  Viewpoint viewpoint;  // Rig centre, yaw, pitch.
  double baseline_m = 0.12;

  std::string ToString() const;
};

struct RenderedView {
  // Images of the camera's size (imageio/image_cv.h views them as cv::Mat).
  Image left;                    // 3 × 8-bit BGR.
  Image right;                   // 3 × 8-bit BGR; empty when the right eye was not asked for.
  Image idmap;                   // 3 × 8-bit BGR, left view.
  Image labels;                  // 8-bit label ids, left view.
  Image depth_mm;                // 16-bit millimetres along the optical axis; 0 = nothing within 65.535 m.
  Image normals;                 // 3 × 8-bit BGR encoding (n + 1) / 2 of camera-frame normals; empty unless asked.
  Image instance_ids;            // 16-bit: SceneMesh object index + 1, 0 = sky; empty unless asked.
  ViewEffects effects;           // The camera effects applied.
  std::int64_t rays_traced = 0;  // Every ray cast (primary, shadow, bounce), both eyes.
};

// A photograph as the albedo of a material (photo_textures.h). The photo is
// laid out like the procedural textures (in the plane most aligned with the
// surface) and tiles every size_m metres.
struct PhotoAlbedo {
  std::shared_ptr<const Photo> photo;
  double size_m = 0.5;           // Real-world width of one tile of the photo (its height keeps the aspect).
  double colour = 1.0;           // [0, 1]: 1 = the photo's colours, brightness matched to the material's
                                 // base colour; 0 = only its light/dark detail on the base colour.
  double detail = 1.0;           // [0, 2]: strength of the photo's light/dark detail (colour < 1).
  bool swap_uv = false;          // Turn the photo 90° (grain direction).
  bool keep_procedural = false;  // Also keep the material's procedural pattern's light/dark (panel gaps, joints).
  Vec2 offset_m = Vec2::Zero();  // Shift of the tiling.
};

// How a scene looks beyond its model: photographic albedo, the view outside,
// rooms behind doors. dataset synth's realism levers fill it; the default
// (empty) renders the scene's own materials under the sky gradient.
struct SceneLook {
  std::map<std::string, PhotoAlbedo> albedo;  // By material name.
  // Seen through windows (and wherever a ray leaves the building) instead of
  // the sky gradient and the ground and exterior boxes; lighting still comes
  // from the scene's sky and sun. Null: the sky gradient.
  std::shared_ptr<const Photo> outside;
  double outside_yaw_deg = 0.0;  // Turns the panorama about +Z.
  double outside_gain = 1.0;     // Radiance scale of the photo relative to the sky gradient's mean.
  SceneMeshOptions mesh;         // Rooms behind doors.

  // "SceneLook(albedo wall=paper.pat floor=parque1.pat, outside=city.exr, next_room_depth_m=3.2)".
  std::string ToString() const;
};

// A scene prepared for rendering (triangles + Embree BVH), reused across views.
class SceneRenderer {
 public:
  // Throws InputError for unknown material names (see BuildSceneMesh).
  explicit SceneRenderer(const Scene& scene, SceneLook look = {});
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // Renders one view. `view_key` tells views apart for sampling and effects
  // (use the view or item index). Thread-safe; uses all cores itself.
  RenderedView Render(const StereoCamera& camera, const RenderOptions& options, std::uint64_t view_key,
                      bool right_eye = true) const;

  const SceneMesh& mesh() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// World-from-camera transform of one eye, pitch included.
Eigen::Isometry3d WorldFromStereoEye(const Viewpoint& viewpoint, double baseline_m, StereoEye eye);

}  // namespace asbuilt

#endif  // ASBUILT_RENDER_RENDERER_H_
