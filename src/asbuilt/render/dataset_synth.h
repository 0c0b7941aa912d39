#ifndef ASBUILT_RENDER_DATASET_SYNTH_H_
#define ASBUILT_RENDER_DATASET_SYNTH_H_

// `asbuilt dataset synth`: a synthetic segmentation training set from random
// rooms (scene/procedural.h) rendered by the ray tracer.
//
//   DIR/images/NNNNNN.png   8-bit RGB (left eye), camera effects randomised
//   DIR/labels/NNNNNN.png   8-bit label ids (0 background, 1 wall, 2 door, 3 window)
//   DIR/idmaps/NNNNNN.png   ID-map colours (render/renderer.h kIdMapColors, drifting)
//   DIR/depth/NNNNNN.png    uint16 mm along the optical axis (0 = none)
//   DIR/meta/NNNNNN.json    scene seed, view kind, camera, pose, effects, class fractions
//
// Items are like the paper's photographs: a single camera 1.5–3 m from a
// wall, door or window, 1–2 classes dominating, varied height and pitch; a
// share are level rig views from the room's turn-in-place spot. Item i is a
// pure function of (options, i): shards split the items into contiguous
// blocks, so shards never overlap and their union equals the unsharded run.
// Resumable: a complete item (formats/synth_dataset.h: every file there; the
// meta file is written last, every file atomically) is skipped, and the temp
// files of a killed writer are removed. Memory stays flat: one scene is held at a time.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/render/photo_textures.h"
#include "asbuilt/render/renderer.h"
#include "asbuilt/scene/procedural.h"
#include "asbuilt/util/progress.h"
#include "asbuilt/util/shard.h"

namespace asbuilt {

// Realism levers (issue 21: real photos; docs/render.md "Realism levers").
// All off by default, so a seed gives the items it always gave (the shipped
// model's data, MODEL_CARD.md, stays reproducible). Each lever changes what
// the scene holds or how it looks, never a label convention.
struct SynthLevers {
  bool photo_textures = false;      // Photos (photo_textures.h) as albedo of walls, ceilings, floors, doors,
                                    // cabinets, worktops, furniture, curtains.
  bool outside_photos = false;      // An outdoor HDR panorama seen through windows instead of the sky
                                    // gradient and boxes; often brighter than the room (blown out).
  bool next_rooms = false;          // Doors open onto a lit room (2.5–5 m deep) instead of a dark 1.2 m
                                    // closet, and 45 % of closed doors swing open. Door label over the opening.
  bool door_leaves = false;         // 80 % of doors white-painted or wooden (leaf, lining, casing).
  bool home_palette = false;        // 65 % of rooms: white or off-white walls and ceiling, as most homes.
  bool sunlight = false;            // Half the rooms: a low strong sun in through a window (sunlit patches).
  bool kitchens = false;            // 35 % of rooms: kitchen units, worktops, wall units, white appliances (label 0).
  bool wall_details = false;        // 70 % of rooms: radiators, sockets, switches (label 0).
  bool window_dressing = false;     // Half the windows: curtains (label 0) or a roller blind in the opening (window).
  bool phone_camera = false;        // RenderOptions::phone_camera: wider exposure/noise/JPEG, chromatic
                                    // aberration, sharpening, saturation.
  bool glass_doors = false;         // 30 % of doors glazed to the floor (patio / French doors), the outside
                                    // seen through them; label door over the whole opening.
  bool close_views = false;         // 30 % of views 0.4–1.5 m from a plain wall or into a corner, level or
                                    // pitched up to the wall–ceiling edge: the wall fills the frame.
  bool ceiling_like_walls = false;  // Half the rooms: the ceiling in the walls' paint, soft fill light.
  bool wall_art = false;            // 60 % of rooms: framed pictures, mirrors, a TV on the walls (label 0).
  bool close_doors = false;         // 20 % of views 0.5–1.6 m from a door, ±40° off its normal: the door (an
                                    // open leaf, the room beyond) fills much of the frame, as in hallways.

  bool Any() const;
  // Comma-separated names of the levers that are on, or "none".
  std::string ToString() const;
};
// The lever names, in SynthLevers' order ("photo_textures", …, "phone_camera").
const std::vector<std::string>& SynthLeverNames();
// "all", "none", or comma-separated names (each optionally prefixed by "-"
// to turn it off after "all": "all,-sunlight"). Throws InvalidArgument
// naming an unknown lever.
SynthLevers ParseSynthLevers(std::string_view list);

struct DatasetSynthOptions {
  int count = 100;         // Items in the whole dataset (all shards).
  std::uint64_t seed = 0;  // Scenes, views and rendering.
  int shard_index = 0;     // This run renders shard shard_index of shard_count.
  int shard_count = 1;
  int width_px = 320;  // Image size of every item.
  int height_px = 240;
  double min_hfov_deg = 60.0;  // Horizontal field of view, drawn per item.
  double max_hfov_deg = 80.0;
  double rig_view_share = 0.25;  // Share of level rig views (the rest: photo-like views).
  int items_per_scene = 8;       // Consecutive items share a room (amortises scene building).
  RenderOptions render = {.samples_per_pixel = 2, .camera_effects = 1.0};
  RandomSceneOptions scene;  // The random rooms.
  bool resume = true;        // Skip items already written.
  SynthLevers levers;        // Realism levers (all off: the scene as modelled).
  std::vector<std::filesystem::path> photo_dirs =
      DefaultPhotoDirs();  // Where photo_textures and
                           // outside_photos look (absent folders skipped; none found:
                           // procedural textures and the sky gradient, with a warning).

  void Check() const;
};

// The field list (util/fields.h): the options above but the shard, resume,
// the scene's options and the photo folders; the render options it nests
// keep their names (samples_per_pixel, …).
const FieldList<DatasetSynthOptions>& DatasetSynthOptionFields();

struct DatasetSynthSummary {
  int items = 0;  // In this shard.
  int rendered = 0;
  int skipped = 0;                             // Already complete (resume).
  int scenes = 0;                              // Rooms built in this run.
  double seconds = -1;                         // Wall time; −1 if not run.
  std::array<std::int64_t, 4> class_pixels{};  // Over the rendered items.
  std::string dir;

  std::string BriefReport() const;
};

// The scene and camera of item `index` (exposed for tests and tools).
struct SynthItem {
  int index = 0;
  std::uint64_t scene_seed = 0;
  std::string kind;    // "photo" or "rig".
  std::string target;  // "wall", "door", "window", "close_wall", "corner" (photo views) or "turn".
  StereoCamera camera;
};
SynthItem PlanSynthItem(const DatasetSynthOptions& options, const Scene& scene, int index);
// The scene options with the scene-side levers turned on (door_leaves,
// next_rooms' open doors, sunlight, kitchens, wall_details, window_dressing,
// glass_doors, ceiling_like_walls, wall_art).
RandomSceneOptions LeveredSceneOptions(const DatasetSynthOptions& options);
// The look of a scene under the render-side levers (photo_textures,
// outside_photos, next_rooms), drawn from `seed`; may add materials to
// `scene` (the next room's walls and floor). Empty when those levers are off.
SceneLook MakeSceneLook(const SynthLevers& levers, const PhotoLibrary& photos, Scene& scene, std::uint64_t seed);
std::uint64_t SynthSceneSeed(const DatasetSynthOptions& options, int index);

// What DIR/synth.json records (formats/synth_dataset.h): every option that
// changes an item's bytes; not the shard, not resume.
nlohmann::json SynthRecordOptions(const DatasetSynthOptions& options);

// Renders this shard's items into `dir`. A folder made with other options is
// refused (InputError naming them) before anything is written.
DatasetSynthSummary SynthesizeDataset(const std::filesystem::path& dir, const DatasetSynthOptions& options,
                                      const ProgressCallback& progress = {});

}  // namespace asbuilt

#endif  // ASBUILT_RENDER_DATASET_SYNTH_H_
