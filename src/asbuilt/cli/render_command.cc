// `asbuilt render SCENE -o DIR` — renders a scene's stereo views into a
// synthetic capture (left/right RGB, labels, ID map, depth, capture.json,
// truth.json; render/capture_render.h).

#include <cstdio>
#include <string>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/render/capture_render.h"
#include "asbuilt/scene/scene_json.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {

int RunRenderCommand(int argc, char** argv) {
  CLI::App app(
      "Render a scene's stereo views into a capture: left/ right/ labels/ idmap/ depth/ (NNN.png),\n"
      "capture.json and truth.json. Views come from the scene (viewpoints, turn) unless --views or\n"
      "--step-deg asks for a turn-in-place. Finished views are skipped when re-run.",
      "asbuilt render");
  AddCommonFlags(app);
  std::string scene_path, out_dir, size;
  CaptureRenderOptions options;
  bool no_resume = false, no_indirect = false;
  app.add_option("scene", scene_path, "scene JSON file")->required();
  app.add_option("-o,--out", out_dir, "output folder")->required();
  app.add_option("--views", options.views, "turn-in-place with N views (replaces the scene's views)");
  app.add_option("--step-deg", options.step_deg, "turn step in degrees (default 360/N)");
  app.add_option("--size", size, "image size WxH (default: the scene rig's)");
  app.add_option("--fov-deg", options.fov_deg, "horizontal field of view (default: the scene rig's)");
  app.add_option("--baseline-m", options.baseline_m, "stereo baseline (default: the scene rig's)");
  app.add_option("--spp", options.render.samples_per_pixel, "RGB samples per pixel")->capture_default_str();
  app.add_option("--seed", options.render.seed, "sampling and camera-effect seed")->capture_default_str();
  app.add_option("--effects", options.render.camera_effects,
                 "camera effects strength in [0, 1] (exposure, white balance, noise, blur, JPEG)")
      ->capture_default_str();
  app.add_option("--id-drift", options.render.id_drift, "ID-map colour drift with the light, [0, 1]")
      ->capture_default_str();
  app.add_flag("--normals", options.render.normals, "also write normals/ (camera frame)");
  app.add_flag("--instances", options.render.instance_ids, "also write instances/ (uint16 object ids)");
  app.add_flag("--no-indirect", no_indirect, "direct light only (faster)");
  app.add_flag("--no-resume", no_resume, "re-render views that already exist");
  Parse(app, argc, argv);

  if (!size.empty()) {
    if (std::sscanf(size.c_str(), "%dx%d", &options.width_px, &options.height_px) != 2 || options.width_px <= 0 ||
        options.height_px <= 0) {
      throw CLI::ValidationError("--size", fmt::format("'{}' is not WxH (e.g. 640x480)", size));
    }
  }
  options.resume = !no_resume;
  options.render.indirect_light = !no_indirect;
  options.Check();

  Scene scene = ReadScene(scene_path);
  ProgressPrinter printer;
  CaptureRenderSummary summary = RenderCapture(scene, out_dir, options, printer.Callback());
  printer.Finish();
  fmt::print("{}\n", summary.BriefReport());
  return 0;
}

}  // namespace asbuilt::cli
