// `asbuilt render SCENE -o DIR` — renders a scene's stereo views into a
// synthetic capture (left/right RGB, labels, ID map, depth, capture.json,
// truth.json; render/capture_render.h).

#include <cstdio>
#include <string>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/cli/field_flags.h"
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
  bool no_resume = false;
  app.add_option("scene", scene_path, "scene JSON file")->required();
  app.add_option("-o,--out", out_dir, "output folder")->required();
  app.add_option("--size", size, "image size WxH, short for --width-px W --height-px H");
  app.add_flag("--no-resume", no_resume, "re-render views that already exist");
  CaptureRenderOptions options;
  FieldFlags flags(app, CaptureRenderOptionFields().Fields(options),  // = MCP render_capture.
                   {{"samples_per_pixel", "--spp"}, {"camera_effects", "--effects"},
                    {"indirect_light", "!--no-indirect"}, {"instance_ids", "--instances"}});
  Parse(app, argc, argv);

  flags.Read(CaptureRenderOptionFields(), options);
  if (!size.empty()) {
    if (std::sscanf(size.c_str(), "%dx%d", &options.width_px, &options.height_px) != 2 || options.width_px <= 0 ||
        options.height_px <= 0) {
      throw CLI::ValidationError("--size", fmt::format("'{}' is not WxH (e.g. 640x480)", size));
    }
  }
  options.resume = !no_resume;
  options.Check();

  Scene scene = ReadScene(scene_path);
  ProgressPrinter printer;
  CaptureRenderSummary summary = RenderCapture(scene, out_dir, options, printer.Callback());
  printer.Finish();
  fmt::print("{}\n", summary.BriefReport());
  return 0;
}

}  // namespace asbuilt::cli
