// `asbuilt scene <text|random|truth|describe|export-blender|schema>` — make,
// inspect and convert scenes (scene/).

#include <cstdio>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/formats/plan_file.h"
#include "asbuilt/scene/blender_export.h"
#include "asbuilt/scene/llm.h"
#include "asbuilt/scene/procedural.h"
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
  SceneTextOptions text_options;
  LlmOptions llm_options;
  std::string llm_url;
  text_cmd->add_option("description", text, "the room in words, e.g. \"a 6 by 8 m classroom, 3 m high, ...\"")
      ->required();
  text_cmd->add_option("-o,--output", text_out, "scene file to write")->required();
  text_cmd->add_option("--seed", text_options.seed, "furniture placement seed")->capture_default_str();
  text_cmd->add_option("--rig-height", text_options.rig_height_m, "default rig height, m")->capture_default_str();
  text_cmd->add_option("--step", text_options.turn_step_deg, "default turn step, degrees")->capture_default_str();
  text_cmd->add_flag("!--no-furniture", text_options.furnish, "do not add the room kind's usual furniture");
  text_cmd->add_flag("!--no-default-door", text_options.add_door_if_none, "do not add a door when none is named");
  text_cmd->add_option("--llm", llm_url,
                       "OpenAI-compatible base URL (e.g. http://localhost:8080/v1); key from ASBUILT_LLM_API_KEY");
  text_cmd->add_option("--llm-model", llm_options.model, "model name sent to the endpoint")->capture_default_str();
  text_cmd->add_option("--llm-rounds", llm_options.max_repair_rounds, "repair rounds after the first answer")
      ->capture_default_str();
  text_cmd->add_option("--llm-timeout", llm_options.timeout_s, "seconds per request")->capture_default_str();

  // random
  CLI::App* random_cmd = app.add_subcommand("random", "procedural rooms → DIR/scene_NNNN.json");
  RandomSceneOptions random_options;
  std::uint64_t seed = 0;
  int count = 1;
  std::string random_out;
  random_cmd->add_option("--seed", seed, "first seed; scene i uses seed + i")->capture_default_str();
  random_cmd->add_option("--count", count, "number of scenes")->capture_default_str()->check(CLI::PositiveNumber);
  random_cmd->add_option("-o,--output", random_out, "output folder")->required();
  random_cmd->add_option("--min-side", random_options.min_side_m, "smallest room side, m")->capture_default_str();
  random_cmd->add_option("--max-side", random_options.max_side_m, "largest room side, m")->capture_default_str();
  random_cmd->add_option("--l-shape-probability", random_options.l_shape_probability, "share of L-shaped rooms")
      ->capture_default_str();
  random_cmd->add_option("--rotated-probability", random_options.rotated_probability, "share of rotated rooms")
      ->capture_default_str();
  random_cmd->add_option("--max-openings", random_options.max_openings, "most doors + windows per room")
      ->capture_default_str();
  random_cmd->add_option("--step", random_options.turn_step_deg, "rig turn step, degrees")->capture_default_str();

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
      result = SceneFromText(text, text_options);
      for (const std::string& a : result.assumptions) spdlog::info("assumed: {}", a);
    }
    WriteScene(result.scene, text_out);
    fmt::print("{}: {}\n", text_out, llm_url.empty() ? result.BriefReport() : result.scene.ToString());
    return 0;
  }
  if (random_cmd->parsed()) {
    ProgressPrinter printer;
    RandomScenesSummary summary =
        WriteRandomScenes(random_options, seed, count, random_out,
                          StderrIsTerminal() ? printer.Callback() : ProgressCallback{});
    printer.Finish();
    fmt::print("{}\n", summary.BriefReport());
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
