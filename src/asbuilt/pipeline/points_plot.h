#ifndef ASBUILT_PIPELINE_POINTS_PLOT_H_
#define ASBUILT_PIPELINE_POINTS_PLOT_H_

// The survey report's top-down picture of the evidence: the measured plan's
// sheet (plan/sheet.h, default DrawingOptions) with, over it, the class
// points (black background, grey wall, orange door, blue window), the truth
// plan's walls dashed green and the rig positions as red discs.

#include <optional>
#include <string>
#include <vector>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/formats/points_file.h"

namespace asbuilt {

// PNG bytes, at most kPointsPlotSidePx a side: the plan's sheet, grown to
// hold the truth walls and the rigs (0.6 m around them) and, when neither
// plan nor truth has walls, the central 98 % of the points; at most 40000
// points are drawn (every n-th). Empty when there is nothing to draw (no
// walls, points or rigs). Throws Error as LayOutPlanSheet does for a plan
// that cannot be drawn.
inline constexpr int kPointsPlotSidePx = 640;
std::string PointsPlotPng(const std::vector<ClassPoint>& points, const Plan& plan, const std::optional<Plan>& truth,
                          const std::vector<Vec2>& rigs);

}  // namespace asbuilt

#endif  // ASBUILT_PIPELINE_POINTS_PLOT_H_
