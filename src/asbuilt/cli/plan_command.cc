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
#include "asbuilt/cli/field_flags.h"
#include "asbuilt/formats/capture.h"
#include "asbuilt/formats/points_file.h"
#include "asbuilt/plan/drawing.h"
#include "asbuilt/plan/label_points.h"
#include "asbuilt/plan/fit_plan.h"

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
  app.add_option("--viewpoint", viewpoint, "capture centre X Y Z (world m): --viewpoint-m as three values")
      ->expected(3);
  app.add_option("--stride-px", stride_px, "capture.json input: use every n-th pixel")->capture_default_str();
  app.add_option("--scale", drawing.scale, "paper scale 1:N of SVG and PDF")->capture_default_str();
  app.add_option("--png-px-per-m", drawing.png_px_per_m, "PNG resolution")->capture_default_str();
  app.add_option("--wall-thickness-m", drawing.nominal_thickness_m,
                 "thickness of walls whose thickness is unknown, in the drawings and plan.ifc (marked there "
                 "as a default)")
      ->capture_default_str();
  app.add_option("--wall-height-m", ifc.default_wall_height_m,
                 "plan.ifc: height of walls whose height is unknown (marked as a default)")
      ->capture_default_str();
  bool no_uncertainty = false;
  app.add_flag("--no-uncertainty", no_uncertainty, "do not print ± on the drawings");
  FieldFlags plan_flags(app, PlanOptionFields().Fields(options), {}, "Plan options (PlanOptions, docs/plan.md)");
  Parse(app, argc, argv);
  plan_flags.Read(PlanOptionFields(), options);
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
  // Points alone say nothing of where they were seen from: the viewpoint is
  // the flag's (or a capture's first frame), the labels count as segmented.
  PlanResult result = FitPlan({.points = std::move(points), .source = input}, options);
  WritePlanFiles(result.plan, out_dir, drawing, ifc);
  fmt::print("{}: {}\n", out_dir, result.summary.BriefReport());
  return 0;
}

}  // namespace asbuilt::cli
