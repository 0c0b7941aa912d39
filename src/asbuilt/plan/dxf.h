#ifndef ASBUILT_PLAN_DXF_H_
#define ASBUILT_PLAN_DXF_H_

// plan.dxf — asbuilt's own DXF writer (dxflib is GPL-2.0 and cannot be
// linked with the Apache-2.0 dependencies). AutoCAD 2000 (AC1015) ASCII DXF
// in metres ($INSUNITS 6), with the tables, blocks and handles CAD programs
// expect, on layers:
//   WALLS       inner face LINE per wall (the measured line) + solid HATCH
//               and outline of each wall piece between openings
//   DOORS       jambs, leaf, swing ARC
//   WINDOWS     jambs, wall faces and glass lines across the opening
//   DIMENSIONS  true DIMENSION entities (linear, along the wall) (block-rendered *Dn) for each
//               wall's inner length and each opening's width; the dimension
//               style shows millimetres (DIMLFAC 1000)
//   TEXT        room area, title
// Checked by an independent reader (Debian python3-ezdxf) in plan's tests.

#include <filesystem>
#include <string>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/plan/drawing.h"

namespace asbuilt {

std::string PlanToDxf(const Plan& plan, const DrawingOptions& options = {});
// Writes atomically.
void WritePlanDxf(const Plan& plan, const std::filesystem::path& path, const DrawingOptions& options = {});

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_DXF_H_
