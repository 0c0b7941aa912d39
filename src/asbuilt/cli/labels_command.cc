// `asbuilt labels <calibrate|convert|import|compare>` — ID maps → label maps
// (PAPER.md §3.3–3.4) and real annotations in (labels/, docs/labels.md).

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/dataset/pairs.h"
#include "asbuilt/labels/agreement.h"
#include "asbuilt/labels/calibrate.h"
#include "asbuilt/labels/convert.h"
#include "asbuilt/labels/import.h"
#include "asbuilt/labels/label_io.h"
#include "asbuilt/labels/palette.h"
#include "asbuilt/util/progress.h"
#include "asbuilt/util/text.h"

namespace asbuilt::cli {
namespace {
namespace fs = std::filesystem;

// Inputs given as folders and/or files → files (folders listed with `list`).
template <typename ListFn>
std::vector<fs::path> ExpandInputs(const std::vector<std::string>& inputs, ListFn list) {
  std::vector<fs::path> out;
  for (const std::string& in : inputs) {
    std::error_code ec;
    if (fs::is_directory(in, ec)) {
      std::vector<fs::path> found = list(fs::path(in));
      if (found.empty()) throw InputError(in, "", "no input files in this folder");
      for (fs::path& p : found) out.push_back(std::move(p));
    } else {
      out.emplace_back(in);  // A missing file is reported by the batch, by name.
    }
  }
  return out;
}

int ReportFailures(const std::vector<Problem>& failed) {
  for (const Problem& p : failed) fmt::print(stderr, "{}\n", p.ToString());
  return failed.empty() ? 0 : 1;
}

int Calibrate(const std::string& idmaps_dir, const std::string& masks_dir, const std::string& out,
              const PaletteCalibrateOptions& options) {
  std::vector<fs::path> idmaps, masks;
  if (masks_dir.empty()) {
    idmaps = ListImageFiles(idmaps_dir);
  } else {
    PairListing pairs = ListPairs(idmaps_dir, masks_dir);
    for (const fs::path& p : pairs.images_without_label) spdlog::warn("calibrate: no mask for {}", p.string());
    for (const ImagePair& p : pairs.pairs) {
      idmaps.push_back(p.image);
      masks.push_back(p.label);
    }
  }
  if (idmaps.empty()) throw InputError(idmaps_dir, "", "no ID maps found");
  ProgressPrinter printer;
  CalibrateSummary summary = CalibrateFiles(options, idmaps, masks, printer.Callback());
  printer.Finish();
  WritePalette(summary.palette, out);
  fmt::print("{}\n", summary.BriefReport());
  if (summary.palette.threshold) fmt::print("suggested threshold {:.1f}\n", *summary.palette.threshold);
  fmt::print("wrote {}\n", out);
  return ReportFailures(summary.failed);
}

int Compare(const std::string& predicted_dir, const std::string& exact_dir, const AgreementOptions& options) {
  PairListing pairs = ListPairs(predicted_dir, exact_dir);
  for (const fs::path& p : pairs.images_without_label) spdlog::warn("compare: no exact labels for {}", p.string());
  LabelAgreement total;
  std::vector<Problem> failed;
  for (const ImagePair& p : pairs.pairs) {
    try {
      cv::Mat predicted = ReadLabelImage(p.image), exact = ReadLabelImage(p.label);
      if (predicted.size() != exact.size()) {
        throw InputError(p.image.string(), "",
                         fmt::format("{}x{} but the exact labels are {}x{}", predicted.cols, predicted.rows, exact.cols,
                                     exact.rows));
      }
      total.Add(CompareLabels(predicted, exact, options));
    } catch (const InputError& e) {
      failed.push_back(e.problems().front());
    }
  }
  fmt::print("{} label maps: {}\n", pairs.pairs.size() - failed.size(), total.ToString());
  static const char* kNames[] = {"background", "wall", "door", "window", "other"};
  fmt::print("confusion (rows exact, columns predicted, pixels):\n{:>11}", "");
  for (const char* n : kNames) fmt::print(" {:>11}", n);
  fmt::print("\n");
  for (int i = 0; i < 5; ++i) {
    fmt::print("{:>11}", kNames[i]);
    for (int j = 0; j < 5; ++j) fmt::print(" {:>11}", total.confusion[i][j]);
    fmt::print("\n");
  }
  return ReportFailures(failed);
}

}  // namespace

int RunLabelsCommand(int argc, char** argv) {
  CLI::App app(
      "ID maps → label maps, and real annotations in (docs/labels.md).\n"
      "  calibrate  measure each class's ID-map colour → palette.json (with exact masks, or k-means)\n"
      "  convert    ID maps → single-channel label PNGs (nearest palette colour, threshold → background)\n"
      "  import     ADE20K / NYUv2-40 / LabelMe / colour-palette annotations → label PNGs\n"
      "  compare    pixel agreement of label maps with exact ones (overall, boundary band, confusion)",
      "asbuilt labels");
  AddCommonFlags(app);
  app.require_subcommand(1);

  // calibrate
  CLI::App* cal = app.add_subcommand("calibrate", "ID maps (+ exact masks) → palette.json");
  std::string cal_idmaps, cal_masks, cal_out;
  PaletteCalibrateOptions cal_options;
  cal->add_option("--idmaps", cal_idmaps, "folder of ID maps")->required();
  cal->add_option("--masks", cal_masks,
                  "folder of exact label maps with the same file names (ids 0-3); without: k-means");
  cal->add_option("-o,--output", cal_out, "palette file to write")->required();
  cal->add_option("--edge-margin", cal_options.edge_margin_px, "skip mask pixels this close to another class (px)")
      ->capture_default_str();
  cal->add_option("--kmeans-radius", cal_options.kmeans_radius, "k-means capture radius (RGB distance)")
      ->capture_default_str();
  cal->add_option("--seed", cal_options.seed, "k-means sampling seed")->capture_default_str();
  cal->add_option("--threads", cal_options.num_threads, "worker threads (0 = all cores)")->capture_default_str();

  // convert
  CLI::App* conv = app.add_subcommand("convert", "ID maps → label PNGs");
  std::vector<std::string> conv_inputs;
  std::string conv_palette, conv_out;
  std::optional<double> conv_threshold;
  ConvertOptions conv_options;
  conv->add_option("idmaps", conv_inputs, "ID map files or folders")->required();
  conv->add_option("--palette", conv_palette, "palette.json (default: the renderer's nominal colours)");
  conv->add_option("--threshold", conv_threshold,
                   fmt::format("RGB distance beyond which a pixel is background (default: the palette's suggested "
                               "threshold, else {})",
                               conv_options.threshold));
  conv->add_option("-o,--output", conv_out, "output folder (same file names, .png)")->required();
  conv->add_option("--threads", conv_options.num_threads, "worker threads (0 = all cores)")->capture_default_str();

  // import
  CLI::App* imp = app.add_subcommand("import", "annotations → label PNGs");
  std::vector<std::string> imp_inputs;
  std::string imp_format, imp_out, imp_palette, imp_unlabeled = "ignore";
  std::vector<std::string> imp_names;
  ImportOptions imp_options;
  imp->add_option("inputs", imp_inputs, "annotation files or folders")->required();
  imp->add_option("--format", imp_format, "ade20k, nyuv2, labelme or palette")->required();
  imp->add_option("-o,--output", imp_out, "output folder (same stems, .png)")->required();
  imp->add_option("--palette", imp_palette, "palette.json for --format palette (colour → class id)");
  imp->add_option("--palette-threshold", imp_options.palette_threshold, "RGB distance for palette masks")
      ->capture_default_str();
  imp->add_option("--unlabeled", imp_unlabeled, "ADE20K/NYUv2 id 0 becomes: ignore (255) or background (0)")
      ->check(CLI::IsMember({"ignore", "background"}))
      ->capture_default_str();
  imp->add_option("--name", imp_names, "LabelMe label name → id, e.g. --name glazing=3 (repeatable)");
  imp->add_option("--threads", imp_options.num_threads, "worker threads (0 = all cores)")->capture_default_str();

  // compare
  CLI::App* cmp = app.add_subcommand("compare", "label maps vs exact label maps");
  std::string cmp_pred, cmp_exact;
  AgreementOptions cmp_options;
  cmp->add_option("predicted", cmp_pred, "folder of label maps to score")->required();
  cmp->add_option("exact", cmp_exact, "folder of exact label maps (same file names)")->required();
  cmp->add_option("--band", cmp_options.boundary_band_px, "boundary band half-width, px")->capture_default_str();

  Parse(app, argc, argv);

  if (cal->parsed()) {
    cal_options.Check();
    return Calibrate(cal_idmaps, cal_masks, cal_out, cal_options);
  }
  if (conv->parsed()) {
    Palette palette = conv_palette.empty() ? Palette::Nominal() : ReadPalette(conv_palette);
    conv_options.threshold = conv_threshold.value_or(palette.threshold.value_or(conv_options.threshold));
    conv_options.Check();
    std::vector<fs::path> inputs = ExpandInputs(conv_inputs, [](const fs::path& d) { return ListImageFiles(d); });
    spdlog::info("convert: {} ID maps, threshold {:.1f}, {}", inputs.size(), conv_options.threshold,
                 palette.ToString());
    ProgressPrinter printer;
    ConvertSummary summary = ConvertIdMapFiles(conv_options, palette, inputs, conv_out, printer.Callback());
    printer.Finish();
    fmt::print("{}\n", summary.BriefReport());
    return ReportFailures(summary.failed);
  }
  if (imp->parsed()) {
    std::optional<AnnotationFormat> format = ParseAnnotationFormat(imp_format);
    if (!format) {
      throw CLI::ValidationError(
          "--format", fmt::format("unknown format '{}'; known: ade20k, nyuv2, labelme, palette", imp_format));
    }
    imp_options.format = *format;
    imp_options.unlabeled_to_ignore = imp_unlabeled == "ignore";
    if (*format == AnnotationFormat::kPalette) {
      if (imp_palette.empty()) throw CLI::ValidationError("--palette", "required with --format palette");
      imp_options.palette = ReadPalette(imp_palette);
    }
    for (const std::string& n : imp_names) {
      auto eq = n.rfind('=');
      int id = -1;
      if (eq != std::string::npos) {
        try {
          id = std::stoi(n.substr(eq + 1));
        } catch (const std::exception&) {
        }
      }
      if (eq == std::string::npos || eq == 0 || !((id >= 0 && id <= 3) || id == 255)) {
        throw CLI::ValidationError("--name", fmt::format("'{}' is not NAME=ID with ID 0-3 or 255", n));
      }
      imp_options.labelme_names[AsciiLower(n.substr(0, eq))] = static_cast<std::uint8_t>(id);
    }
    imp_options.Check();
    std::vector<fs::path> inputs =
        ExpandInputs(imp_inputs, [&](const fs::path& d) { return ListAnnotationFiles(d, *format); });
    ProgressPrinter printer;
    ImportSummary summary = ImportAnnotations(imp_options, inputs, imp_out, printer.Callback());
    printer.Finish();
    fmt::print("{}\n", summary.BriefReport());
    return ReportFailures(summary.failed);
  }
  cmp_options.Check();
  return Compare(cmp_pred, cmp_exact, cmp_options);
}

}  // namespace asbuilt::cli
