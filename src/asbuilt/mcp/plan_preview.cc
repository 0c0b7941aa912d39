#include "asbuilt/mcp/plan_preview.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/plan/sheet.h"
#include "asbuilt/plan/sheet_cairo.h"
#include "asbuilt/util/error.h"

namespace asbuilt::mcp {
namespace {

SheetColour Rgb(int r, int g, int b) { return {r / 255.0, g / 255.0, b / 255.0}; }
const SheetColour kBackground = Rgb(250, 250, 250);
const SheetColour kFloor = Rgb(242, 238, 232);
const SheetColour kWall = Rgb(55, 55, 55);
const SheetColour kWindowFill = Rgb(160, 215, 240);
const SheetColour kWindowLine = Rgb(30, 90, 150);
const SheetColour kDoor = Rgb(190, 100, 40);
const SheetColour kFurnitureFill = Rgb(225, 200, 170);
const SheetColour kFurnitureLine = Rgb(140, 110, 80);
const SheetColour kRig = Rgb(210, 30, 30);
const SheetColour kLight = Rgb(250, 190, 0);
const SheetColour kText = Rgb(40, 40, 40);

// The preview's sheet: sizes in pixels (1 paper mm = 1 px), `px_per_m`
// pixels per world metre; primitives on the overlay layer, paper view.
struct Canvas {
  PlanSheet sheet;
  double px_per_m = 1;

  // World point at pixel (x right, y down from the top-left corner).
  Vec2 AtPx(double x, double y) const { return {sheet.lo.x() + x / px_per_m, sheet.hi.y() - y / px_per_m}; }
  void Add(decltype(SheetPrimitive::shape) shape) {
    sheet.Add(SheetLayer::kOverlay, SheetView::kPaper, std::move(shape));
  }
  void Fill(std::vector<Vec2> polygon, const SheetColour& colour) {
    if (polygon.size() >= 3) Add(SheetPath{.points = std::move(polygon), .closed = true, .fill = colour});
  }
  void Line(std::vector<Vec2> points, const SheetColour& colour, double width_px = 1) {
    Add(SheetPath{.points = std::move(points), .stroke = SheetStroke{.colour = colour, .width_mm = width_px}});
  }
  // Text centred on `centre` (world), `height_px` capitals.
  void Text(const std::string& text, const Vec2& centre, double height_px) {
    Add(SheetText{.at = centre - Vec2(0, 0.5 * height_px / px_per_m),
                  .height_m = height_px / px_per_m,
                  .text = text,
                  .colour = kText});
  }
};

Vec2 Rotate(const Vec2& v, double rad) {
  return {std::cos(rad) * v.x() - std::sin(rad) * v.y(), std::sin(rad) * v.x() + std::cos(rad) * v.y()};
}

// Outward normal of a wall of a counter-clockwise polygon (interior on the left).
Vec2 Outward(const Vec2& a, const Vec2& b) {
  Vec2 d = (b - a).normalized();
  return {d.y(), -d.x()};
}

// Polygon offset outwards by `t` with mitred corners (mitre capped at 4t).
std::vector<Vec2> Offset(const std::vector<Vec2>& poly, double t) {
  const std::size_t n = poly.size();
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& prev = poly[(i + n - 1) % n];
    const Vec2& cur = poly[i];
    const Vec2& next = poly[(i + 1) % n];
    if ((cur - prev).norm() < 1e-9 || (next - cur).norm() < 1e-9) {
      out.push_back(cur);
      continue;
    }
    Vec2 n1 = Outward(prev, cur), n2 = Outward(cur, next);
    Vec2 bis = n1 + n2;
    double c = bis.norm();
    if (c < 1e-6) {
      out.push_back(cur + t * n1);
      continue;
    }
    bis /= c;
    double len = t / std::max(0.25, bis.dot(n1));
    out.push_back(cur + len * bis);
  }
  return out;
}

// A circle as a closed polygon of 32 sides.
std::vector<Vec2> Circle(const Vec2& centre, double radius) {
  std::vector<Vec2> points;
  for (int k = 0; k < 32; ++k) points.push_back(centre + radius * Vec2(std::cos(k * kPi / 16), std::sin(k * kPi / 16)));
  return points;
}

void DrawOpening(Canvas& canvas, const Room& room, const Opening& o) {
  const int n = static_cast<int>(room.polygon.size());
  if (o.wall < 0 || o.wall >= n) return;
  Vec2 a = room.polygon[o.wall], b = room.polygon[(o.wall + 1) % n];
  if ((b - a).norm() < 1e-9) return;
  Vec2 d = (b - a).normalized();
  Vec2 out = Outward(a, b);
  double t = std::max(room.wall_thickness_m, 0.02);
  Vec2 p0 = a + d * o.offset_m, p1 = a + d * (o.offset_m + o.width_m);
  std::vector<Vec2> gap = {p0 - out * 0.01, p1 - out * 0.01, p1 + out * (t + 0.01), p0 + out * (t + 0.01)};
  if (o.kind == OpeningKind::kWindow) {
    canvas.Fill(gap, kWindowFill);
    for (double across : {0.0, t / 2, t}) canvas.Line({p0 + out * across, p1 + out * across}, kWindowLine);
    return;
  }
  canvas.Fill(gap, kBackground);
  // Hinge on the right seen from inside (looking along `out`, right is −d):
  // the opening's start end; on the left, its far end. The leaf swings in.
  bool right = o.hinge == HingeSide::kRight;
  Vec2 hinge = right ? p0 : p1;
  Vec2 closed = (right ? d : -d) * o.width_m;  // Hinge → other jamb.
  double open = DegToRad(o.open_deg > 0 ? o.open_deg : 90.0);
  // Rotate the closed leaf towards the inside (−out).
  double sign = Rotate(closed, 0.1).dot(-out) > 0 ? 1.0 : -1.0;
  canvas.Line({hinge, hinge + Rotate(closed, sign * open)}, kDoor, 2);
  std::vector<Vec2> arc;
  for (int i = 0; i <= 24; ++i) arc.push_back(hinge + Rotate(closed, sign * open * i / 24.0));
  canvas.Line(std::move(arc), kDoor);
}

void DrawFurniture(Canvas& canvas, const Furniture& f) {
  double yaw = DegToRad(f.yaw_deg);
  double hx = f.size_m.x() / 2, hy = f.size_m.y() / 2;
  std::vector<Vec2> box;
  for (Vec2 c : {Vec2(-hx, -hy), Vec2(hx, -hy), Vec2(hx, hy), Vec2(-hx, hy)}) {
    box.push_back(f.centre_m + Rotate(c, yaw));
  }
  canvas.Add(SheetPath{.points = box,
                       .closed = true,
                       .fill = kFurnitureFill,
                       .stroke = SheetStroke{.colour = kFurnitureLine, .width_mm = 1}});
}

// A "nice" scale bar length (1, 2 or 5 × 10^k metres) near `target_m`.
double NiceLength(double target_m) {
  double p = std::pow(10.0, std::floor(std::log10(target_m)));
  for (double k : {1.0, 2.0, 5.0, 10.0}) {
    if (k * p >= target_m) return k * p;
  }
  return 10 * p;
}

// North arrow (top right) and scale bar (bottom left), placed in pixels.
void DrawNorthAndScaleBar(Canvas& canvas, int width_px, int height_px, double span_x) {
  const double nx = width_px - 22.0;
  const Vec2 tail = canvas.AtPx(nx, 54), tip = canvas.AtPx(nx, 26);
  canvas.Line({tail, tip}, kText, 2);
  const double head = 0.35 * (tail - tip).norm();
  for (double side : {-1.0, 1.0}) {
    canvas.Line({tip, tip + head * Vec2(side * std::sqrt(0.5), -std::sqrt(0.5))}, kText, 2);
  }
  canvas.Text("N", canvas.AtPx(nx, 16), 10);
  const double bar_m = NiceLength(span_x / 5);
  const double y = height_px - 14.0, x0 = 12, x1 = 12 + bar_m * canvas.px_per_m;
  canvas.Line({canvas.AtPx(x0, y), canvas.AtPx(x1, y)}, kText, 2);
  for (double x : {x0, x1}) canvas.Line({canvas.AtPx(x, y - 4), canvas.AtPx(x, y + 4)}, kText);
  canvas.Text(fmt::format("{:g} m", bar_m), canvas.AtPx((x0 + x1) / 2, height_px - 26.0), 9);
}

}  // namespace

void PlanPreviewOptions::Check() const {
  CheckArgument(width_px >= 64 && width_px <= 4096,
                fmt::format("PlanPreviewOptions.width_px = {}, must be in 64..4096", width_px));
  CheckArgument(max_height_px >= 64 && max_height_px <= 4096,
                fmt::format("PlanPreviewOptions.max_height_px = {}, must be in 64..4096", max_height_px));
  CheckArgument(margin_px >= 0 && 2 * margin_px < std::min(width_px, max_height_px) - 16,
                fmt::format("PlanPreviewOptions.margin_px = {}, must be >= 0 and leave room "
                            "for the drawing",
                            margin_px));
}

std::string RenderPlanPreviewPng(const Scene& scene, const PlanPreviewOptions& options) {
  options.Check();
  const std::vector<Viewpoint> views = ResolveViewpoints(scene);

  // Bounds of everything drawn.
  double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;
  auto grow = [&](const Vec2& p) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return;
    min_x = std::min(min_x, p.x()), max_x = std::max(max_x, p.x());
    min_y = std::min(min_y, p.y()), max_y = std::max(max_y, p.y());
  };
  for (const Room& r : scene.rooms) {
    if (r.polygon.size() < 3) {
      for (const Vec2& p : r.polygon) grow(p);
      continue;
    }
    for (const Vec2& p : Offset(r.polygon, r.wall_thickness_m)) grow(p);
  }
  for (const Furniture& f : scene.furniture) grow(f.centre_m);
  for (const Viewpoint& v : views) grow(v.position_m.head<2>());
  for (const Light& l : scene.lights) {
    if (l.kind != LightKind::kSun) grow(l.position_m.head<2>());
  }
  if (min_x > max_x) min_x = min_y = -3, max_x = max_y = 3;
  double span_x = std::max(max_x - min_x, 1.0), span_y = std::max(max_y - min_y, 1.0);
  double cx = (min_x + max_x) / 2, cy = (min_y + max_y) / 2;
  min_x = cx - span_x / 2, max_y = cy + span_y / 2;

  // Pixels per metre, image height; the sheet is the image.
  double scale = (options.width_px - 2.0 * options.margin_px) / span_x;
  int height = static_cast<int>(std::ceil(span_y * scale)) + 2 * options.margin_px;
  if (height > options.max_height_px) {
    scale = (options.max_height_px - 2.0 * options.margin_px) / span_y;
    height = options.max_height_px;
  }
  Canvas canvas;
  canvas.px_per_m = scale;
  canvas.sheet.scale = 1000.0 / scale;  // 1 paper mm = 1 px.
  canvas.sheet.lo = Vec2(min_x - options.margin_px / scale, max_y + options.margin_px / scale - height / scale);
  canvas.sheet.hi = Vec2(canvas.sheet.lo.x() + options.width_px / scale, max_y + options.margin_px / scale);
  canvas.Fill({canvas.sheet.lo, Vec2(canvas.sheet.hi.x(), canvas.sheet.lo.y()), canvas.sheet.hi,
               Vec2(canvas.sheet.lo.x(), canvas.sheet.hi.y())},
              kBackground);

  // Rooms: walls as the band between the inner polygon and its offset.
  for (const Room& r : scene.rooms) {
    if (r.polygon.size() < 3) continue;
    canvas.Fill(Offset(r.polygon, std::max(r.wall_thickness_m, 0.02)), kWall);
    canvas.Fill(r.polygon, kFloor);
  }
  for (const Room& r : scene.rooms) {
    for (const Opening& o : r.openings) DrawOpening(canvas, r, o);
  }
  for (const Furniture& f : scene.furniture) DrawFurniture(canvas, f);
  for (const Light& l : scene.lights) {
    if (l.kind == LightKind::kSun) continue;
    canvas.Add(SheetPath{.points = Circle(l.position_m.head<2>(), 5 / scale),
                         .closed = true,
                         .stroke = SheetStroke{.colour = kLight, .width_mm = 2}});
  }

  // The rig: a dot per position, a short ray per view direction.
  const std::size_t max_rays = 360;
  SheetDots rig{.radius_mm = 4, .colour = kRig};
  for (std::size_t i = 0; i < views.size() && i < max_rays; ++i) {
    Vec2 p = views[i].position_m.head<2>();
    double yaw = DegToRad(views[i].yaw_deg);
    Vec2 forward(-std::sin(yaw), std::cos(yaw));
    if (options.view_rays) canvas.Line({p, p + forward * (28.0 / scale)}, kRig);
    rig.centres.push_back(p);
  }
  canvas.Add(std::move(rig));

  // Wall numbers and lengths, outside each wall.
  if (options.wall_labels) {
    for (const Room& r : scene.rooms) {
      const int n = static_cast<int>(r.polygon.size());
      if (n < 3) continue;
      for (int w = 0; w < n; ++w) {
        Vec2 a = r.polygon[w], b = r.polygon[(w + 1) % n];
        if ((b - a).norm() < 1e-9) continue;
        Vec2 mid = (a + b) / 2 + Outward(a, b) * (r.wall_thickness_m + 16.0 / scale);
        canvas.Text(fmt::format("{}: {:.2f} m", w, (b - a).norm()), mid, 9);
      }
    }
  }
  DrawNorthAndScaleBar(canvas, options.width_px, height, span_x);
  if (scene.rooms.empty()) {
    canvas.Text("no rooms yet: call add_room", canvas.AtPx(options.width_px / 2.0, height / 2.0), 13);
  }
  return SheetToPng(canvas.sheet, {.px_per_m = scale, .px_per_mm = 1.0, .max_side_px = 4096});
}

}  // namespace asbuilt::mcp
