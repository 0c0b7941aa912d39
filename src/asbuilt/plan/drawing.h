#ifndef ASBUILT_PLAN_DRAWING_H_
#define ASBUILT_PLAN_DRAWING_H_

// Floor plan drawings to architectural convention: walls as filled thick
// bands (their thickness when known, else a nominal one drawn outside the
// inner face), cut at openings; doors as a gap with the leaf and its swing
// arc; windows as jamb lines and a double glass line in the wall; dimension
// strings outside each wall (a chain through the openings and the overall
// inner length) with extension lines and 45° ticks, text in mm (± where the
// uncertainty is significant); overall dimensions for rooms that are not
// rectangles; the room area; a scale bar.
//
// SVG is written as text; PDF and PNG through cairo; DXF by asbuilt's own
// writer (dxf.h). Every file is written atomically: on failure nothing
// appears under the final name.

#include <filesystem>
#include <string>

#include "asbuilt/formats/plan_file.h"

namespace asbuilt {

struct DrawingOptions {
  double nominal_thickness_m = 0.2;  // Drawn thickness of walls the plan gives none for.
  double scale = 50.0;               // Paper scale 1:scale for SVG and PDF sizes (1:50 default).
  double png_px_per_m = 120.0;       // PNG resolution; 120 px/m ≈ 1:50 at 150 dpi.
  double text_height_m = 0.13;       // Dimension text height in world metres (2.6 mm at 1:50).
  bool show_uncertainty = true;      // Print ±σ next to a dimension…
  double significant_sigma_m = 0.005;  // …when σ is at least this.
  std::string title = "as-built floor plan";  // Title line under the plan; empty: none.

  void Check() const;
};

void WritePlanSvg(const Plan& plan, const std::filesystem::path& path, const DrawingOptions& options = {});
void WritePlanPdf(const Plan& plan, const std::filesystem::path& path, const DrawingOptions& options = {});
void WritePlanPng(const Plan& plan, const std::filesystem::path& path, const DrawingOptions& options = {});

// The SVG document as a string (what WritePlanSvg writes).
std::string PlanToSvg(const Plan& plan, const DrawingOptions& options = {});

// Writes plan.json, plan.svg, plan.dxf, plan.pdf and plan.png into `folder`
// (created if missing). Throws Error naming the file that failed.
void WritePlanFiles(const Plan& plan, const std::filesystem::path& folder, const DrawingOptions& options = {});

// Text of a length in the drawing's units: millimetres, rounded ("4500"),
// with " ±5" appended when `sigma_m` is significant for the options.
std::string DimensionText(double length_m, std::optional<double> sigma_m, const DrawingOptions& options);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_DRAWING_H_
