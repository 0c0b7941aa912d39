// `asbuilt model <what> …` — segmenter model files (seg/model_file.h):
//   model info M                         what a checkpoint holds
//   model export M.pt -o W.safetensors   weights + metadata for PyTorch users
//   model import W.safetensors -o M.pt   back from PyTorch (tools/pytorch/)

#include <string>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/seg/model_file.h"
#include "asbuilt/seg/segmenter.h"

namespace asbuilt::cli {
namespace {

std::string Describe(const SegmenterInfo& info) {
  const nlohmann::json& m = info.metadata;
  std::string out = info.ToString();
  if (info.config.arch != "tflite") {
    out += "\n  " + info.config.ToString();
  } else if (m.contains("config") && m["config"].contains("graph")) {
    const nlohmann::json& graph = m["config"]["graph"];
    out += fmt::format("\n  tflite: {} operators, {} ({})", graph.at("operators").size(),
                       graph.value("description", std::string("no description")),
                       m["config"].value("class_map", std::string()));
  }
  if (m.contains("best_miou") && m["best_miou"].is_number()) {
    out += fmt::format("\n  best validation mIoU {:.4f} (epoch {})", m["best_miou"].get<double>(),
                       m.value("best_epoch", 0));
  }
  if (m.contains("trainer") && m["trainer"].is_string()) out += "\n  trained by " + m["trainer"].get<std::string>();
  return out;
}

}  // namespace

int RunModelCommand(int argc, char** argv) {
  CLI::App app("Segmenter model files: inspect, move weights to and from PyTorch (safetensors), average.",
               "asbuilt model");
  AddCommonFlags(app);
  app.require_subcommand(1);

  CLI::App* info_cmd = app.add_subcommand("info", "print what a checkpoint holds: architecture, size, training");
  std::string info_path;
  bool info_json = false;
  info_cmd->add_option("model", info_path, "checkpoint (.pt)")->required();
  info_cmd->add_flag("--json", info_json, "print the whole metadata as JSON");

  CLI::App* export_cmd = app.add_subcommand("export",
                                            "write a checkpoint's weights and metadata as safetensors, for PyTorch\n"
                                            "(tools/pytorch/asbuilt_segformer.py loads it into the same network)");
  std::string export_in, export_out;
  export_cmd->add_option("model", export_in, "checkpoint (.pt)")->required();
  export_cmd->add_option("-o,--out", export_out, "output .safetensors")->required();

  CLI::App* import_cmd =
      app.add_subcommand("import",
                         "make a checkpoint from safetensors written by `model export` or tools/pytorch/\n"
                         "(every tensor of the configured model, with its shape; metadata key asbuilt_meta)");
  std::string import_in, import_out;
  import_cmd->add_option("weights", import_in, "input .safetensors")->required();
  import_cmd->add_option("-o,--out", import_out, "output checkpoint (.pt)")->required();

  CLI::App* average_cmd = app.add_subcommand(
      "average",
      "the weighted mean of checkpoints of one network, weight by weight (a model soup: fine-tunes of one\n"
      "model along different data or schedules)");
  std::vector<std::string> average_in;
  std::vector<double> average_weights;
  std::string average_out;
  average_cmd->add_option("models", average_in, "two or more checkpoints of one network")->required();
  average_cmd->add_option("--weights", average_weights, "one per checkpoint, summing to 1 (default: equal)")
      ->delimiter(',');
  average_cmd->add_option("-o,--out", average_out, "output checkpoint (.pt)")->required();

  Parse(app, argc, argv);

  if (info_cmd->parsed()) {
    SegmenterInfo info = ReadSegmenterInfo(info_path);
    fmt::print("{}\n", info_json ? info.metadata.dump(2) : Describe(info));
  } else if (export_cmd->parsed()) {
    SegmenterInfo info = ExportModel(export_in, export_out);
    fmt::print("{}\nwrote {}\n", Describe(info), export_out);
  } else if (average_cmd->parsed()) {
    const std::vector<std::filesystem::path> models(average_in.begin(), average_in.end());
    SegmenterInfo info = AverageModels(models, average_weights, average_out);
    fmt::print("{}\nwrote {}\n", Describe(info), average_out);
  } else if (import_cmd->parsed()) {
    SegmenterInfo info = ImportModel(import_in, import_out);
    fmt::print("{}\nwrote {}\n", Describe(info), import_out);
  }
  return 0;
}

}  // namespace asbuilt::cli
