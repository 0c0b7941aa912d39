// `asbuilt demo [-o DIR]` — the whole method on a built-in classroom.

#include <string>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/pipeline/demo.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {

int RunDemoCommand(int argc, char** argv) {
  CLI::App app(
      "Run the whole method on a built-in example: a sentence becomes a classroom scene, asbuilt\n"
      "renders a turn-in-place stereo capture of it, surveys it with the shipped segmentation model\n"
      "and prints measured against true sizes. Needs no data, GPU or network.",
      "asbuilt demo");
  AddCommonFlags(app);
  std::string out_dir = "asbuilt-demo", model, sentence;
  DemoOptions options;
  app.add_option("-o,--out", out_dir, "output folder")->capture_default_str();
  app.add_option("--text", options.sentence, "the room description")->capture_default_str();
  app.add_option("--views", options.views, "turn-in-place views")->capture_default_str();
  app.add_option("--spp", options.samples_per_pixel, "renderer samples per pixel")->capture_default_str();
  app.add_option("--model", model,
                 "segmentation model: a shipped model's name (default, renders, real), a checkpoint or a .tflite file");
  app.add_flag("--capture-labels", options.survey.use_capture_labels,
               "survey with the rendered exact labels instead of the segmenter (upper bound)");
  Parse(app, argc, argv);
  if (!model.empty()) options.survey.model_path = ModelPathFor(model);
  options.Check();

  fmt::print("asbuilt demo: \"{}\"\n", options.sentence);
  ProgressPrinter printer;
  DemoSummary summary = RunDemo(out_dir, options, printer.Callback());
  printer.Finish();
  fmt::print("\nscene:  {}\nrender: {} views in {:.1f} s\nsurvey: {}\n\n", summary.scene_brief, options.views,
             summary.render_seconds, summary.survey.labels_source);
  if (!summary.comparison.empty()) fmt::print("{}\n", summary.comparison);
  for (const std::string& n : summary.survey.notes) fmt::print("note: {}\n", n);
  fmt::print("{}\nverdict: {}\nreport: {}\n", summary.survey.BriefReport(), summary.survey.verdict.BriefReport(),
             (summary.out_dir / "survey" / "report.html").string());
  return 0;
}

}  // namespace asbuilt::cli
