// `asbuilt points capture.json --labels DIR -o points/` — world points by
// class from a stereo capture and its segmentation (stereo/capture_points.h).

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/cli/command.h"
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
  bool use_capture_labels = false, no_corners = false, no_edges = false, no_dense = false, no_vertices = false;
  FramePointsOptions options;
  app.add_option("capture", capture_path, "capture.json")->required();
  app.add_option("--labels", labels_dir, "folder of label images NNN.png (left view)");
  app.add_flag("--use-capture-labels", use_capture_labels, "use each frame's `labels` key of capture.json");
  app.add_option("-o,--out", out_dir, "output folder")->required();
  app.add_option("--num-disparities", options.disparity.num_disparities_px, "disparity range, multiple of 16")
      ->capture_default_str();
  app.add_option("--dense-stride", options.dense_stride_px, "keep every n-th dense pixel")->capture_default_str();
  app.add_option("--row-tolerance", options.match.row_tolerance_px, "search rows v +- n (imperfect rectification)")
      ->capture_default_str();
  app.add_flag("--wls", options.disparity.wls_filter, "WLS-filter the dense disparity guide");
  app.add_flag("--no-corners", no_corners, "skip contour corners");
  app.add_flag("--no-edges", no_edges, "skip edge points");
  app.add_flag("--no-dense", no_dense, "skip dense points");
  app.add_flag("--no-vertices", no_vertices, "skip wall-wall corner columns (vertex points)");
  AddContactsOption(app, &options.contacts);
  std::optional<int> snap_px;
  AddContactSnapOption(app, &snap_px);
  Parse(app, argc, argv);
  if (labels_dir.empty() == !use_capture_labels) {
    throw CLI::ValidationError("--labels", "give exactly one of --labels DIR or --use-capture-labels");
  }
  options.use_corners = !no_corners;
  options.use_edges = !no_edges;
  options.use_dense = !no_dense;
  options.use_vertices = !no_vertices;
  options.contact_snap_px = FramePointsOptions::ContactSnapPxFor(snap_px, use_capture_labels);
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
    throw InputError(capture_path, "", "no point could be triangulated in any frame (no labelled wall, door or "
                                       "window with a valid disparity): check the labels and the stereo pair");
  }
  const std::filesystem::path out(out_dir);
  WritePoints(result.points, out / "points.txt");
  WritePointsPly(result.points, out / "points.ply");
  fmt::print("{} → {}\n", result.BriefReport(), (out / "points.txt").string());
  return 0;
}

}  // namespace asbuilt::cli
