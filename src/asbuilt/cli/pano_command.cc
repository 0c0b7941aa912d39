// `asbuilt pano views PANO -o DIR [--zind TOUR]` — an equirectangular
// panorama turned into turn-in-place perspective views, written as a mono
// capture (pano/pano_views.h); with --zind, also layout labels and the
// room's truth plan from the tour's annotation.

#include <filesystem>
#include <string>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/formats/zind.h"
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
  std::string pano, out, size, zind_dir, layout = "raw";
  PanoViewsOptions options;
  double camera_height_m = 0;
  views_cmd->add_option("panorama", pano, "equirectangular image (2:1), or with --zind a pano id")->required();
  views_cmd->add_option("-o,--out", out, "output folder")->required();
  AddTurnInPlaceFlags(*views_cmd, &options.turn, &size);
  views_cmd->add_option("--camera-height-m", camera_height_m,
                        "camera height above the floor for capture.json's position_m (default: ZInD's, else none)");
  views_cmd->add_option("--zind", zind_dir, "ZInD tour folder (with zind_data.json): also labels and truth.json");
  views_cmd->add_option("--layout", layout, "ZInD layout the labels come from: raw, complete, visible")
      ->capture_default_str();
  views_cmd->add_flag("--overlay", options.overlays, "with --zind: also DIR/overlays/NNN.png (labels over the views)");
  Parse(app, argc, argv);

  ApplyTurnInPlaceSize(size, options.turn);
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
