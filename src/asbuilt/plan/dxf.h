#ifndef ASBUILT_PLAN_DXF_H_
#define ASBUILT_PLAN_DXF_H_

// plan.dxf — asbuilt's own DXF writer (dxflib is GPL-2.0 and cannot be
// linked with the Apache-2.0 dependencies): the model view of the plan sheet
// (plan/sheet.h) as AutoCAD 2000 (AC1015) ASCII DXF in metres ($INSUNITS 6),
// with the tables, blocks and handles CAD programs expect, on layers:
//   WALLS       inner face LINE per wall (the measured line) + solid HATCH
//               and outline of each wall piece between openings
//   DOORS       jambs, leaf, swing ARC
//   WINDOWS     jambs, wall faces and glass lines across the opening
//   DIMENSIONS  true DIMENSION entities (linear, along the wall; block-rendered *Dn) for each
//               wall's inner length and each opening's width; the dimension
//               style shows millimetres (DIMLFAC 1000)
//   TEXT        room area
// Colours and line weights come from the layer (BYLAYER); fills are grey
// (ACI 8) hatches. Checked by an independent reader (Debian python3-ezdxf)
// in plan's tests.

#include <filesystem>
#include <string>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/plan/drawing.h"
#include "asbuilt/plan/sheet.h"

namespace asbuilt {

// The DXF document of the sheet's model view: its primitives as entities in
// list order, then its dimensions, each a DIMENSION entity with its rendered
// block *D1, *D2, …; the dimension style is the sheet's. Throws
// InvalidArgument if the model view holds dots or an OVERLAY primitive.
std::string SheetToDxf(const PlanSheet& sheet);

// SheetToDxf of LayOutPlanSheet(plan, options) (drawn at options.scale).
// Throws as LayOutPlanSheet does.
std::string PlanToDxf(const Plan& plan, const DrawingOptions& options = {});
// Writes atomically; throws as PlanToDxf, naming `path`.
void WritePlanDxf(const Plan& plan, const std::filesystem::path& path, const DrawingOptions& options = {});

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_DXF_H_
