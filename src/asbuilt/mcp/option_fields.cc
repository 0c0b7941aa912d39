#include "asbuilt/mcp/option_fields.h"

#include <cstdint>

namespace asbuilt::mcp {

std::vector<ToolField> SceneTextOptionFields() {
  const SceneTextOptions d;
  return {
      {.name = "furnish", .type = ArgType::kBool,
       .description = "Add the room kind's usual furniture when the text names none.",
       .default_value = d.furnish, .cli_names = "!--no-furniture"},
      {.name = "add_door_if_none", .type = ArgType::kBool,
       .description = "Give a room with no door mentioned a door (listed in the assumptions).",
       .default_value = d.add_door_if_none, .cli_names = "!--no-default-door"},
      {.name = "rig_height_m", .type = ArgType::kNumber,
       .description = "Height of the default turn-in-place rig (capped below the ceiling).",
       .exclusive_minimum = 0.0, .maximum = 20.0, .default_value = d.rig_height_m,
       .cli_names = "--rig-height"},
      {.name = "turn_step_deg", .type = ArgType::kNumber,
       .description = "Yaw step of the default rig (30 → 12 views for a full turn).",
       .exclusive_minimum = 0.0, .maximum = 360.0, .default_value = d.turn_step_deg,
       .cli_names = "--step"},
      {.name = "seed", .type = ArgType::kInteger,
       .description = "Seed for furniture placement (same text + seed → same scene).",
       .minimum = 0.0, .maximum = 4294967295.0, .default_value = d.seed},
  };
}

SceneTextOptions SceneTextOptionsFromArgs(const ToolArgs& a) {
  SceneTextOptions o;
  o.furnish = a.Bool("furnish");
  o.add_door_if_none = a.Bool("add_door_if_none");
  o.rig_height_m = a.Number("rig_height_m");
  o.turn_step_deg = a.Number("turn_step_deg");
  o.seed = static_cast<std::uint64_t>(a.Integer("seed"));
  return o;
}

std::vector<ToolField> RandomSceneOptionFields() {
  const RandomSceneOptions d;
  auto probability = [](std::string_view name, std::string_view description, double value,
                        std::string_view cli_names = {}) {
    return ToolField{.name = name, .type = ArgType::kNumber, .description = description,
                     .minimum = 0.0, .maximum = 1.0, .default_value = value, .cli_names = cli_names};
  };
  return {
      {.name = "seed", .type = ArgType::kInteger,
       .description = "Seed of the (first) scene; same options + seed → same scene.",
       .minimum = 0.0, .maximum = 4294967295.0, .default_value = 0},
      {.name = "min_side_m", .type = ArgType::kNumber,
       .description = "Smallest side of the room's bounding box.", .minimum = 1.5,
       .maximum = 100.0, .default_value = d.min_side_m, .cli_names = "--min-side"},
      {.name = "max_side_m", .type = ArgType::kNumber,
       .description = "Largest side of the room's bounding box (>= min_side_m).", .minimum = 1.5,
       .maximum = 100.0, .default_value = d.max_side_m, .cli_names = "--max-side"},
      {.name = "min_height_m", .type = ArgType::kNumber, .description = "Lowest ceiling.",
       .minimum = 2.2, .maximum = 20.0, .default_value = d.min_height_m},
      {.name = "max_height_m", .type = ArgType::kNumber,
       .description = "Highest ceiling (>= min_height_m).", .minimum = 2.2, .maximum = 20.0,
       .default_value = d.max_height_m},
      probability("l_shape_probability", "Share of L-shaped rooms.", d.l_shape_probability),
      probability("rotated_probability", "Share of rooms turned by a random angle.",
                  d.rotated_probability),
      {.name = "min_openings", .type = ArgType::kInteger,
       .description = "Fewest doors + windows per room (the first is always a door).",
       .minimum = 1.0, .maximum = 12.0, .default_value = d.min_openings},
      {.name = "max_openings", .type = ArgType::kInteger,
       .description = "Most doors + windows per room (>= min_openings).", .minimum = 1.0,
       .maximum = 12.0, .default_value = d.max_openings},
      probability("same_wall_probability",
                  "Chance an opening joins a wall that already has one.", d.same_wall_probability),
      probability("corner_door_probability", "Chance a door sits tight in a corner.",
                  d.corner_door_probability),
      {.name = "min_furniture", .type = ArgType::kInteger,
       .description = "Fewest furniture pieces tried per room (some may not fit).",
       .minimum = 0.0, .maximum = 64.0, .default_value = d.min_furniture},
      {.name = "max_furniture", .type = ArgType::kInteger,
       .description = "Most furniture pieces tried per room (>= min_furniture).", .minimum = 0.0,
       .maximum = 64.0, .default_value = d.max_furniture},
      {.name = "turn_step_deg", .type = ArgType::kNumber,
       .description = "Rig yaw step; 360 / step views.", .exclusive_minimum = 0.0,
       .maximum = 360.0, .default_value = d.turn_step_deg, .cli_names = "--step"},
      {.name = "rig_spot", .type = ArgType::kEnum,
       .description = "Where the rig stands: random (anywhere 0.8 m clear of the walls, for "
                      "training views) or survey (where a surveyor would: the spot that sees every "
                      "wall, farthest from them).",
       .choices = {"random", "survey"}, .default_value = RigSpotName(d.rig_spot)},
  };
}

RandomSceneOptions RandomSceneOptionsFromArgs(const ToolArgs& a) {
  RandomSceneOptions o;
  o.min_side_m = a.Number("min_side_m");
  o.max_side_m = a.Number("max_side_m");
  o.min_height_m = a.Number("min_height_m");
  o.max_height_m = a.Number("max_height_m");
  o.l_shape_probability = a.Number("l_shape_probability");
  o.rotated_probability = a.Number("rotated_probability");
  o.min_openings = static_cast<int>(a.Integer("min_openings"));
  o.max_openings = static_cast<int>(a.Integer("max_openings"));
  o.same_wall_probability = a.Number("same_wall_probability");
  o.corner_door_probability = a.Number("corner_door_probability");
  o.min_furniture = static_cast<int>(a.Integer("min_furniture"));
  o.max_furniture = static_cast<int>(a.Integer("max_furniture"));
  o.turn_step_deg = a.Number("turn_step_deg");
  o.rig_spot = ParseRigSpot(a.String("rig_spot"));
  return o;
}

std::vector<ToolField> CaptureRenderOptionFields(const ToolLimits* limits) {
  const CaptureRenderOptions d;
  const double max_views = limits ? limits->max_views : 3600.0;
  const double max_width = limits ? limits->max_image_width_px : 16384.0;
  const double max_height = limits ? limits->max_image_height_px : 16384.0;
  return {
      {.name = "views", .type = ArgType::kInteger,
       .description = "A turn-in-place of this many views replaces the scene's views; 0 keeps "
                      "the scene's.",
       .minimum = 0.0, .maximum = max_views, .default_value = d.views},
      {.name = "step_deg", .type = ArgType::kNumber,
       .description = "Turn step of that turn; 0 = 360 / views.", .minimum = 0.0,
       .maximum = 360.0, .default_value = d.step_deg},
      {.name = "width_px", .type = ArgType::kInteger,
       .description = "Image width; 0 = the scene rig's (give with height_px).", .minimum = 0.0,
       .maximum = max_width, .default_value = d.width_px},
      {.name = "height_px", .type = ArgType::kInteger,
       .description = "Image height; 0 = the scene rig's (give with width_px).", .minimum = 0.0,
       .maximum = max_height, .default_value = d.height_px},
      {.name = "fov_deg", .type = ArgType::kNumber,
       .description = "Horizontal field of view, centred; 0 = the scene rig's intrinsics.",
       .minimum = 0.0, .maximum = 178.0, .default_value = d.fov_deg},
      {.name = "baseline_m", .type = ArgType::kNumber,
       .description = "Stereo baseline; 0 = the scene rig's.", .minimum = 0.0, .maximum = 10.0,
       .default_value = d.baseline_m},
      {.name = "samples_per_pixel", .type = ArgType::kInteger,
       .description = "RGB path-tracing samples per pixel (less noise vs linear time).",
       .minimum = 1.0, .maximum = 256.0, .default_value = d.render.samples_per_pixel,
       .cli_names = "--spp"},
      {.name = "seed", .type = ArgType::kInteger,
       .description = "Sampling and camera-effect seed; same seed → identical images.",
       .minimum = 0.0, .maximum = 4294967295.0, .default_value = d.render.seed},
      {.name = "camera_effects", .type = ArgType::kNumber,
       .description = "Strength of the randomised camera effects (exposure, white balance, "
                      "noise, blur, JPEG); 0 = clean.",
       .minimum = 0.0, .maximum = 1.0, .default_value = d.render.camera_effects,
       .cli_names = "--effects"},
      {.name = "id_drift", .type = ArgType::kNumber,
       .description = "How much ID-map colours follow the light; 0 = flat colours.",
       .minimum = 0.0, .maximum = 1.0, .default_value = d.render.id_drift},
      {.name = "denoise_passes", .type = ArgType::kInteger,
       .description = "Edge-aware denoising passes over the lighting; 0 = raw.", .minimum = 0.0,
       .maximum = 8.0, .default_value = d.render.denoise_passes},
      {.name = "indirect_light", .type = ArgType::kBool,
       .description = "One diffuse bounce; off = direct light + ambient only (about 2× faster).",
       .default_value = d.render.indirect_light, .cli_names = "!--no-indirect"},
      {.name = "normals", .type = ArgType::kBool,
       .description = "Also write normals/ (camera frame).", .default_value = d.render.normals},
      {.name = "instance_ids", .type = ArgType::kBool,
       .description = "Also write instances/ (uint16 object index + 1, 0 = sky).",
       .default_value = d.render.instance_ids, .cli_names = "--instances"},
  };
}

CaptureRenderOptions CaptureRenderOptionsFromArgs(const ToolArgs& a) {
  CaptureRenderOptions o;
  o.views = static_cast<int>(a.Integer("views"));
  o.step_deg = a.Number("step_deg");
  o.width_px = static_cast<int>(a.Integer("width_px"));
  o.height_px = static_cast<int>(a.Integer("height_px"));
  o.fov_deg = a.Number("fov_deg");
  o.baseline_m = a.Number("baseline_m");
  o.render.samples_per_pixel = static_cast<int>(a.Integer("samples_per_pixel"));
  o.render.seed = static_cast<std::uint64_t>(a.Integer("seed"));
  o.render.camera_effects = a.Number("camera_effects");
  o.render.id_drift = a.Number("id_drift");
  o.render.denoise_passes = static_cast<int>(a.Integer("denoise_passes"));
  o.render.indirect_light = a.Bool("indirect_light");
  o.render.normals = a.Bool("normals");
  o.render.instance_ids = a.Bool("instance_ids");
  return o;
}

}  // namespace asbuilt::mcp
