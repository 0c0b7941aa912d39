// `asbuilt pano views PANO -o DIR [--zind TOUR]` — an equirectangular
// panorama turned into turn-in-place perspective views, written as a mono
// capture (pano/pano_views.h); with --zind, also layout labels and the
// room's truth plan from the tour's annotation.
// `asbuilt pano level PANO -o OUT [--estimate-only]` — the panorama's tilt
// from its own lines, and the panorama resampled level (pano/level.h).

#include <filesystem>
#include <string>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/formats/zind.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/pano/level.h"
#include "asbuilt/pano/pano_views.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {
namespace {
namespace fs = std::filesystem;

ZindLayoutKind ParseLayoutKind(const std::string& name) {
  for (ZindLayoutKind k : {ZindLayoutKind::kRaw, ZindLayoutKind::kComplete, ZindLayoutKind::kVisible}) {
    if (name == ZindLayoutKindName(k)) return k;
  }
  throw CLI::ValidationError("--layout", fmt::format("expected raw, complete or visible, got '{}'", name));
}

// The tour's panorama that `pano` names: a key (pano id, full name, image
// path as in the file) or the image file itself.
const ZindPanorama& FindPanorama(const ZindTour& tour, const std::string& pano) {
  if (const ZindPanorama* p = tour.Find(pano)) return *p;
  std::error_code ec;
  for (const ZindPanorama& p : tour.panoramas) {
    if (fs::exists(pano) && fs::equivalent(pano, p.image, ec)) return p;
  }
  throw InputError(tour.file.string(), "merger",
                   fmt::format("no panorama '{}' (give a pano id such as pano_15, or one of the tour's images)", pano));
}

}  // namespace

int RunPanoCommand(int argc, char** argv) {
  CLI::App app("Equirectangular 360° panoramas.", "asbuilt pano");
  AddCommonFlags(app);
  app.require_subcommand(1);

  CLI::App* views_cmd = app.add_subcommand(
      "views",
      "turn a panorama into the perspective views a camera turning in place at its centre takes:\n"
      "DIR/images/NNN.png and DIR/capture.json (a mono capture: camera, yaw and pitch per view; docs/formats.md).\n"
      "With --zind TOUR (a ZInD tour folder; PANO is then a pano id such as pano_15 or one of the tour's\n"
      "images) also layout labels DIR/labels/NNN.png and the room's plan DIR/truth.json, in the pano frame\n"
      "(docs/seg.md). ZInD is for academic use only: research measurement, never training data.");
  std::string pano, out, zind_dir, layout = "raw";
  PanoViewsOptions options;
  double camera_height_m = 0;
  views_cmd->add_option("panorama", pano, "equirectangular image (2:1), or with --zind a pano id")->required();
  views_cmd->add_option("-o,--out", out, "output folder")->required();
  const auto turn_flags = AddTurnInPlaceFlags(*views_cmd, options.turn);
  views_cmd->add_option("--camera-height-m", camera_height_m,
                        "camera height above the floor for capture.json's position_m (default: ZInD's, else none)");
  views_cmd->add_option("--zind", zind_dir, "ZInD tour folder (with zind_data.json): also labels and truth.json");
  views_cmd->add_option("--layout", layout, "ZInD layout the labels come from: raw, complete, visible")
      ->capture_default_str();
  views_cmd->add_option("--labels-pano", options.label_panorama,
                        "a label panorama of the same scene (8-bit label PNG, or the object-index EXR of `scene "
                        "export-blender --panorama --labels-pass`): also DIR/labels/NNN.png, nearest pixel");
  views_cmd->add_flag("--overlay", options.overlays, "with labels: also DIR/overlays/NNN.png (labels over the views)");

  CLI::App* level_cmd = app.add_subcommand(
      "level",
      "estimate a panorama's tilt from its own vertical and horizontal lines and write it resampled level\n"
      "(the smallest rotation that makes the estimated up the image's up; no turn about the vertical).\n"
      "Prints e.g. 'tilted 0.76° toward yaw 328° (column 90 of 1024) ± 0.11°, 1031 lines (244 vertical)'.");
  std::string level_in, level_out;
  bool estimate_only = false, vertical_only = false;
  LevelOptions level_options;
  level_cmd->add_option("panorama", level_in, "equirectangular image (2:1; .hdr is tone-mapped)")->required();
  level_cmd->add_option("-o,--out", level_out, "the levelled panorama (same size; format from the extension)");
  level_cmd->add_flag("--estimate-only", estimate_only, "print the tilt, write nothing");
  level_cmd->add_option("--max-tilt-deg", level_options.max_tilt_deg, "largest tilt searched, degrees")
      ->capture_default_str();
  level_cmd->add_option("--min-segment-deg", level_options.min_segment_deg, "shortest line segment used, degrees")
      ->capture_default_str();
  level_cmd->add_flag("--vertical-only", vertical_only, "use vertical lines only (a room that is not square)");
  Parse(app, argc, argv);

  if (level_cmd->parsed()) {
    if (level_out.empty() && !estimate_only) throw CLI::RequiredError("--out (or --estimate-only)");
    level_options.use_horizontal_lines = !vertical_only;
    level_options.Check();
    const Image equirect = ReadEquirect(level_in);
    const PanoTilt tilt = EstimatePanoTilt(equirect, level_options);
    fmt::print("{}\n", tilt.BriefReport(equirect.width()));
    if (estimate_only) return 0;
    if (!tilt.found) throw Error(fmt::format("{}: no tilt estimate, {} not written", level_in, level_out));
    WriteImageAtomic(level_out, LevelPanorama(equirect, tilt));
    fmt::print("levelled → {}\n", level_out);
    return 0;
  }

  turn_flags->ReadGiven(TurnInPlaceOptionFields(), options.turn);
  if (camera_height_m != 0) options.camera_height_m = camera_height_m;
  options.layout = ParseLayoutKind(layout);
  options.Check();
  ProgressPrinter printer;
  PanoViewsSummary summary;
  if (!zind_dir.empty()) {
    const ZindTour tour = ReadZindTour(zind_dir);
    const ZindPanorama& p = FindPanorama(tour, pano);
    fmt::print(stderr, "{}\n{}\n", kZindNotice, p.ToString());
    summary = WritePanoViews(p.image, out, options, &p, printer.Callback());
  } else {
    summary = WritePanoViews(pano, out, options, nullptr, printer.Callback());
  }
  printer.Finish();
  fmt::print("{}\n", summary.BriefReport());
  return 0;
}

}  // namespace asbuilt::cli
