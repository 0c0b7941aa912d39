#include "asbuilt/pipeline/points_plot.h"

#include <algorithm>
#include <array>

#include "asbuilt/plan/sheet.h"
#include "asbuilt/plan/sheet_cairo.h"

namespace asbuilt {
namespace {

constexpr double kPlotMarginM = 0.6;  // Around truth walls, rigs and points.
constexpr std::size_t kPlotMaxPoints = 40000;

// Colours by LabelClass: background, wall, door, window.
const std::array<SheetColour, 4> kPlotClassColour = {
    SheetColour{0, 0, 0}, SheetColour{150 / 255.0, 150 / 255.0, 150 / 255.0},
    SheetColour{240 / 255.0, 140 / 255.0, 40 / 255.0}, SheetColour{40 / 255.0, 160 / 255.0, 230 / 255.0}};
const SheetColour kPlotTruth{60 / 255.0, 170 / 255.0, 60 / 255.0};
const SheetColour kPlotRig{220 / 255.0, 40 / 255.0, 40 / 255.0};

// The central 98 % of the points (every n-th of at most about 5000), as
// the corners of their box; none when there are no points.
std::vector<Vec2> CentralPointsBox(const std::vector<ClassPoint>& points) {
  std::vector<double> xs, ys;
  for (std::size_t i = 0; i < points.size(); i += std::max<std::size_t>(1, points.size() / 5000)) {
    xs.push_back(points[i].position_m.x());
    ys.push_back(points[i].position_m.y());
  }
  if (xs.empty()) return {};
  auto range = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return std::pair(v[v.size() / 100], v[v.size() - 1 - v.size() / 100]);
  };
  auto [x0, x1] = range(xs);
  auto [y0, y1] = range(ys);
  return {{x0, y0}, {x1, y1}};
}

}  // namespace

std::string PointsPlotPng(const std::vector<ClassPoint>& points, const Plan& plan, const std::optional<Plan>& truth,
                          const std::vector<Vec2>& rigs) {
  const bool truth_walls = truth && !truth->walls.empty();
  if (plan.walls.empty() && !truth_walls && points.empty() && rigs.empty()) return {};
  PlanSheet sheet = LayOutPlanSheet(plan, {.title = "class points, measured plan, truth dashed, rigs"});
  const Vec2 margin = Vec2::Constant(kPlotMarginM);
  auto grow = [&](const Vec2& p) {
    sheet.Grow(p - margin);
    sheet.Grow(p + margin);
  };
  if (truth) {
    for (const PlanWall& w : truth->walls) {
      grow(w.start);
      grow(w.end);
    }
  }
  if (plan.walls.empty() && !truth_walls) {
    for (const Vec2& p : CentralPointsBox(points)) grow(p);
  }
  for (const Vec2& r : rigs) grow(r);

  // Raster: the longest side kPointsPlotSidePx; lines at their paper width,
  // at least 1 px.
  const double px_per_m = kPointsPlotSidePx / std::max({sheet.Width(), sheet.Height(), 1.0});
  const double px_per_mm = std::max(px_per_m * sheet.scale / 1000.0, 1.0);
  std::array<SheetDots, 4> by_class;
  for (std::size_t c = 0; c < by_class.size(); ++c) {
    by_class[c] = {.radius_mm = 0.8 / px_per_mm, .colour = kPlotClassColour[c]};
  }
  const std::size_t step = std::max<std::size_t>(1, points.size() / kPlotMaxPoints);
  for (std::size_t i = 0; i < points.size(); i += step) {
    by_class[static_cast<int>(points[i].label) & 3].centres.push_back(points[i].position_m.head<2>());
  }
  for (SheetDots& dots : by_class) sheet.Add(SheetLayer::kOverlay, SheetView::kPaper, std::move(dots));
  if (truth) {
    for (const PlanWall& w : truth->walls) {
      sheet.Add(SheetLayer::kOverlay, SheetView::kPaper,
                SheetPath{.points = {w.start, w.end},
                          .stroke = SheetStroke{.colour = kPlotTruth, .width_mm = 2 / px_per_mm, .dash_m = 0.1}});
    }
  }
  sheet.Add(SheetLayer::kOverlay, SheetView::kPaper,
            SheetDots{.centres = rigs, .radius_mm = 5 / px_per_mm, .colour = kPlotRig});
  return SheetToPng(sheet, {.px_per_m = px_per_m, .px_per_mm = px_per_mm, .max_side_px = kPointsPlotSidePx});
}

}  // namespace asbuilt
