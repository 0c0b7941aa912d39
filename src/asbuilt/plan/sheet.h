#ifndef ASBUILT_PLAN_SHEET_H_
#define ASBUILT_PLAN_SHEET_H_

// The plan sheet: a floor plan laid out once as a list of backend-neutral
// drawing primitives, which the writers serialise (sheet_svg.h: SVG;
// sheet_cairo.h: PDF and PNG; dxf.h: DXF) and previews draw over
// (pipeline/points_plot.h; mcp/plan_preview.h).
//
// Frames and units: every position and length is in world metres, x right
// and y up, as in plan.json; a text's height is world metres too (its size
// on paper at the sheet's scale). Line widths, dot sizes and dash lengths
// are paper millimetres, so they keep their look at any scale.
//
// Two drawings of the plan share the sheet, told apart by each primitive's
// views:
//   paper  the printed sheet (SVG, PDF, PNG): walls as poché with mitred
//          outer corners and cut lines, chain dimensions through the
//          openings, room name and area, scale bar and title block;
//   model  the CAD model (DXF): the measured inner face of each wall, a
//          hatch and outline per wall piece, one true dimension per wall and
//          per opening, the room area.
// Primitives both drawings show (jambs, door swings, window lines) are
// listed once, in both views. Each serialiser reads its view in list order.

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/plan/drawing.h"

namespace asbuilt {

struct SheetColour {
  double r = 0, g = 0, b = 0;  // Each in [0, 1].
};

// The CAD layer a primitive is on (the DXF writes it by SheetLayerName).
// kOverlay: preview content, never in the model view.
// kCheck and kUnreliable hold the verdict line of a plan that is not
// "good" (formats/plan_file.h PlanVerdictNote): their names say it in a CAD
// program's layer list.
enum class SheetLayer : std::uint8_t { kWalls, kDoors, kWindows, kDimensions, kText, kOverlay, kCheck, kUnreliable };
const char* SheetLayerName(
    SheetLayer layer);  // "WALLS", "DOORS", …, "OVERLAY", "CHECK_BEFORE_USE", "UNRELIABLE_NOT_A_MEASUREMENT".

// Which drawings a primitive belongs to (a bit set).
enum class SheetView : std::uint8_t { kPaper = 1, kModel = 2, kBoth = 3 };
inline bool InView(SheetView views, SheetView view) {
  return (static_cast<unsigned>(views) & static_cast<unsigned>(view)) != 0;
}

struct SheetStroke {
  SheetColour colour;
  double width_mm = 0.18;  // Paper mm.
  double dash_m = 0.0;     // Dash and gap length, world metres; 0: solid.
};

// A polyline (open) or a polygon (closed, optionally filled); at least two
// points. A fill draws solid (the DXF writes it as a HATCH).
struct SheetPath {
  std::vector<Vec2> points;
  bool closed = false;
  std::optional<SheetColour> fill;    // Closed paths only.
  std::optional<SheetStroke> stroke;  // None: fill alone.
};

// A circular arc, counter-clockwise from from_rad to to_rad (world frame).
struct SheetArc {
  Vec2 centre = Vec2::Zero();
  double radius_m = 0;
  double from_rad = 0, to_rad = 0;
  SheetStroke stroke;
};

// One line of text on its baseline.
struct SheetText {
  Vec2 at = Vec2::Zero();  // Baseline anchor.
  double angle_rad = 0;    // Of the baseline, counter-clockwise.
  double height_m = 0.13;  // Cap height.
  double anchor = 0.5;     // Where `at` is along the text: 0 left, 0.5 centre, 1 right.
  std::string text;
  bool bold = false;
  SheetColour colour;
};

// Filled discs of one colour and size (point clouds, markers).
struct SheetDots {
  std::vector<Vec2> centres;
  double radius_mm = 0.5;  // Paper mm.
  SheetColour colour;
};

// How dimensions look (the DXF's dimension style); lengths in world metres
// at the sheet's scale, widths in paper mm.
struct SheetDimensionStyle {
  double text_height_m = 0.13;    // Cap height of the text.
  double extension_gap_m = 0.05;  // From the measured point to the extension line.
  double overshoot_m = 0.08;      // Of extension and dimension lines past each other.
  double tick_m = 0.07;           // Half length of the 45° tick.
  double text_gap_m = 0.04;       // From the dimension line up to the text's baseline.
  double line_mm = 0.13;
  double tick_mm = 0.35;
  SheetColour colour{0.1, 0.1, 0.35};
};

// A linear dimension of the distance p1 → p2, its dimension line offset by
// `offset_m` along `out` (unit, pointing away from what is measured), with
// extension lines, 45° ticks and text above the line ("4500" and " ±4").
struct SheetDimension {
  Vec2 p1 = Vec2::Zero(), p2 = Vec2::Zero();
  Vec2 out = Vec2::UnitY();
  double offset_m = 0;
  std::string value_text;      // The measured length as shown ("4500").
  std::string tolerance_text;  // Appended to it ("" or " ±4").
};

// A dimension's drawn geometry under a style (what both the paper
// serialisers and the DXF's dimension blocks draw).
struct SheetDimensionGeometry {
  Vec2 line1, line2;                                                 // Dimension line ends, opposite p1 and p2.
  std::vector<std::pair<Vec2, Vec2>> extension_and_dimension_lines;  // 3 lines.
  std::vector<std::pair<Vec2, Vec2>> ticks;                          // 2 lines.
  Vec2 text_at;                                                      // Baseline centre.
  double text_angle_rad = 0;                                         // Readable: left-to-right or bottom-to-top.
};
SheetDimensionGeometry DimensionGeometry(const SheetDimension& dimension, const SheetDimensionStyle& style);

struct SheetPrimitive {
  SheetLayer layer = SheetLayer::kOverlay;
  SheetView views = SheetView::kPaper;
  std::variant<SheetPath, SheetArc, SheetText, SheetDots, SheetDimension> shape;
};

struct PlanSheet {
  std::vector<SheetPrimitive> primitives;
  // The paper's extent, world metres (the drawing and its margin).
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 hi = Vec2::Constant(-std::numeric_limits<double>::infinity());
  double scale = 50.0;  // Drawn at 1:scale.
  SheetDimensionStyle dimension_style;

  void Add(SheetLayer layer, SheetView views, decltype(SheetPrimitive::shape) shape) {
    primitives.push_back({layer, views, std::move(shape)});
  }
  void Grow(const Vec2& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool Empty() const { return !(lo.x() <= hi.x() && lo.y() <= hi.y()); }
  double Width() const { return hi.x() - lo.x(); }
  double Height() const { return hi.y() - lo.y(); }
};

// The sheet of `plan` drawn at 1:scale (options.scale by default). Walls and
// openings are drawn to their world size; the annotation (text, dimension
// spacing and ticks, scale bar, title block, margin) is sized for paper at
// options.scale and grows by scale / options.scale, so it keeps that paper
// size. Throws Error ("plan: cannot draw the plan: walls[1].end = (nan, 3.6)
// is not finite") unless every coordinate is finite and every opening's
// wall exists. An empty plan gives the scale bar and title block alone.
PlanSheet LayOutPlanSheet(const Plan& plan, const DrawingOptions& options);
PlanSheet LayOutPlanSheet(const Plan& plan, const DrawingOptions& options, double scale);

// Throws Error "`name`: cannot draw the plan: …" as LayOutPlanSheet does.
void CheckPlanDrawable(const Plan& plan, const std::string& name);

// A scale denominator as the title block writes it after "1:": 50, 200, 1000000.
std::string SheetScaleText(double scale);

// The paper view flattened for painting: dimensions drawn as their lines and
// text, then grouped by kind in the order painted (polygons, dots, lines,
// arcs, texts: fills under linework under text), each group in list order.
struct PaperDrawing {
  std::vector<SheetPath> polygons;  // Closed.
  std::vector<SheetDots> dots;
  std::vector<SheetPath> lines;  // Open.
  std::vector<SheetArc> arcs;
  std::vector<SheetText> texts;
};
PaperDrawing FlattenPaperView(const PlanSheet& sheet);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_SHEET_H_
