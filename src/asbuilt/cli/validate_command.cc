// `asbuilt validate FILE…` — checks any asbuilt file and reports every
// problem found, not just the first.

#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/dataset/manifest.h"
#include "asbuilt/formats/capture.h"
#include "asbuilt/formats/plan_file.h"
#include "asbuilt/stereo/rectify.h"
#include "asbuilt/labels/palette.h"
#include "asbuilt/scene/scene_json.h"
#include "asbuilt/util/json_reader.h"

namespace asbuilt::cli {
namespace {
namespace fs = std::filesystem;

// One row per file kind `validate` knows. `looks_like` decides from the
// parsed document when --kind is not given.
struct FileKind {
  std::string_view name;
  bool (*looks_like)(const nlohmann::json& doc);
  FileReport (*check)(const fs::path& path);
};

const FileKind kFileKinds[] = {
    {"capture",
     [](const nlohmann::json& d) {
       return (d.contains("frames") && d.contains("camera")) || d.contains("panorama") ||
              (d.contains("kind") && d.value("kind", nlohmann::json()).is_string());
     },
     &CheckCaptureFile},
    {"plan", [](const nlohmann::json& d) { return d.contains("walls"); }, &CheckPlanFile},
    // OpenCV YAML, not JSON: only with --kind calibration.
    {"calibration", [](const nlohmann::json&) { return false; }, &CheckCalibrationFile},
    {"scene", [](const nlohmann::json& d) { return d.contains("rooms") && !d.contains("walls"); }, &CheckSceneFile},
    {"manifest", [](const nlohmann::json& d) { return d.contains("train") && d.contains("config"); },
     &CheckManifestFile},
    {"palette", [](const nlohmann::json& d) { return d.contains("colours"); }, &CheckPaletteFile},
};

std::string KindNames() {
  std::string out;
  for (const FileKind& k : kFileKinds) out += (out.empty() ? "" : ", ") + std::string(k.name);
  return out;
}

}  // namespace

int RunValidateCommand(int argc, char** argv) {
  CLI::App app(
      "Check asbuilt files and report every problem (file, field path, what is wrong).\n"
      "The kind of each file is recognised from its contents unless --kind is given.",
      "asbuilt validate");
  AddCommonFlags(app);
  std::vector<std::string> files;
  std::string kind;
  app.add_option("files", files, "files to check")->required();
  app.add_option("--kind", kind, "force the file kind: " + KindNames());
  Parse(app, argc, argv);

  const FileKind* forced = nullptr;
  if (!kind.empty()) {
    for (const FileKind& k : kFileKinds) {
      if (k.name == kind) forced = &k;
    }
    if (forced == nullptr) {
      throw CLI::ValidationError("--kind", fmt::format("unknown kind '{}'; known: {}", kind, KindNames()));
    }
  }

  int invalid = 0;
  for (const std::string& file : files) {
    const FileKind* k = forced;
    FileReport report;
    if (k == nullptr) {
      JsonDiagnostics diag(file);
      nlohmann::json doc = ParseJsonFile(file, diag);
      for (const FileKind& candidate : kFileKinds) {
        if (diag.ok() && doc.is_object() && candidate.looks_like(doc)) {
          k = &candidate;
          break;
        }
      }
      if (k == nullptr) {
        report.errors = diag.errors();
        if (diag.ok()) {
          report.errors.push_back(
              {file, "", fmt::format("not a known asbuilt file (kinds: {}); use --kind", KindNames())});
        }
      }
    }
    if (k != nullptr) report = k->check(file);
    for (const Problem& w : report.warnings) fmt::print(stderr, "warning: {}\n", w.ToString());
    for (const Problem& e : report.errors) fmt::print(stderr, "{}\n", e.ToString());
    if (report.errors.empty()) {
      fmt::print("{}: ok ({})\n", file, k->name);
    } else {
      ++invalid;
      fmt::print("{}: invalid ({} problem{})\n", file, report.errors.size(), report.errors.size() == 1 ? "" : "s");
    }
  }
  return invalid == 0 ? 0 : 1;
}

}  // namespace asbuilt::cli
