#include "asbuilt/plan/drawing.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/plan/dxf.h"
#include "asbuilt/plan/sheet.h"
#include "asbuilt/plan/sheet_cairo.h"
#include "asbuilt/plan/sheet_svg.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

// The next scale denominator of the 1-2-5 series above `scale` > 0
// (50 → 100 → 200 → 500 → 1000 …).
double NextCoarserScale(double scale) {
  const double base = std::pow(10.0, std::floor(std::log10(scale)) - 1);
  for (double decade : {1.0, 10.0, 100.0}) {
    for (double m : {1.0, 2.0, 5.0}) {
      if (m * decade * base > scale * (1 + 1e-9)) return m * decade * base;
    }
  }
  return 1000 * base;
}

// The sheet at the first scale of options.scale, then the 1-2-5 series, at
// which `size(sheet)` (its longest side in the limit's unit) is within
// `limit`. Where the annotation alone exceeds the limit no scale fits; the
// sheet returned then is the coarsest tried (its size still above `limit`).
// Throws Error naming `name` if the plan cannot be drawn or the sheet's
// extent overflows.
template <typename Size>
PlanSheet FitSheet(const Plan& plan, const DrawingOptions& o, double limit, const Size& size, const std::string& name) {
  CheckPlanDrawable(plan, name);
  double scale = o.scale;
  PlanSheet sheet = LayOutPlanSheet(plan, o, scale);
  double now = size(sheet);
  while (std::isfinite(now) && now > limit) {
    // The plan shrinks as 1/scale on paper, the annotation not at all, so
    // at least scale · now / limit is needed.
    double next = NextCoarserScale(scale);
    while (next < scale * now / limit) next = NextCoarserScale(next);
    PlanSheet coarser = LayOutPlanSheet(plan, o, next);
    double then = size(coarser);
    if (!(then < 0.99 * now)) break;  // Only the annotation is left.
    scale = next;
    sheet = std::move(coarser);
    now = then;
  }
  if (!std::isfinite(now)) {
    throw Error(fmt::format("{}: cannot draw the plan: its extent ({} x {} m) is not finite", name, sheet.Width(),
                            sheet.Height()));
  }
  return sheet;
}

// Longest side of the SVG/PDF page, paper mm.
double PageSideMm(const PlanSheet& sheet) { return std::max(sheet.Width(), sheet.Height()) * 1000.0 / sheet.scale; }

// PNG pixels per world metre at the sheet's scale (the paper resolution of
// png_px_per_m at options.scale kept).
double PngPxPerM(const PlanSheet& sheet, const DrawingOptions& o) { return o.png_px_per_m * o.scale / sheet.scale; }

// Logs that `path` is drawn at a coarser scale than asked for, if it is.
void WarnIfReduced(const PlanSheet& sheet, const DrawingOptions& o, const fs::path& path, const std::string& limit) {
  if (sheet.scale == o.scale) return;
  spdlog::warn("{}: at 1:{} the drawing would exceed {}; drawn at 1:{} (the sheet is {:.0f} x {:.0f} m)", path.string(),
               SheetScaleText(o.scale), limit, SheetScaleText(sheet.scale), sheet.Width(), sheet.Height());
}

// The sheet for SVG and PDF: within max_page_side_mm, else an Error.
PlanSheet PageSheet(const Plan& plan, const DrawingOptions& o, const std::string& name) {
  PlanSheet sheet = FitSheet(plan, o, o.max_page_side_mm, PageSideMm, name);
  if (PageSideMm(sheet) > o.max_page_side_mm) {
    throw Error(
        fmt::format("{}: cannot draw the plan: its annotation alone needs {:.0f} mm, more than "
                    "DrawingOptions.max_page_side_mm = {}",
                    name, PageSideMm(sheet), o.max_page_side_mm));
  }
  return sheet;
}

// The sheet for PNG: within max_png_side_px where the annotation allows.
PlanSheet PngSheet(const Plan& plan, const DrawingOptions& o, const std::string& name) {
  auto side_px = [&](const PlanSheet& sheet) { return std::max(sheet.Width(), sheet.Height()) * PngPxPerM(sheet, o); };
  return FitSheet(plan, o, o.max_png_side_px, side_px, name);
}

}  // namespace

void DrawingOptions::Check() const {
  CheckArgument(nominal_thickness_m > 0,
                fmt::format("DrawingOptions.nominal_thickness_m = {}, must be > 0", nominal_thickness_m));
  CheckArgument(std::isfinite(scale) && scale > 0,
                fmt::format("DrawingOptions.scale = {}, must be finite and > 0", scale));
  CheckArgument(png_px_per_m > 0 && png_px_per_m <= 2000,
                fmt::format("DrawingOptions.png_px_per_m = {}, must be in (0, 2000]", png_px_per_m));
  CheckArgument(text_height_m > 0, fmt::format("DrawingOptions.text_height_m = {}, must be > 0", text_height_m));
  CheckArgument(significant_sigma_m >= 0,
                fmt::format("DrawingOptions.significant_sigma_m = {}, must be >= 0", significant_sigma_m));
  CheckArgument(max_page_side_mm > 0 && max_page_side_mm <= 5080,
                fmt::format("DrawingOptions.max_page_side_mm = {}, must be in (0, 5080]", max_page_side_mm));
  CheckArgument(max_png_side_px >= 16 && max_png_side_px <= 32767,
                fmt::format("DrawingOptions.max_png_side_px = {}, must be in [16, 32767]", max_png_side_px));
}

double DrawnThickness(const PlanWall& wall, const DrawingOptions& options) {
  return wall.thickness.value_or(options.nominal_thickness_m);
}

double ReadableTextAngle(double angle) {
  while (angle > kPi / 2 + 1e-9) angle -= kPi;
  while (angle <= -kPi / 2 + 1e-9) angle += kPi;
  return angle;
}

std::string DimensionText(double length_m, std::optional<double> sigma_m, const DrawingOptions& options) {
  std::string text = fmt::format("{}", static_cast<long>(std::lround(length_m * 1000)));
  if (options.show_uncertainty && sigma_m && *sigma_m >= options.significant_sigma_m) {
    text += fmt::format(" ±{}", std::max(1L, static_cast<long>(std::lround(*sigma_m * 1000))));
  }
  return text;
}

std::string PlanToSvg(const Plan& plan, const DrawingOptions& options) {
  options.Check();
  return SheetToSvg(PageSheet(plan, options, "plan"));
}

double PlanPageScale(const Plan& plan, const DrawingOptions& options) {
  options.Check();
  return PageSheet(plan, options, "plan").scale;
}

double PlanPngScale(const Plan& plan, const DrawingOptions& options) {
  options.Check();
  return PngSheet(plan, options, "plan").scale;
}

void WritePlanSvg(const Plan& plan, const fs::path& path, const DrawingOptions& options) {
  options.Check();
  PlanSheet sheet = PageSheet(plan, options, path.string());
  WarnIfReduced(sheet, options, path, fmt::format("{} mm", options.max_page_side_mm));
  WriteFileAtomic(path, SheetToSvg(sheet));
}

void WritePlanPdf(const Plan& plan, const fs::path& path, const DrawingOptions& options) {
  options.Check();
  PlanSheet sheet = PageSheet(plan, options, path.string());
  WarnIfReduced(sheet, options, path, fmt::format("{} mm", options.max_page_side_mm));
  WriteSheetPdf(sheet, path);
}

void WritePlanPng(const Plan& plan, const fs::path& path, const DrawingOptions& options) {
  options.Check();
  PlanSheet sheet = PngSheet(plan, options, path.string());
  WarnIfReduced(sheet, options, path, fmt::format("{} px", options.max_png_side_px));
  double unit = PngPxPerM(sheet, options);
  // Where the annotation alone is larger than the cap, a lower resolution.
  unit = std::min(unit, options.max_png_side_px / std::max(sheet.Width(), sheet.Height()));
  // Line widths: paper mm at the drawing scale, but at least ~1 px.
  const double mm = std::max(unit * sheet.scale / 1000.0, 1.0);
  WriteFileAtomic(path, SheetToPng(sheet, {.px_per_m = unit, .px_per_mm = mm, .max_side_px = options.max_png_side_px}));
}

void WritePlanFiles(const Plan& plan, const fs::path& folder, const DrawingOptions& options, const IfcOptions& ifc) {
  options.Check();
  ifc.Check();
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw Error(fmt::format("{}: cannot create folder: {}", folder.string(), ec.message()));
  WritePlan(plan, folder / "plan.json");
  WritePlanSvg(plan, folder / "plan.svg", options);
  WritePlanDxf(plan, folder / "plan.dxf", options);
  WritePlanPdf(plan, folder / "plan.pdf", options);
  WritePlanPng(plan, folder / "plan.png", options);
  WritePlanIfc(plan, folder / "plan.ifc", ifc);
}

}  // namespace asbuilt
