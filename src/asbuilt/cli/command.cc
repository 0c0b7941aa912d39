#include "asbuilt/cli/command.h"

#include <glob.h>

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

#include "asbuilt/util/log.h"

namespace asbuilt::cli {

std::span<const Command> Commands() {
  static const Command kCommands[] = {
      {"help", "list the commands, or show one command's help", &RunHelpCommand},
      {"survey", "the main job: stereo capture → dimensioned floor plan (SVG, DXF, PDF, JSON, IFC) + report.html",
       &RunSurveyCommand},
      {"demo", "the whole method on a built-in classroom: text → scene → render → survey → measured vs true",
       &RunDemoCommand},
      {"validate", "check asbuilt files (capture, plan/truth, scene, manifest) and report every problem",
       &RunValidateCommand},
      {"plan", "floor plan from labelled points: walls, openings, dimensions → JSON, SVG, DXF, PDF, PNG",
       &RunPlanCommand},
      {"eval",
       "score results against the truth (eval plan: a floor plan vs truth.json; eval seg: a segmenter; "
       "eval zind: a segmenter on real photos)",
       &RunEvalCommand},
      {"scene",
       "scenes from words or at random: text (built-in parser or --llm URL), random, truth, describe, "
       "export-blender, schema",
       &RunSceneCommand},
      {"render", "render a scene's stereo views into a capture (RGB, labels, ID map, depth, truth)", &RunRenderCommand},
      {"calibrate", "stereo calibration from chessboard pairs → OpenCV YAML (K1 D1 K2 D2 R T, rms)",
       &RunCalibrateCommand},
      {"rectify", "rectify stereo pairs with a calibration (maps computed once)", &RunRectifyCommand},
      {"disparity", "dense disparity of a rectified pair → float PFM + colour picture", &RunDisparityCommand},
      {"points", "world points by class (wall/door/window) from a capture and its labels → points.txt, PLY",
       &RunPointsCommand},
      {"review", "check and correct a survey in the browser: drag corners, set the ceiling, openings; re-fit per edit",
       &RunReviewCommand},
      {"mcp", "MCP server on stdio: scene-building and rendering tools for LLM agents (Claude Desktop)",
       &RunMcpCommand},
      {"labels", "ID maps → label maps (calibrate, convert), real annotations in (ADE20K, NYUv2, LabelMe), compare",
       &RunLabelsCommand},
      {"dataset",
       "training sets: synthetic items (synth, merge, verify), real/synthetic mixes → manifest.json (mix), pair "
       "checks (check)",
       &RunDatasetCommand},
      {"cluster", "sharded work on Slurm: a dataset rendered by an array job and merged (synth), shard states (status)",
       &RunClusterCommand},
      {"train", "train the SegFormer segmenter (walls, doors, windows): checkpoints, resume, logs, plot",
       &RunTrainCommand},
      {"segment", "label images with a trained segmenter → label PNGs (+ colour overlays)", &RunSegmentCommand},
      {"experiment", "segmentation experiments: real/synthetic ratios (the paper's table + plot), toy rooms",
       &RunExperimentCommand},
      {"learn",
       "learn from corrections: reviewed surveys + renders → fine-tuned model, kept only if better on held-out rooms",
       &RunLearnCommand},
      {"model", "segmenter model files: info, export to / import from PyTorch (safetensors)", &RunModelCommand},
      {"pano", "equirectangular panoramas → turn-in-place perspective views (+ ZInD layout labels, truth plan)",
       &RunPanoCommand},
      {"version", "print the version", &RunVersionCommand},
  };
  return kCommands;
}

const Command* FindCommand(std::string_view name) {
  for (const Command& c : Commands()) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

void AddCommonFlags(CLI::App& app) {
  app.add_flag_callback(
      "-q,--quiet", [] { ConfigureLogging(Verbosity::kQuiet); }, "only print errors");
  app.add_flag_callback(
      "-v,--verbose", [] { ConfigureLogging(Verbosity::kVerbose); }, "print debug messages");
}

std::unique_ptr<FieldFlags> AddTurnInPlaceFlags(CLI::App& app, const TurnInPlaceOptions& defaults,
                                                std::string_view group) {
  // The --pano-* spellings are `survey`'s for the same four.
  auto flags = std::make_unique<FieldFlags>(app, TurnInPlaceOptionFields().Fields(defaults),
                                            std::vector<FlagAlias>{{"fx", "--pano-fx"},
                                                                   {"views", "--pano-views"},
                                                                   {"yaw_step_deg", "--yaw-step,--pano-yaw-step"},
                                                                   {"first_yaw_deg", "--first-yaw"},
                                                                   {"pitch_deg", "--pitch"}},
                                            group);
  flags->AddSize("width_px", "height_px", "--size,--pano-size", "view size");
  return flags;
}

std::unique_ptr<FieldFlags> AddSegmentFlags(CLI::App& app, const SegmentOptions& defaults, std::string_view scale_names,
                                            bool with_batch) {
  std::vector<Field> fields;
  for (Field& f : SegmentOptionFields().Fields(defaults)) {
    if (with_batch || f.name != "batch_size") fields.push_back(std::move(f));
  }
  std::vector<FlagAlias> aliases;
  if (with_batch) aliases.push_back({"batch_size", "--batch"});
  auto flags = std::make_unique<FieldFlags>(app, std::move(fields), std::move(aliases));
  flags->AddSize("scale_width_px", "scale_height_px", scale_names, "inference scale");
  return flags;
}

void ParseSizeFlag(const std::string& text, const std::string& flag, int& w, int& h) {
  if (text.empty()) return;
  int a = 0, b = 0;
  char x = 0;
  if (std::sscanf(text.c_str(), "%d%c%d", &a, &x, &b) != 3 || (x != 'x' && x != 'X') || a <= 0 || b <= 0) {
    throw CLI::ValidationError(flag, fmt::format("expected WIDTHxHEIGHT (e.g. 256x192), got '{}'", text));
  }
  w = a;
  h = b;
}

std::vector<std::filesystem::path> ExpandFileArgs(const std::vector<std::string>& args, const std::string& flag) {
  std::vector<std::filesystem::path> out;
  for (const std::string& a : args) {
    if (a.find_first_of("*?[") == std::string::npos) {
      out.emplace_back(a);
      continue;
    }
    glob_t g{};
    const int rc = ::glob(a.c_str(), 0, nullptr, &g);
    if (rc == 0) {
      for (std::size_t i = 0; i < g.gl_pathc; ++i) out.emplace_back(g.gl_pathv[i]);
    }
    ::globfree(&g);
    if (rc != 0) throw CLI::ValidationError(flag, fmt::format("no files match '{}'", a));
  }
  std::sort(out.begin(), out.end());
  return out;
}

void Parse(CLI::App& app, int argc, char** argv) {
  // CLI11 skips argv[0]; ours is the command name.
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    throw HelpPrinted{};
  } catch (const CLI::CallForAllHelp&) {
    std::fputs(app.help("", CLI::AppFormatMode::All).c_str(), stdout);
    throw HelpPrinted{};
  }
}

}  // namespace asbuilt::cli
