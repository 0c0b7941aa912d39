// CaptureRenderOptions' field list (capture_render.h): `asbuilt render` flags
// and the MCP tool render_capture.

#include "asbuilt/render/capture_render.h"

namespace asbuilt {

const FieldList<CaptureRenderOptions>& CaptureRenderOptionFields() {
  using O = CaptureRenderOptions;
  using R = RenderOptions;
  static const FieldList<O> kList = [] {
    FieldList<O> list = {
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
    };
    list.Nest("", &O::render, RenderOptionFields(), {"samples_per_pixel"});
    list.Add(Bind(&O::render, &R::seed,
                  {.name = "seed",
                   .description = "Sampling and camera-effect seed; same seed → identical images.",
                   .minimum = 0.0,
                   .maximum = 4294967295.0}));
    list.Nest("", &O::render, RenderOptionFields(),
              {"camera_effects", "id_drift", "denoise_passes", "indirect_light", "normals", "instance_ids"});
    return list;
  }();
  return kList;
}

}  // namespace asbuilt
