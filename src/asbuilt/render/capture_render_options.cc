// CaptureRenderOptions' field list (capture_render.h): `asbuilt render` flags
// and the MCP tool render_capture.

#include "asbuilt/render/capture_render.h"

namespace asbuilt {

const FieldList<CaptureRenderOptions>& CaptureRenderOptionFields() {
  using O = CaptureRenderOptions;
  using R = RenderOptions;
  static const FieldList<O> kList = {
      Bind(&O::views, {.name = "views",
                       .description = "A turn-in-place of this many views replaces the scene's views; 0 keeps "
                                      "the scene's.",
                       .minimum = 0.0,
                       .maximum = 3600.0}),
      Bind(&O::step_deg, {.name = "step_deg",
                          .description = "Turn step of that turn; 0 = 360 / views.",
                          .minimum = 0.0,
                          .maximum = 360.0}),
      Bind(&O::width_px, {.name = "width_px",
                          .description = "Image width; 0 = the scene rig's (give with height_px).",
                          .minimum = 0.0,
                          .maximum = 16384.0}),
      Bind(&O::height_px, {.name = "height_px",
                           .description = "Image height; 0 = the scene rig's (give with width_px).",
                           .minimum = 0.0,
                           .maximum = 16384.0}),
      Bind(&O::fov_deg, {.name = "fov_deg",
                         .description = "Horizontal field of view, centred; 0 = the scene rig's intrinsics.",
                         .minimum = 0.0,
                         .maximum = 178.0}),
      Bind(&O::baseline_m, {.name = "baseline_m",
                            .description = "Stereo baseline; 0 = the scene rig's.",
                            .minimum = 0.0,
                            .maximum = 10.0}),
      Bind(&O::render, &R::samples_per_pixel,
           {.name = "samples_per_pixel",
            .description = "RGB path-tracing samples per pixel (less noise vs linear time).",
            .minimum = 1.0,
            .maximum = 256.0}),
      Bind(&O::render, &R::seed,
           {.name = "seed",
            .description = "Sampling and camera-effect seed; same seed → identical images.",
            .minimum = 0.0,
            .maximum = 4294967295.0}),
      Bind(&O::render, &R::camera_effects,
           {.name = "camera_effects",
            .description = "Strength of the randomised camera effects (exposure, white balance, noise, blur, "
                           "JPEG); 0 = clean.",
            .minimum = 0.0,
            .maximum = 1.0}),
      Bind(&O::render, &R::id_drift,
           {.name = "id_drift",
            .description = "How much ID-map colours follow the light; 0 = flat colours.",
            .minimum = 0.0,
            .maximum = 1.0}),
      Bind(&O::render, &R::denoise_passes,
           {.name = "denoise_passes",
            .description = "Edge-aware denoising passes over the lighting; 0 = raw.",
            .minimum = 0.0,
            .maximum = 8.0}),
      Bind(&O::render, &R::indirect_light,
           {.name = "indirect_light",
            .description = "One diffuse bounce; off = direct light + ambient only (about 2× faster)."}),
      Bind(&O::render, &R::normals, {.name = "normals", .description = "Also write normals/ (camera frame)."}),
      Bind(&O::render, &R::instance_ids,
           {.name = "instance_ids", .description = "Also write instances/ (uint16 object index + 1, 0 = sky)."}),
  };
  return kList;
}

}  // namespace asbuilt
