#include "asbuilt/plan/sheet_cairo.h"

#include <algorithm>
#include <cmath>

#include <cairo-pdf.h>
#include <cairo.h>
#include <fmt/format.h>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

void CairoColour(cairo_t* cr, const SheetColour& c) { cairo_set_source_rgb(cr, c.r, c.g, c.b); }

// Sets the stroke's colour, width and dashes; `unit`: device units per world
// metre; `mm`: per paper mm.
void CairoStroke(cairo_t* cr, const SheetStroke& stroke, double unit, double mm) {
  CairoColour(cr, stroke.colour);
  cairo_set_line_width(cr, stroke.width_mm * mm);
  if (stroke.dash_m > 0) {
    const double dash = stroke.dash_m * unit;
    cairo_set_dash(cr, &dash, 1, 0);
  } else {
    cairo_set_dash(cr, nullptr, 0, 0);
  }
}

// Paints the paper view on a cairo context at `unit` device units per world
// metre (y flipped, the sheet's lo.x / hi.y at the origin) and `mm` device
// units per paper mm.
void PaintSheet(cairo_t* cr, const PlanSheet& sheet, double unit, double mm) {
  const PaperDrawing paper = FlattenPaperView(sheet);
  auto X = [&](const Vec2& p) { return (p.x() - sheet.lo.x()) * unit; };
  auto Y = [&](const Vec2& p) { return (sheet.hi.y() - p.y()) * unit; };
  auto trace = [&](const SheetPath& path) {
    cairo_new_path(cr);
    for (size_t k = 0; k < path.points.size(); ++k) {
      (k == 0 ? cairo_move_to : cairo_line_to)(cr, X(path.points[k]), Y(path.points[k]));
    }
    if (path.closed) cairo_close_path(cr);
  };
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_MITER);
  for (const SheetPath& poly : paper.polygons) {
    trace(poly);
    if (poly.fill) {
      CairoColour(cr, *poly.fill);
      cairo_fill_preserve(cr);
    }
    if (poly.stroke) {
      CairoStroke(cr, *poly.stroke, unit, mm);
      cairo_stroke(cr);
    }
    cairo_new_path(cr);
  }
  for (const SheetDots& dots : paper.dots) {
    CairoColour(cr, dots.colour);
    for (const Vec2& p : dots.centres) {
      cairo_new_sub_path(cr);
      cairo_arc(cr, X(p), Y(p), dots.radius_mm * mm, 0, 2 * kPi);
    }
    cairo_fill(cr);
  }
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  for (const SheetPath& line : paper.lines) {
    if (!line.stroke) continue;
    trace(line);
    CairoStroke(cr, *line.stroke, unit, mm);
    cairo_stroke(cr);
  }
  for (const SheetArc& a : paper.arcs) {
    CairoStroke(cr, a.stroke, unit, mm);
    cairo_new_path(cr);
    // y is flipped: counter-clockwise in the world is clockwise on the device.
    cairo_arc_negative(cr, X(a.centre), Y(a.centre), a.radius_m * unit, -a.from_rad, -a.to_rad);
    cairo_stroke(cr);
  }
  for (const SheetText& t : paper.texts) {
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                           t.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, t.height_m * unit * 1.35);  // Cap height ≈ 0.74 em.
    cairo_text_extents_t ext;
    cairo_text_extents(cr, t.text.c_str(), &ext);
    cairo_save(cr);
    cairo_translate(cr, X(t.at), Y(t.at));
    cairo_rotate(cr, -t.angle_rad);
    cairo_move_to(cr, -t.anchor * ext.x_advance, 0);
    CairoColour(cr, t.colour);
    cairo_show_text(cr, t.text.c_str());
    cairo_restore(cr);
  }
}

void CheckCairoStatus(cairo_status_t status, const std::string& name) {
  if (status != CAIRO_STATUS_SUCCESS) {
    throw Error(fmt::format("{}: cannot write: {}", name, cairo_status_to_string(status)));
  }
}

cairo_status_t AppendToString(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

void SheetPngOptions::Check() const {
  CheckArgument(std::isfinite(px_per_m) && px_per_m > 0,
                fmt::format("SheetPngOptions.px_per_m = {}, must be finite and > 0", px_per_m));
  CheckArgument(std::isfinite(px_per_mm) && px_per_mm > 0,
                fmt::format("SheetPngOptions.px_per_mm = {}, must be finite and > 0", px_per_mm));
  CheckArgument(max_side_px >= 1 && max_side_px <= 32767,
                fmt::format("SheetPngOptions.max_side_px = {}, must be in [1, 32767]", max_side_px));
}

std::string SheetToPng(const PlanSheet& sheet, const SheetPngOptions& options) {
  options.Check();
  auto pixels = [&](double extent_m) {
    return std::clamp(static_cast<int>(std::ceil(extent_m * options.px_per_m - 1e-6)), 1, options.max_side_px);
  };
  const int width = pixels(sheet.Width()), height = pixels(sheet.Height());
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  cairo_t* cr = cairo_create(surface);
  PaintSheet(cr, sheet, options.px_per_m, options.px_per_mm);
  cairo_status_t status = cairo_status(cr);
  cairo_destroy(cr);
  std::string png;
  if (status == CAIRO_STATUS_SUCCESS) status = cairo_surface_write_to_png_stream(surface, AppendToString, &png);
  cairo_surface_destroy(surface);
  CheckCairoStatus(status, "PNG");
  return png;
}

void WriteSheetPdf(const PlanSheet& sheet, const fs::path& path) {
  // Points per world metre at the paper scale (1 pt = 1/72 in).
  const double unit = 1000.0 / sheet.scale / 25.4 * 72.0;
  const double mm = 72.0 / 25.4;
  AtomicFile file(path);
  cairo_surface_t* surface =
      cairo_pdf_surface_create(file.temp_path().c_str(), sheet.Width() * unit, sheet.Height() * unit);
  cairo_t* cr = cairo_create(surface);
  PaintSheet(cr, sheet, unit, mm);
  cairo_show_page(cr);
  cairo_status_t status = cairo_status(cr);
  cairo_destroy(cr);
  cairo_surface_finish(surface);
  if (status == CAIRO_STATUS_SUCCESS) status = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  CheckCairoStatus(status, path.string());
  file.Commit();
}

}  // namespace asbuilt
