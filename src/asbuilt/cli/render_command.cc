// `asbuilt render SCENE -o DIR` — renders a scene's stereo views into a
// synthetic capture (left/right RGB, labels, ID map, depth, capture.json,
// truth.json; render/capture_render.h).

#include <string>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/cli/field_flags.h"
#include "asbuilt/render/capture_render.h"
#include "asbuilt/render/home_render.h"
#include "asbuilt/scene/scene_json.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {

int RunRenderCommand(int argc, char** argv) {
  CLI::App app(
      "Render a scene's stereo views into a capture: left/ right/ labels/ idmap/ depth/ (NNN.png),\n"
      "capture.json and truth.json. Views come from the scene (viewpoints, turn) unless --views or\n"
      "--step-deg asks for a turn-in-place. Finished views are skipped when re-run.\n"
      "--home: a scene of several rooms (asbuilt scene home) as a surveyor captures a home: a turn in\n"
      "place in each room (--views, default 12), each room's capture in a frame of its own, and\n"
      "OUT/home.json for `asbuilt survey` (docs/home.md).",
      "asbuilt render");
  AddCommonFlags(app);
  std::string scene_path, out_dir;
  bool no_resume = false;
  app.add_option("scene", scene_path, "scene JSON file")->required();
  app.add_option("-o,--out", out_dir, "output folder")->required();
  app.add_flag("--no-resume", no_resume, "re-render views that already exist");
  bool home = false;
  app.add_flag("--home", home, "one capture per room, each in its own frame, and OUT/home.json");
  CaptureRenderOptions options;
  FieldFlags flags(app, CaptureRenderOptionFields().Fields(options),  // = MCP render_capture.
                   {{"samples_per_pixel", "--spp"},
                    {"camera_effects", "--effects"},
                    {"indirect_light", "!--no-indirect"},
                    {"instance_ids", "--instances"}});
  flags.AddSize("width_px", "height_px", "--size", "image size");
  Parse(app, argc, argv);

  flags.Read(CaptureRenderOptionFields(), options);
  options.resume = !no_resume;
  options.Check();

  Scene scene = ReadScene(scene_path);
  ProgressPrinter printer;
  if (home) {
    HomeRenderOptions home_options;
    home_options.capture = options;
    if (home_options.capture.views == 0) home_options.capture.views = 12;
    const HomeRenderSummary summary = RenderHome(scene, out_dir, home_options, printer.Callback());
    printer.Finish();
    fmt::print("{} rooms rendered in {:.0f} s → {}\n", summary.rooms.size(), summary.seconds,
               summary.home_json.string());
    return 0;
  }
  CaptureRenderSummary summary = RenderCapture(scene, out_dir, options, printer.Callback());
  printer.Finish();
  fmt::print("{}\n", summary.BriefReport());
  return 0;
}

}  // namespace asbuilt::cli
