#ifndef ASBUILT_PLAN_SHEET_SVG_H_
#define ASBUILT_PLAN_SHEET_SVG_H_

// The paper view of a plan sheet (plan/sheet.h) as an SVG document: 1 user
// unit = 1 world metre (y flipped), the page sized in mm at the sheet's
// scale; groups "walls" (polygons), "dots" (when there are any), "lines",
// "arcs" and "text", painted in that order.

#include <string>

#include "asbuilt/plan/sheet.h"

namespace asbuilt {

std::string SheetToSvg(const PlanSheet& sheet);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_SHEET_SVG_H_
