// `asbuilt points capture.json --labels DIR -o points/` — world points by
// class from a stereo capture and its segmentation (stereo/capture_points.h).

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/cli/field_flags.h"
#include "asbuilt/formats/capture.h"
#include "asbuilt/formats/points_file.h"
#include "asbuilt/formats/points_ply.h"
#include "asbuilt/stereo/capture_points.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {

int RunPointsCommand(int argc, char** argv) {
  CLI::App app(
      "Triangulate wall/door/window points from a stereo capture and left-view labels\n"
      "(DIR/NNN.png per frame index; DIR/right/NNN.png used when present). Cues: matched\n"
      "contour corners, edges inside components, dense consistent disparity, opening\n"
      "boundaries, and floor/ceiling contacts where the walls' stereo fails (--contacts). Writes\n"
      "OUT/points.txt (class x y z sigma_m source frame) and OUT/points.ply.",
      "asbuilt points");
  AddCommonFlags(app);
  std::string capture_path, labels_dir, out_dir;
  bool use_capture_labels = false;
  FramePointsOptions options;
  app.add_option("capture", capture_path, "capture.json")->required();
  app.add_option("--labels", labels_dir, "folder of label images NNN.png (left view)");
  app.add_flag("--use-capture-labels", use_capture_labels, "use each frame's `labels` key of capture.json");
  app.add_option("-o,--out", out_dir, "output folder")->required();
  // The short spellings are older flags that scripts use.
  FieldFlags point_flags(app, FramePointsOptionFields().Fields(options),
                         {{"disparity.num_disparities_px", "--num-disparities"},
                          {"dense_stride_px", "--dense-stride"},
                          {"match.row_tolerance_px", "--row-tolerance"},
                          {"disparity.wls_filter", "--wls"},
                          {"use_corners", "!--no-corners"},
                          {"use_edges", "!--no-edges"},
                          {"use_dense", "!--no-dense"},
                          {"use_vertices", "!--no-vertices"},
                          {"contact_snap_px", "--snap-contacts-px"}},
                         "Points options (FramePointsOptions, docs/stereo.md)");
  Parse(app, argc, argv);
  point_flags.Read(FramePointsOptionFields(), options);
  if (labels_dir.empty() == !use_capture_labels) {
    throw CLI::ValidationError("--labels", "give exactly one of --labels DIR or --use-capture-labels");
  }
  options.ResolveSnaps(use_capture_labels);
  options.Check();

  const Capture capture = ReadCapture(capture_path);
  std::unique_ptr<LabelSource> labels;
  if (use_capture_labels) {
    labels = std::make_unique<CaptureLabels>(capture);
  } else {
    labels = std::make_unique<DirectoryLabels>(labels_dir);
  }
  ProgressPrinter printer;
  const CapturePointsResult result = ComputeCapturePoints(capture, *labels, options, nullptr, printer.Callback());
  printer.Finish();
  for (const FrameCues& f : result.frames) fmt::print(stderr, "  {}\n", f.BriefReport());
  if (!result.wall_cue.empty()) spdlog::info("points: {}", result.wall_cue);
  if (result.points.empty()) {
    throw InputError(capture_path, "",
                     "no point could be triangulated in any frame (no labelled wall, door or "
                     "window with a valid disparity): check the labels and the stereo pair");
  }
  const std::filesystem::path out(out_dir);
  WritePoints(result.points, out / "points.txt");
  WritePointsPly(result.points, out / "points.ply");
  fmt::print("{} → {}\n", result.BriefReport(), (out / "points.txt").string());
  return 0;
}

}  // namespace asbuilt::cli
