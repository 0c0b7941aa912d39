#ifndef ASBUILT_PLAN_IFC_H_
#define ASBUILT_PLAN_IFC_H_

// plan.ifc — the plan as a BIM model for Revit, ArchiCAD, BlenderBIM, FreeCAD:
// IFC4 (ISO 16739) in the STEP physical file format (ISO 10303-21), written
// by asbuilt's own small writer. Metres, radians; plan coordinates are the
// model's (world frame, +Z up, floor at z = 0).
//
//   IfcProject → IfcSite → IfcBuilding → IfcBuildingStorey
//     IfcSpace per room       body: the room polygon extruded to the room's
//                             height; Qto_SpaceBaseQuantities.NetFloorArea =
//                             area_m2
//     IfcWall per wall        placed at the wall's start, local x along the
//                             wall, local y into the room (inner face on
//                             y = 0, the wall on y ∈ [−thickness, 0]);
//                             'Axis' = the inner face line (what plan.json
//                             holds), 'Body' = its footprint (mitred at
//                             joined corners) extruded by the height;
//                             Qto_WallBaseQuantities Length/Width/Height
//     IfcOpeningElement       voids its wall (IfcRelVoidsElement): a box
//                             width × (thickness + 2 × 5 cm) × height placed
//                             at the opening's start along the wall, z = sill
//     IfcDoor / IfcWindow     fills its opening (IfcRelFillsElement):
//                             OverallWidth, OverallHeight, a thin panel body
//
// Every wall, opening and space carries the property set `Asbuilt_Dimensions`:
// its plan.json index, each dimension, its 1σ (`…Sigma`, when the plan has
// one) and, for a dimension the plan does not give (wall thickness is never
// measured by a one-sided survey), `…IsDefault` = TRUE with the value
// IfcOptions states. GlobalIds are derived from the plan's content and the
// object's index, so the same plan always gives the same file (the header's
// time stamp aside, see IfcOptions).

#include <cstdint>
#include <filesystem>
#include <string>

#include "asbuilt/formats/plan_file.h"

namespace asbuilt {

struct IfcOptions {
  // Dimensions a plan may lack; each use is marked …IsDefault in the file.
  double default_wall_thickness_m = 0.2;         // Not measured by a survey from inside the room.
  double default_wall_height_m = 2.5;            // Walls without a height.
  double default_door_height_m = 2.1;            // Doors without a height.
  double default_window_height_m = 1.2;          // Windows without a height.
  double default_window_sill_m = 0.9;            // Windows without a sill (doors: 0).
  std::string project_name = "as-built survey";  // IfcProject.Name; also site and building.
  std::string storey_name = "Ground floor";      // IfcBuildingStorey.Name.
  // FILE_NAME time stamp (ISO 8601). Empty: the current UTC time; set it for
  // byte-identical files.
  std::string time_stamp;

  void Check() const;
};

// The file's text. Throws Error ("plan: cannot model the plan: walls[2].end =
// (nan, 1) is not finite", "… openings[0].wall = 5 is not a wall of the
// plan (4 walls)") for a plan that cannot be modelled, InvalidArgument for
// bad options. A zero-length wall or a room without area is written without
// geometry (its properties kept), as the drawings draw such a plan.
std::string PlanToIfc(const Plan& plan, const IfcOptions& options = {});

// Writes PlanToIfc() atomically; errors name `path` instead of "plan".
void WritePlanIfc(const Plan& plan, const std::filesystem::path& path, const IfcOptions& options = {});

// IFC's 22-character GlobalId (IfcGloballyUniqueId) of the 128-bit number
// high·2⁶⁴ + low: base 64 with the digits 0-9 A-Z a-z _ $, most significant
// first, the first digit holding the top 2 bits.
std::string IfcGuid(std::uint64_t high, std::uint64_t low);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_IFC_H_
