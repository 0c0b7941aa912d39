#ifndef ASBUILT_PLAN_SHEET_CAIRO_H_
#define ASBUILT_PLAN_SHEET_CAIRO_H_

// The paper view of a plan sheet (plan/sheet.h) painted by cairo: a PDF page
// at the sheet's scale, or a PNG image. Painted in FlattenPaperView's order
// on white; miter joins, butt caps; text in cairo's "sans-serif".

#include <filesystem>
#include <string>

#include "asbuilt/plan/sheet.h"

namespace asbuilt {

struct SheetPngOptions {
  double px_per_m = 120.0;  // Pixels per world metre.
  double px_per_mm = 6.0;   // Pixels per paper mm: line widths and dot sizes.
  int max_side_px = 32767;  // The image is the sheet's extent at px_per_m, cut to this (cairo's limit).

  // Throws InvalidArgument naming the field ("SheetPngOptions.px_per_m = 0, must be finite and > 0").
  void Check() const;
};

// PNG bytes of the sheet: ceil(extent · px_per_m) pixels a side, at least 1
// and at most max_side_px. Throws Error ("PNG: cannot write: …") when cairo fails.
std::string SheetToPng(const PlanSheet& sheet, const SheetPngOptions& options);

// Writes the sheet as a one-page PDF at its scale, atomically. Throws Error
// naming `path` when cairo fails or the file cannot be written.
void WriteSheetPdf(const PlanSheet& sheet, const std::filesystem::path& path);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_SHEET_CAIRO_H_
