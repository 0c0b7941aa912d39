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
// Each writer lays the plan out once as a plan sheet (sheet.h) and
// serialises it: SVG as text (sheet_svg.h), PDF and PNG through cairo
// (sheet_cairo.h), DXF by asbuilt's own writer (dxf.h). Every file is
// written atomically: on failure nothing appears under the final name.
//
// Any plan with finite coordinates can be drawn, however large or bad: when
// the sheet would not fit the page (SVG, PDF) or image (PNG) limit at
// `DrawingOptions.scale`, it is drawn at the first coarser scale of the
// 1-2-5 series (1:100, 1:200, 1:500, …) that fits, with text, dimension
// offsets, the scale bar and the margin kept at their paper size; the title
// block states the scale actually used. Sharp wall corners whose mitre
// would reach far beyond the wall are bevelled.

#include <filesystem>
#include <optional>
#include <string>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/plan/ifc.h"

namespace asbuilt {

struct DrawingOptions {
  double nominal_thickness_m = 0.2;           // Drawn thickness of walls the plan gives none for.
  double scale = 50.0;                        // Paper scale 1:scale (unless too large, see above).
  double png_px_per_m = 120.0;                // PNG resolution at `scale`; 120 px/m ≈ 1:50 at 150 dpi.
  double text_height_m = 0.13;                // Dimension text height in world metres at `scale` (2.6 mm at 1:50).
  bool show_uncertainty = true;               // Print ±σ next to a dimension…
  double significant_sigma_m = 0.0;           // …when σ is at least this (shown as at least ±1 mm).
  std::string title = "as-built floor plan";  // Title line under the plan; empty: none.
  // Longest page side for SVG and PDF, paper mm; a larger sheet is drawn at a
  // coarser scale. cairo's PDF pages are at most 14400 pt = 5080 mm.
  double max_page_side_mm = 5080.0;
  // Longest PNG side, px; a larger image is drawn at a coarser scale (and, if
  // the annotation alone is larger, at a lower resolution). cairo's limit is 32767.
  int max_png_side_px = 8192;

  void Check() const;
};

// Writers. Throw Error naming `path` when the plan cannot be drawn (a
// non-finite coordinate, an opening on a wall that does not exist; for SVG
// and PDF, title block and text larger than max_page_side_mm at any scale)
// or written. An empty plan gives the scale bar and title block alone.
void WritePlanSvg(const Plan& plan, const std::filesystem::path& path, const DrawingOptions& options = {});
void WritePlanPdf(const Plan& plan, const std::filesystem::path& path, const DrawingOptions& options = {});
void WritePlanPng(const Plan& plan, const std::filesystem::path& path, const DrawingOptions& options = {});

// The SVG document as a string (what WritePlanSvg writes). Throws Error
// ("plan: …") when the plan cannot be drawn.
std::string PlanToSvg(const Plan& plan, const DrawingOptions& options = {});

// The scale denominator N (drawing at 1:N) that WritePlanSvg and WritePlanPdf
// use for `plan`: options.scale when the sheet fits max_page_side_mm, else the
// first coarser 1-2-5 scale that does.
double PlanPageScale(const Plan& plan, const DrawingOptions& options = {});
// Likewise for WritePlanPng and max_png_side_px.
double PlanPngScale(const Plan& plan, const DrawingOptions& options = {});

// Writes plan.json, plan.svg, plan.dxf, plan.pdf, plan.png and plan.ifc
// (plan/ifc.h) into `folder` (created if missing). Throws Error naming the
// file that failed.
void WritePlanFiles(const Plan& plan, const std::filesystem::path& folder, const DrawingOptions& options = {},
                    const IfcOptions& ifc = {});

// Text of a length in the drawing's units: millimetres, rounded ("4500"),
// with " ±5" appended when `sigma_m` is significant for the options.
std::string DimensionText(double length_m, std::optional<double> sigma_m, const DrawingOptions& options);

// Used by the sheet's layout (sheet.h): a wall's drawn thickness (its
// own, or the options' nominal one), and a text angle (radians) turned by π
// where needed so that it reads left-to-right or bottom-to-top.
double DrawnThickness(const PlanWall& wall, const DrawingOptions& options);
double ReadableTextAngle(double angle);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_DRAWING_H_
