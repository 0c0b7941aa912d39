// `asbuilt plan POINTS -o FOLDER` — floor plan from labelled class points
// (the point file of `asbuilt points`), written as plan.json, plan.svg,
// plan.dxf, plan.pdf, plan.png and plan.ifc. Given a synthetic capture.json with label
// and depth maps instead, it back-projects the labelled pixels first (the
// "exact labels" upper bound of the survey).

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/formats/capture.h"
#include "asbuilt/formats/points_file.h"
#include "asbuilt/plan/drawing.h"
#include "asbuilt/plan/label_points.h"
#include "asbuilt/plan/reconstruct.h"

namespace asbuilt::cli {

int RunPlanCommand(int argc, char** argv) {
  CLI::App app(
      "Floor plan from labelled class points: walls, openings, dimensions with ± uncertainty.\n"
      "Writes plan.json, plan.svg, plan.dxf, plan.pdf, plan.png and plan.ifc (IFC4, for BIM tools)\n"
      "into the output folder.\n"
      "INPUT is a point file (`class x y z [sigma source frame]` lines), or a synthetic\n"
      "capture.json with label and depth maps (exact class points from the labels).",
      "asbuilt plan");
  AddCommonFlags(app);
  std::string input, out_dir;
  PlanOptions options;
  DrawingOptions drawing;
  IfcOptions ifc;
  std::vector<double> viewpoint;
  int stride_px = 2;
  app.add_option("input", input, "points.txt, or capture.json with labels + depth")->required();
  app.add_option("-o,--output", out_dir, "output folder")->required();
  app.add_option("--epsilon-m", options.epsilon_m, "collinearity tolerance ε (base inlier band), m")
      ->capture_default_str();
  app.add_option("--max-inlier-distance-m", options.max_inlier_distance_m,
                 "cap on a wall's inlier band for noisy points, m")->capture_default_str();
  app.add_option("--min-wall-points", options.min_wall_points, "fewer points are not a wall")
      ->capture_default_str();
  app.add_option("--min-wall-length-m", options.min_wall_length_m, "shorter point runs are not walls, m")
      ->capture_default_str();
  app.add_option("--max-gap-m", options.max_gap_m, "split a line into separate walls at longer gaps, m")
      ->capture_default_str();
  app.add_option("--door-casing-m", options.door_casing_m,
                 "door labels extend this far beyond the clear opening (0 if labels mark the clear opening)")
      ->capture_default_str();
  app.add_option("--window-casing-m", options.window_casing_m, "same for windows, m")->capture_default_str();
  app.add_option("--viewpoint", viewpoint, "capture centre X Y Z (world m); improves openings")->expected(3);
  app.add_option("--seed", options.seed, "RANSAC seed")->capture_default_str();
  app.add_option("--stride-px", stride_px, "capture.json input: use every n-th pixel")->capture_default_str();
  app.add_option("--scale", drawing.scale, "paper scale 1:N of SVG and PDF")->capture_default_str();
  app.add_option("--png-px-per-m", drawing.png_px_per_m, "PNG resolution")->capture_default_str();
  app.add_option("--wall-thickness-m", drawing.nominal_thickness_m,
                 "thickness of walls whose thickness is unknown, in the drawings and plan.ifc (marked there "
                 "as a default)")->capture_default_str();
  app.add_option("--wall-height-m", ifc.default_wall_height_m,
                 "plan.ifc: height of walls whose height is unknown (marked as a default)")->capture_default_str();
  bool no_uncertainty = false;
  app.add_flag("--no-uncertainty", no_uncertainty, "do not print ± on the drawings");
  Parse(app, argc, argv);
  drawing.show_uncertainty = !no_uncertainty;
  ifc.default_wall_thickness_m = drawing.nominal_thickness_m;
  if (viewpoint.size() == 3) options.viewpoint_m = Vec3(viewpoint[0], viewpoint[1], viewpoint[2]);
  options.Check();  // Usage errors before any file is read.
  drawing.Check();
  ifc.Check();

  std::vector<ClassPoint> points;
  if (std::filesystem::path(input).extension() == ".json") {
    Capture capture = ReadCapture(input);
    points = PointsFromLabelledDepth(capture, {.stride_px = stride_px});
    if (!options.viewpoint_m && !capture.frames.empty()) options.viewpoint_m = capture.frames[0].position_m;
  } else {
    points = ReadPoints(input);
  }
  PlanResult result = ReconstructPlan(points, options, input);
  WritePlanFiles(result.plan, out_dir, drawing, ifc);
  fmt::print("{}: {}\n", out_dir, result.summary.BriefReport());
  return 0;
}

}  // namespace asbuilt::cli
