// `asbuilt scene <text|random|truth|describe|export-blender|schema>` — make,
// inspect and convert scenes (scene/).

#include <cstdio>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/cli/field_flags.h"
#include "asbuilt/formats/plan_file.h"
#include "asbuilt/scene/blender_export.h"
#include "asbuilt/scene/llm.h"
#include "asbuilt/scene/procedural.h"
#include "asbuilt/scene/procedural_home.h"
#include "asbuilt/scene/scene_json.h"
#include "asbuilt/scene/scene_text.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {
namespace fs = std::filesystem;

int RunSceneCommand(int argc, char** argv) {
  CLI::App app(
      "Make, inspect and convert scenes (docs/scene.md).\n"
      "  text            description → scene.json (built-in parser, or --llm URL)\n"
      "  random          procedural rooms → DIR/scene_NNNN.json\n"
      "  truth           scene.json → truth.json (the exact floor plan)\n"
      "  describe        one-paragraph summary of a scene\n"
      "  export-blender  scene.json → Blender Python script (Cycles stereo renders)\n"
      "  schema          the scene file's JSON Schema",
      "asbuilt scene");
  AddCommonFlags(app);
  app.require_subcommand(1);

  // text
  CLI::App* text_cmd = app.add_subcommand("text", "description → scene.json");
  std::string text, text_out;
  LlmOptions llm_options;
  std::string llm_url;
  text_cmd->add_option("description", text, "the room in words, e.g. \"a 6 by 8 m classroom, 3 m high, ...\"")
      ->required();
  text_cmd->add_option("-o,--output", text_out, "scene file to write")->required();
  FieldFlags text_flags(*text_cmd, SceneTextOptionFields().Fields(),  // = MCP scene_from_text.
                        {{"furnish", "!--no-furniture"},
                         {"add_door_if_none", "!--no-default-door"},
                         {"rig_height_m", "--rig-height"},
                         {"turn_step_deg", "--step"}});
  text_cmd->add_option("--llm", llm_url,
                       "OpenAI-compatible base URL (e.g. http://localhost:8080/v1); key from ASBUILT_LLM_API_KEY");
  text_cmd->add_option("--llm-model", llm_options.model, "model name sent to the endpoint")->capture_default_str();
  text_cmd->add_option("--llm-rounds", llm_options.max_repair_rounds, "repair rounds after the first answer")
      ->capture_default_str();
  text_cmd->add_option("--llm-timeout", llm_options.timeout_s, "seconds per request")->capture_default_str();

  // random
  CLI::App* random_cmd = app.add_subcommand("random", "procedural rooms → DIR/scene_NNNN.json");
  int count = 1;
  std::string random_out;
  random_cmd->add_option("--count", count, "number of scenes; scene i uses seed + i")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  random_cmd->add_option("-o,--output", random_out, "output folder")->required();
  std::vector<Field> random_fields = RandomSceneOptionFields().Fields();  // = MCP random_scene.
  random_fields.insert(random_fields.begin(), RandomSceneSeedField());
  FieldFlags random_flags(*random_cmd, std::move(random_fields),
                          {{"min_side_m", "--min-side"}, {"max_side_m", "--max-side"}, {"turn_step_deg", "--step"}});

  // home
  CLI::App* home_cmd = app.add_subcommand("home", "a procedural home of several rooms joined by doors → scene.json");
  std::uint64_t home_seed = 1;
  int home_rooms = 0;
  std::string home_out;
  home_cmd->add_option("-o,--output", home_out, "scene file to write")->required();
  home_cmd->add_option("--seed", home_seed, "random seed")->capture_default_str();
  home_cmd->add_option("--rooms", home_rooms, "number of rooms (0: 5 to 10)")->check(CLI::Range(0, 100));

  // truth / describe / export-blender / schema
  CLI::App* truth_cmd = app.add_subcommand("truth", "scene.json → truth.json (exact floor plan)");
  std::string scene_path, truth_out;
  truth_cmd->add_option("scene", scene_path, "scene file")->required();
  truth_cmd->add_option("-o,--output", truth_out, "plan file to write")->required();

  CLI::App* describe_cmd = app.add_subcommand("describe", "summary of a scene");
  describe_cmd->add_option("scene", scene_path, "scene file")->required();

  CLI::App* blender_cmd = app.add_subcommand("export-blender", "scene.json → Blender Python script");
  std::string blender_out;
  BlenderExportOptions blender_options;
  blender_cmd->add_option("scene", scene_path, "scene file")->required();
  blender_cmd->add_option("-o,--output", blender_out, "script to write (build.py)")->required();
  blender_cmd->add_option("--samples", blender_options.samples, "Cycles samples per pixel")->capture_default_str();
  blender_cmd->add_flag("!--no-denoise", blender_options.denoise, "turn Cycles denoising off");
  blender_cmd
      ->add_option("--panorama", blender_options.panorama_width_px,
                   "render one 360° equirectangular frame WIDTH x WIDTH/2 from the rig's spot instead of the stereo "
                   "pairs (the photo of a panorama capture)")
      ->capture_default_str();
  blender_cmd->add_flag("--labels-pass", blender_options.labels_pass,
                        "the label pass: 1 sample at each pixel's centre, no bounces; use its OUT/index/*.exr");

  CLI::App* schema_cmd = app.add_subcommand("schema", "print (or write) the scene JSON Schema");
  std::string schema_out;
  schema_cmd->add_option("-o,--output", schema_out, "file to write instead of stdout");

  Parse(app, argc, argv);

  if (text_cmd->parsed()) {
    SceneTextResult result;
    if (!llm_url.empty()) {
      llm_options.base_url = llm_url;
      LlmSceneSummary summary;
      result.scene = SceneFromLlm(text, llm_options, &summary);
      spdlog::info("{}", summary.BriefReport());
    } else {
      result = SceneFromText(text, SceneTextOptionFields().FromArgs(text_flags.Args()));
      for (const std::string& a : result.assumptions) spdlog::info("assumed: {}", a);
    }
    WriteScene(result.scene, text_out);
    fmt::print("{}: {}\n", text_out, llm_url.empty() ? result.BriefReport() : result.scene.ToString());
    return 0;
  }
  if (random_cmd->parsed()) {
    FieldArgs args = random_flags.Args();
    ProgressPrinter printer;
    RandomScenesSummary summary =
        WriteRandomScenes(RandomSceneOptionFields().FromArgs(args), static_cast<std::uint64_t>(args.Integer("seed")),
                          count, random_out, StderrIsTerminal() ? printer.Callback() : ProgressCallback{});
    printer.Finish();
    fmt::print("{}\n", summary.BriefReport());
    return 0;
  }
  if (home_cmd->parsed()) {
    HomeLayoutOptions layout;
    if (home_rooms > 0) layout.min_rooms = layout.max_rooms = home_rooms;
    SceneRng rng(home_seed);
    const Scene scene = HomeScene(MakeHomeLayout(rng, layout), home_seed);
    WriteScene(scene, home_out);
    fmt::print("{} rooms → {} (render it with `asbuilt render {} -o DIR --home`)\n", scene.rooms.size(), home_out,
               home_out);
    return 0;
  }
  if (truth_cmd->parsed()) {
    Plan plan = SceneTruth(ReadScene(scene_path));
    WritePlan(plan, truth_out);
    fmt::print("{}: {}\n", truth_out, plan.ToString());
    return 0;
  }
  if (describe_cmd->parsed()) {
    fmt::print("{}\n", DescribeScene(ReadScene(scene_path)));
    return 0;
  }
  if (blender_cmd->parsed()) {
    Scene scene = ReadScene(scene_path);
    BlenderExportSummary summary = WriteBlenderScript(scene, blender_options, blender_out);
    fmt::print("{}: {}\n", blender_out, summary.BriefReport());
    return 0;
  }
  if (schema_cmd->parsed()) {
    std::string json = SceneJsonSchema().dump(2) + "\n";
    if (schema_out.empty()) {
      fmt::print("{}", json);
    } else {
      WriteFileAtomic(schema_out, json);
      fmt::print("{}: scene JSON Schema\n", schema_out);
    }
    return 0;
  }
  return 2;
}

}  // namespace asbuilt::cli
