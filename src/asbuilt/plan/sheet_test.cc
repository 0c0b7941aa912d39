#include "asbuilt/plan/sheet.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "asbuilt/plan/dxf.h"
#include "asbuilt/plan/sheet_cairo.h"
#include "asbuilt/plan/sheet_svg.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

Plan SheetRoom() {
  Plan plan;
  std::vector<Vec2> c = {{0, 0}, {4.5, 0}, {4.5, 3.6}, {0, 3.6}};
  for (int i = 0; i < 4; ++i) {
    plan.walls.push_back({.start = c[i], .end = c[(i + 1) % 4], .height = 2.7, .length_sigma_m = 0.004});
  }
  plan.openings.push_back({.kind = OpeningKind::kDoor, .wall = 0, .start = {0.4, 0}, .end = {1.3, 0}, .width = 0.9});
  plan.openings.push_back(
      {.kind = OpeningKind::kWindow, .wall = 1, .start = {4.5, 0.9}, .end = {4.5, 2.1}, .width = 1.2});
  plan.rooms.push_back({.polygon = c, .area_m2 = 16.2, .area_sigma_m2 = 0.03});
  return plan;
}

// Primitives of one kind in a view.
template <typename Shape>
int CountIn(const PlanSheet& sheet, SheetView view) {
  int n = 0;
  for (const SheetPrimitive& p : sheet.primitives) {
    if (InView(p.views, view) && std::holds_alternative<Shape>(p.shape)) ++n;
  }
  return n;
}

TEST(LayOutPlanSheet, PaperAndModelViewsHoldTheirOwnDimensionsAndShareTheOpenings) {
  const PlanSheet sheet = LayOutPlanSheet(SheetRoom(), {});
  EXPECT_EQ(sheet.scale, 50.0);
  // Paper: per wall with an opening a chain of 3 and the overall; 2 walls
  // without openings: the overall. Model: one per wall and per opening.
  EXPECT_EQ(CountIn<SheetDimension>(sheet, SheetView::kPaper), 2 * 4 + 2);
  EXPECT_EQ(CountIn<SheetDimension>(sheet, SheetView::kModel), 4 + 2);
  // The door swing is in both views.
  int shared_arcs = 0;
  for (const SheetPrimitive& p : sheet.primitives) {
    if (std::holds_alternative<SheetArc>(p.shape) && p.views == SheetView::kBoth) ++shared_arcs;
    if (std::holds_alternative<SheetDimension>(p.shape)) {
      EXPECT_EQ(p.layer, SheetLayer::kDimensions);
    }
  }
  EXPECT_EQ(shared_arcs, 1);
  // The paper's extent holds the plan and the annotation.
  EXPECT_LT(sheet.lo.x(), -0.2);
  EXPECT_GT(sheet.hi.x(), 4.7);
}

TEST(LayOutPlanSheet, AnnotationKeepsItsPaperSizeAtACoarserScale) {
  const PlanSheet at_50 = LayOutPlanSheet(SheetRoom(), {});
  const PlanSheet at_200 = LayOutPlanSheet(SheetRoom(), {}, 200.0);
  EXPECT_EQ(at_200.scale, 200.0);
  EXPECT_DOUBLE_EQ(at_200.dimension_style.text_height_m, 4 * at_50.dimension_style.text_height_m);
  EXPECT_DOUBLE_EQ(at_200.dimension_style.tick_m, 4 * at_50.dimension_style.tick_m);
}

TEST(LayOutPlanSheet, NonFinitePlanIsAnErrorNamingTheField) {
  Plan plan = SheetRoom();
  plan.walls[2].start.y() = std::nan("");
  try {
    LayOutPlanSheet(plan, {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "plan: cannot draw the plan: walls[2].start = (4.5, nan) is not finite");
  }
}

TEST(DimensionGeometry, TextReadsUpwardsAboveTheOffsetLine) {
  // Measured right to left: the text still reads left to right.
  const SheetDimension d{.p1 = {4, 0}, .p2 = {0, 0}, .out = {0, -1}, .offset_m = 0.5};
  const SheetDimensionGeometry g = DimensionGeometry(d, {});
  EXPECT_NEAR(g.line1.y(), -0.5, 1e-12);
  EXPECT_NEAR(g.text_angle_rad, 0.0, 1e-12);
  EXPECT_NEAR(g.text_at.y(), -0.5 + 0.04, 1e-12);
  EXPECT_EQ(g.extension_and_dimension_lines.size(), 3u);
  EXPECT_EQ(g.ticks.size(), 2u);
}

// A hand-made sheet: the serialisers draw what is in their view and nothing else.
PlanSheet HandMadeSheet() {
  PlanSheet sheet;
  sheet.Grow({0, 0});
  sheet.Grow({2, 1});
  sheet.Add(SheetLayer::kWalls, SheetView::kBoth, SheetPath{.points = {{0, 0}, {2, 0}}, .stroke = SheetStroke{}});
  sheet.Add(SheetLayer::kText, SheetView::kModel, SheetText{.at = {1, 0.5}, .text = "model only"});
  sheet.Add(SheetLayer::kOverlay, SheetView::kPaper,
            SheetPath{.points = {{0, 1}, {1, 0.5}, {2, 1}}, .stroke = SheetStroke{.dash_m = 0.1}});
  sheet.Add(SheetLayer::kOverlay, SheetView::kPaper, SheetDots{.centres = {{1, 0.25}}, .radius_mm = 1});
  return sheet;
}

TEST(SheetToSvg, DrawsThePaperViewWithDotsAndDashes) {
  const std::string svg = SheetToSvg(HandMadeSheet());
  EXPECT_NE(svg.find("<line "), std::string::npos);
  EXPECT_NE(svg.find("<polyline "), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray=\"0.1000\""), std::string::npos);
  EXPECT_NE(svg.find("<g id=\"dots\">"), std::string::npos);
  EXPECT_EQ(svg.find("model only"), std::string::npos);
}

TEST(SheetToDxf, WritesTheModelViewOnItsLayers) {
  PlanSheet sheet = HandMadeSheet();
  sheet.primitives.erase(sheet.primitives.begin() + 2, sheet.primitives.end());  // The overlays.
  const std::string dxf = SheetToDxf(sheet);
  EXPECT_NE(dxf.find("LINE\n  5\n"), std::string::npos);
  EXPECT_NE(dxf.find("\n  1\nmodel only\n"), std::string::npos);
  EXPECT_EQ(dxf.substr(dxf.size() - 8), "  0\nEOF\n");
  // Overlays are paper only.
  sheet.Add(SheetLayer::kOverlay, SheetView::kModel, SheetPath{.points = {{0, 0}, {1, 1}}, .stroke = SheetStroke{}});
  EXPECT_THROW(SheetToDxf(sheet), InvalidArgument);
}

TEST(SheetToPng, IsTheExtentAtTheResolutionWithinTheCap) {
  const std::string png = SheetToPng(HandMadeSheet(), {.px_per_m = 100, .px_per_mm = 2});
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  auto be32 = [&](size_t at) {
    uint32_t v = 0;
    for (size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<uint8_t>(png[at + k]);
    return static_cast<int>(v);
  };
  EXPECT_EQ(be32(16), 200);
  EXPECT_EQ(be32(20), 100);
  const std::string capped = SheetToPng(HandMadeSheet(), {.px_per_m = 100, .px_per_mm = 2, .max_side_px = 50});
  EXPECT_EQ(static_cast<uint8_t>(capped[19]), 50);
  EXPECT_THROW(SheetToPng(HandMadeSheet(), {.px_per_m = 0}), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
