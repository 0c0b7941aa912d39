#include "asbuilt/plan/sheet.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "asbuilt/geometry/polygon.h"
#include "asbuilt/plan/reconstruct.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

const SheetColour kSheetBlack{0, 0, 0};
const SheetColour kSheetWall{0.22, 0.22, 0.22};
const SheetColour kSheetWhite{1, 1, 1};
const SheetColour kSheetGlass{0.2, 0.45, 0.75};
const SheetColour kSheetHatch{0.5, 0.5, 0.5};
const SheetColour kSheetWarning{0.75, 0.1, 0.05};  // Model view only (the DXF writes fills in grey).

// A mitre farther from the wall corner than this many wall thicknesses (two
// walls folding back on each other) is drawn as a bevel instead; 4 is SVG's
// default stroke-miterlimit, i.e. corners sharper than about 29°.
constexpr double kSheetMitreLimit = 4.0;

SheetPath SheetSegment(const Vec2& a, const Vec2& b, double width_mm, const SheetColour& colour) {
  return {.points = {a, b}, .stroke = SheetStroke{.colour = colour, .width_mm = width_mm}};
}

SheetPath SheetPolygon(std::vector<Vec2> points, const SheetColour& fill, const SheetColour& stroke, double stroke_mm) {
  return {.points = std::move(points),
          .closed = true,
          .fill = fill,
          .stroke = SheetStroke{.colour = stroke, .width_mm = stroke_mm}};
}

double SheetWrapPositive(double a) {
  a = std::fmod(a, 2 * kPi);
  return a < 0 ? a + 2 * kPi : a;
}

// Largest length of the 1-2-5 series (…, 0.5, 1, 2, 5, 10, …) not above x > 0.
double RoundDown125(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {5.0, 2.0, 1.0}) {
    if (m * decade <= x * (1 + 1e-9)) return m * decade;
  }
  return decade;
}

std::string SheetPointText(const Vec2& p) { return fmt::format("({}, {})", p.x(), p.y()); }

// What the layout steps share: the plan, the options, and the annotation's
// growth factor `paper` (scale / options.scale).
struct LayoutContext {
  const Plan& plan;
  const DrawingOptions& o;
  double paper = 1.0;
  double text_height_m = 0.13;  // Dimension text at this scale.

  int Walls() const { return static_cast<int>(plan.walls.size()); }
  Vec2 Outward(int i) const { return -Perp((plan.walls[i].end - plan.walls[i].start).normalized()); }
  // Wall i ends where wall j starts.
  bool Joined(int i, int j) const { return (plan.walls[i].end - plan.walls[j].start).norm() < 1e-6; }
};

// A dimension of `length_m` (± sigma_m when significant) from a to b.
SheetDimension MakeSheetDimension(const Vec2& a, const Vec2& b, const Vec2& out, double offset_m, double length_m,
                                  std::optional<double> sigma_m, const DrawingOptions& o) {
  std::string text = DimensionText(length_m, sigma_m, o);
  SheetDimension d{.p1 = a, .p2 = b, .out = out, .offset_m = offset_m, .value_text = text};
  if (size_t pm = text.find(" ±"); pm != std::string::npos) {
    d.value_text = text.substr(0, pm);
    d.tolerance_text = text.substr(pm);
  }
  return d;
}

// A paper-view dimension, the paper grown to hold its text.
void AddPaperDimension(PlanSheet& sheet, const LayoutContext& c, const SheetDimension& d) {
  const double reach = 0.08 * c.paper + c.text_height_m + 0.05 * c.paper;
  sheet.Grow(d.p1 + d.offset_m * d.out + reach * d.out);
  sheet.Grow(d.p2 + d.offset_m * d.out + reach * d.out);
  sheet.Add(SheetLayer::kDimensions, SheetView::kPaper, d);
}

// Outer corners of the wall bands: the mitre of neighbouring walls' outer
// faces when the walls join (wall i ends where wall i+1 starts), else a
// square end; a bevel where the mitre would reach beyond kSheetMitreLimit
// thicknesses.
struct OuterCorners {
  std::vector<Vec2> start, end;
  std::vector<bool> bevel_after;  // Bevel between wall i and wall i+1.
};
OuterCorners ComputeOuterCorners(const LayoutContext& c) {
  const Plan& plan = c.plan;
  const int n = c.Walls();
  OuterCorners corners{std::vector<Vec2>(n), std::vector<Vec2>(n), std::vector<bool>(n, false)};
  for (int i = 0; i < n; ++i) {
    const PlanWall& w = plan.walls[i];
    corners.start[i] = w.start + DrawnThickness(w, c.o) * c.Outward(i);
    corners.end[i] = w.end + DrawnThickness(w, c.o) * c.Outward(i);
  }
  for (int i = 0; i < n && n >= 2; ++i) {
    int j = (i + 1) % n;
    if (!c.Joined(i, j)) continue;
    Vec2 da = plan.walls[i].end - plan.walls[i].start, db = plan.walls[j].end - plan.walls[j].start;
    double den = Cross(da, db);
    if (den != 0) {
      double s = Cross(corners.start[j] - corners.start[i], db) / den;
      Vec2 x = corners.start[i] + s * da;
      double th = std::max(std::abs(DrawnThickness(plan.walls[i], c.o)), std::abs(DrawnThickness(plan.walls[j], c.o)));
      if ((x - plan.walls[i].end).norm() <= kSheetMitreLimit * th) {  // False for NaN too.
        corners.end[i] = corners.start[j] = x;
        continue;
      }
    }
    // Collinear and going on: the square ends already meet. Folding back: bevel.
    if (da.dot(db) < 0) corners.bevel_after[i] = true;
  }
  return corners;
}

// Walls cut at openings. Paper: poché outlined in its own colour (no seams
// at the mitred corners), the cut lines of both faces and of free ends
// (jambs come with the openings), bevels. Model: the measured inner face and
// a hatched, outlined band per piece.
void AddWalls(PlanSheet& sheet, const LayoutContext& c) {
  const Plan& plan = c.plan;
  const int n = c.Walls();
  const OuterCorners corners = ComputeOuterCorners(c);
  for (int i = 0; i < n; ++i) {
    const PlanWall& w = plan.walls[i];
    double len = w.Length();
    if (len <= 0) continue;
    Vec2 d = (w.end - w.start) / len, out = c.Outward(i);
    double th = DrawnThickness(w, c.o);
    sheet.Add(SheetLayer::kWalls, SheetView::kModel, SheetSegment(w.start, w.end, 0.5, kSheetBlack));
    for (auto [t0, t1] : WallPiecesBetweenOpenings(plan, i)) {
      Vec2 i0 = w.start + t0 * d, i1 = w.start + t1 * d;
      Vec2 o0 = t0 <= 1e-9 ? corners.start[i] : i0 + th * out;
      Vec2 o1 = t1 >= len - 1e-9 ? corners.end[i] : i1 + th * out;
      sheet.Add(SheetLayer::kWalls, SheetView::kPaper, SheetPolygon({i0, i1, o1, o0}, kSheetWall, kSheetWall, 0.1));
      sheet.Add(SheetLayer::kWalls, SheetView::kPaper, SheetSegment(i0, i1, 0.5, kSheetBlack));
      sheet.Add(SheetLayer::kWalls, SheetView::kPaper, SheetSegment(o0, o1, 0.5, kSheetBlack));
      if (t0 <= 1e-9 && !c.Joined((i + n - 1) % n, i)) {
        sheet.Add(SheetLayer::kWalls, SheetView::kPaper, SheetSegment(i0, o0, 0.5, kSheetBlack));
      }
      if (t1 >= len - 1e-9 && !c.Joined(i, (i + 1) % n)) {
        sheet.Add(SheetLayer::kWalls, SheetView::kPaper, SheetSegment(i1, o1, 0.5, kSheetBlack));
      }
      sheet.Add(SheetLayer::kWalls, SheetView::kModel,
                SheetPolygon({i0, i1, i1 + th * out, i0 + th * out}, kSheetHatch, kSheetBlack, 0.5));
      sheet.Grow(o0);
      sheet.Grow(o1);
    }
  }
  for (int i = 0; i < n; ++i) {
    if (!corners.bevel_after[i]) continue;
    const Vec2& a = corners.end[i];
    const Vec2& b = corners.start[(i + 1) % n];
    sheet.Add(SheetLayer::kWalls, SheetView::kPaper,
              SheetPolygon({plan.walls[i].end, a, b}, kSheetWall, kSheetWall, 0.1));
    sheet.Add(SheetLayer::kWalls, SheetView::kPaper, SheetSegment(a, b, 0.5, kSheetBlack));
  }
}

// Openings: jambs; doors as the leaf open at 90° into the room, hinged at
// the start jamb, and its swing (paper: a leaf of 4 cm; model: a line);
// windows as the wall faces across the opening and a double glass line.
void AddOpenings(PlanSheet& sheet, const LayoutContext& c) {
  for (const PlanOpening& op : c.plan.openings) {
    const PlanWall& w = c.plan.walls[op.wall];
    Vec2 d = (w.end - w.start).normalized(), out = c.Outward(op.wall), in = -out;
    double th = DrawnThickness(w, c.o);
    Vec2 a = op.start, b = op.end;
    if (d.dot(b - a) < 0) std::swap(a, b);
    const SheetLayer layer = op.kind == OpeningKind::kDoor ? SheetLayer::kDoors : SheetLayer::kWindows;
    sheet.Add(layer, SheetView::kBoth, SheetSegment(a, a + th * out, 0.35, kSheetBlack));
    sheet.Add(layer, SheetView::kBoth, SheetSegment(b, b + th * out, 0.35, kSheetBlack));
    double width = (b - a).norm();
    if (op.kind == OpeningKind::kDoor) {
      Vec2 leaf_end = a + width * in;
      Vec2 leaf_side = 0.04 * d;
      sheet.Add(layer, SheetView::kModel, SheetSegment(a, leaf_end, 0.25, kSheetBlack));
      sheet.Add(layer, SheetView::kPaper,
                SheetPolygon({a, a + leaf_side, leaf_end + leaf_side, leaf_end}, kSheetWhite, kSheetBlack, 0.25));
      double from = std::atan2(d.y(), d.x());
      double to = std::atan2(in.y(), in.x());
      if (SheetWrapPositive(to - from) > kPi) std::swap(from, to);
      sheet.Add(layer, SheetView::kBoth,
                SheetArc{.centre = a,
                         .radius_m = width,
                         .from_rad = from,
                         .to_rad = to,
                         .stroke = {.colour = kSheetBlack, .width_mm = 0.13}});
      sheet.Grow(leaf_end);
    } else {
      sheet.Add(layer, SheetView::kBoth, SheetSegment(a, b, 0.13, kSheetBlack));
      sheet.Add(layer, SheetView::kBoth, SheetSegment(a + th * out, b + th * out, 0.13, kSheetBlack));
      for (double side : {-0.015, 0.015}) {
        Vec2 glass = (0.5 * th + side) * out;
        sheet.Add(layer, SheetView::kBoth, SheetSegment(a + glass, b + glass, 0.18, kSheetGlass));
      }
    }
  }
}

// Dimension strings outside each wall. Paper: a chain through the openings
// (when it has any) and the overall inner length further out. Model: the
// overall inner length of each wall, then the width of each opening.
void AddWallDimensions(PlanSheet& sheet, const LayoutContext& c) {
  const Plan& plan = c.plan;
  const double paper = c.paper;
  for (int i = 0; i < c.Walls(); ++i) {
    const PlanWall& w = plan.walls[i];
    double len = w.Length();
    if (len <= 0) continue;
    Vec2 d = (w.end - w.start) / len, out = c.Outward(i);
    double th = DrawnThickness(w, c.o);
    std::vector<std::pair<double, const PlanOpening*>> marks;
    for (const PlanOpening& op : plan.openings) {
      if (op.wall != i) continue;
      double a = d.dot(op.start - w.start), b = d.dot(op.end - w.start);
      marks.push_back({std::min(a, b), &op});
      marks.push_back({std::max(a, b), nullptr});
    }
    double overall_offset = th + 0.45 * paper;
    if (!marks.empty()) {
      std::sort(marks.begin(), marks.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      std::vector<double> ts = {0.0};
      std::vector<const PlanOpening*> span_opening = {};
      for (auto [t, op] : marks) {
        ts.push_back(std::clamp(t, 0.0, len));
        span_opening.push_back(op);  // Opening that starts at this mark, or none.
      }
      ts.push_back(len);
      span_opening.push_back(nullptr);
      for (size_t k = 0; k + 1 < ts.size(); ++k) {
        double seg = ts[k + 1] - ts[k];
        if (seg < 0.005) continue;
        const PlanOpening* op = k > 0 ? span_opening[k - 1] : nullptr;
        AddPaperDimension(sheet, c,
                          MakeSheetDimension(w.start + ts[k] * d, w.start + ts[k + 1] * d, out, th + 0.4 * paper, seg,
                                             op ? op->width_sigma_m : std::nullopt, c.o));
      }
      overall_offset = th + 0.85 * paper;
    }
    // An unreliable wall's length carries the word instead of a ±.
    const bool unreliable = w.verdict && *w.verdict == "unreliable";
    SheetDimension overall = MakeSheetDimension(w.start, w.end, out, overall_offset, len, w.length_sigma_m, c.o);
    if (unreliable) overall.tolerance_text = " unreliable";
    AddPaperDimension(sheet, c, overall);
    overall.offset_m = th + 0.85 * paper;
    sheet.Add(SheetLayer::kDimensions, SheetView::kModel, overall);
  }
  for (const PlanOpening& op : plan.openings) {
    const PlanWall& w = plan.walls[op.wall];
    Vec2 d = (w.end - w.start).normalized();
    Vec2 a = op.start, b = op.end;
    if (d.dot(b - a) < 0) std::swap(a, b);
    sheet.Add(SheetLayer::kDimensions, SheetView::kModel,
              MakeSheetDimension(a, b, c.Outward(op.wall), DrawnThickness(w, c.o) + 0.4 * paper, (b - a).norm(),
                                 op.width_sigma_m, c.o));
  }
}

// Paper: overall dimensions of rooms that are not rectangles, in the frame
// of the longest wall, where no single wall already gives the size.
void AddRoomDimensions(PlanSheet& sheet, const LayoutContext& c) {
  const Plan& plan = c.plan;
  for (const PlanRoom& room : plan.rooms) {
    if (room.polygon.size() <= 4 || plan.walls.empty()) continue;
    const PlanWall* longest = &plan.walls[0];
    for (const PlanWall& w : plan.walls) {
      if (w.Length() > longest->Length()) longest = &w;
    }
    Vec2 u = (longest->end - longest->start).normalized(), v = Perp(u);
    double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
    for (const Vec2& p : room.polygon) {
      u0 = std::min(u0, u.dot(p));
      u1 = std::max(u1, u.dot(p));
      v0 = std::min(v0, v.dot(p));
      v1 = std::max(v1, v.dot(p));
    }
    double max_th = 0;
    for (const PlanWall& w : plan.walls) max_th = std::max(max_th, DrawnThickness(w, c.o));
    double off = max_th + 1.3 * c.paper;
    auto covered = [&](double size) {
      for (const PlanWall& w : plan.walls) {
        if (std::abs(w.Length() - size) < 0.005) return true;
      }
      return false;
    };
    if (!covered(u1 - u0)) {
      AddPaperDimension(sheet, c,
                        MakeSheetDimension(u0 * u + v0 * v, u1 * u + v0 * v, -v, off, u1 - u0, std::nullopt, c.o));
    }
    if (!covered(v1 - v0)) {
      AddPaperDimension(sheet, c,
                        MakeSheetDimension(u0 * u + v1 * v, u0 * u + v0 * v, -u, off, v1 - v0, std::nullopt, c.o));
    }
  }
}

// Text for the DXF's model space, which writes ASCII: the few signs our
// messages use spelled out, any other non-ASCII character as '?'.
std::string AsciiText(const std::string& utf8) {
  static const std::pair<const char*, const char*> kSpelled[] = {
      {"\u00b0", " deg"}, {"\u00b1", "+/-"}, {"\u00b2", "2"}, {"\u2014", "-"}, {"\u2013", "-"}, {"\u2019", "'"}};
  std::string out;
  for (std::size_t i = 0; i < utf8.size();) {
    const unsigned char ch = static_cast<unsigned char>(utf8[i]);
    if (ch < 0x80) {
      out += utf8[i++];
      continue;
    }
    bool spelled = false;
    for (const auto& [sign, text] : kSpelled) {
      if (utf8.compare(i, std::strlen(sign), sign) == 0) {
        out += text, i += std::strlen(sign), spelled = true;
        break;
      }
    }
    if (spelled) continue;
    out += '?';
    for (++i; i < utf8.size() && (static_cast<unsigned char>(utf8[i]) & 0xC0) == 0x80; ++i) {
    }
  }
  return out;
}

// "ROOM", or a home's room name in capitals.
std::string RoomTitle(const PlanRoom& room) {
  if (!room.name || room.name->empty()) return "ROOM";
  std::string title = *room.name;
  for (char& ch : title) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  return title;
}

// Room name and area at the polygon's centroid. Paper: "ROOM" and the area
// (± when significant), at the mean of the corners where the centroid falls
// outside (as in some L shapes) or the polygon has no area. Model: the area
// in ASCII at the centroid (the mean of the corners without area).
void AddRoomLabels(PlanSheet& sheet, const LayoutContext& c) {
  for (const PlanRoom& room : c.plan.rooms) {
    if (room.polygon.size() < 3) continue;
    Vec2 centroid = Vec2::Zero(), mean = Vec2::Zero();
    double a = 0;
    for (size_t k = 0; k < room.polygon.size(); ++k) {
      const Vec2& p = room.polygon[k];
      const Vec2& q = room.polygon[(k + 1) % room.polygon.size()];
      a += Cross(p, q);
      centroid += Cross(p, q) * (p + q);
      mean += p;
    }
    mean /= static_cast<double>(room.polygon.size());
    centroid /= 3 * a;
    const bool finite = std::isfinite(centroid.x()) && std::isfinite(centroid.y());
    const Vec2 at = finite && PointInPolygon(room.polygon, centroid) ? centroid : mean;
    const bool sigma = c.o.show_uncertainty && room.area_sigma_m2.has_value();
    const double sigma_m2 = sigma ? std::max(0.01, *room.area_sigma_m2) : 0.0;
    std::string area =
        sigma ? fmt::format("{:.2f} ± {:.2f} m²", room.area_m2, sigma_m2) : fmt::format("{:.2f} m²", room.area_m2);
    sheet.Add(
        SheetLayer::kText, SheetView::kPaper,
        SheetText{at + Vec2(0, 0.05 * c.paper), 0, 1.4 * c.text_height_m, 0.5, RoomTitle(room), true, kSheetBlack});
    sheet.Add(SheetLayer::kText, SheetView::kPaper,
              SheetText{at - Vec2(0, 0.22 * c.paper), 0, 1.2 * c.text_height_m, 0.5, area, false, kSheetBlack});
    const std::string ascii = AsciiText(room.name ? *room.name + " " + area : area);
    sheet.Add(SheetLayer::kText, SheetView::kModel,
              SheetText{finite ? centroid : mean, 0, 1.2 * c.text_height_m, 0.5, ascii, false, kSheetBlack});
  }
}

// Paper: scale bar (four alternating blocks of a round length, 0.5 m at
// options.scale) and title block under the plan, stating the scale drawn at.
void AddScaleBarAndTitle(PlanSheet& sheet, const LayoutContext& c) {
  const double paper = c.paper, text_height_m = c.text_height_m;
  const double block = RoundDown125(0.5 * paper);
  Vec2 base(sheet.lo.x(), sheet.lo.y() - 0.45 * paper);
  for (int k = 0; k < 4; ++k) {
    Vec2 p = base + Vec2(block * k, 0);
    sheet.Add(SheetLayer::kText, SheetView::kPaper,
              SheetPolygon({p, p + Vec2(block, 0), p + Vec2(block, 0.08 * paper), p + Vec2(0, 0.08 * paper)},
                           k % 2 ? kSheetWhite : kSheetBlack, kSheetBlack, 0.18));
  }
  for (int m = 0; m <= 2; ++m) {
    sheet.Add(SheetLayer::kText, SheetView::kPaper,
              SheetText{base + Vec2(2 * block * m, 0.14 * paper), 0, 0.8 * text_height_m, 0.5,
                        fmt::format("{:g} m", 2 * block * m), false, kSheetBlack});
  }
  std::string note = fmt::format("dimensions in mm, inner faces; 1:{}", SheetScaleText(sheet.scale));
  if (sheet.scale != c.o.scale) note += fmt::format(" (reduced from 1:{} to fit)", SheetScaleText(c.o.scale));
  const Vec2 title_at = base + Vec2(4 * block + 0.3 * paper, 0.0);
  // Text width estimate: 0.6 em per character (UTF-8 bytes overcount).
  auto text_width = [&](const std::string& text, double height) { return 0.6 * 1.35 * height * text.size(); };
  double title_width = text_width(note, 0.8 * text_height_m);
  if (!c.o.title.empty()) {
    sheet.Add(SheetLayer::kText, SheetView::kPaper,
              SheetText{title_at, 0, 1.2 * text_height_m, 0, c.o.title, true, kSheetBlack});
    sheet.Add(SheetLayer::kText, SheetView::kPaper,
              SheetText{title_at - Vec2(0, 0.2 * paper), 0, 0.8 * text_height_m, 0, note, false, kSheetBlack});
    title_width = std::max(title_width, text_width(c.o.title, 1.2 * text_height_m));
  } else {
    sheet.Add(SheetLayer::kText, SheetView::kPaper,
              SheetText{title_at, 0, 0.8 * text_height_m, 0, note, false, kSheetBlack});
  }
  double bottom = 0.35 * paper;
  // A plan that is not "good" says so under the title, in both views (the
  // DXF's model space too), on a layer named for it.
  if (c.plan.verdict && c.plan.verdict->verdict != "good") {
    const bool unreliable = c.plan.verdict->verdict == "unreliable";
    std::string line = unreliable ? "UNRELIABLE - NOT A MEASUREMENT" : "CHECK BEFORE USE";
    if (!c.plan.verdict->reasons.empty()) line.append(": ").append(c.plan.verdict->reasons.front());
    constexpr std::size_t kMaxBytes = 140;
    if (line.size() > kMaxBytes) {  // Cut at a character boundary.
      std::size_t cut = kMaxBytes - 3;
      while (cut > 0 && (static_cast<unsigned char>(line[cut]) & 0xC0) == 0x80) --cut;
      line.resize(cut);
      line.append("...");
    }
    const Vec2 at = title_at - Vec2(0, 0.45 * paper);
    const SheetLayer layer = unreliable ? SheetLayer::kUnreliable : SheetLayer::kCheck;
    sheet.Add(layer, SheetView::kPaper, SheetText{at, 0, text_height_m, 0, line, true, kSheetWarning});
    sheet.Add(layer, SheetView::kModel, SheetText{at, 0, text_height_m, 0, AsciiText(line), true, kSheetWarning});
    title_width = std::max(title_width, text_width(line, text_height_m));
    bottom = 0.6 * paper;
  }
  sheet.Grow(base - Vec2(0, bottom));
  sheet.Grow(base + Vec2(std::max(6.5 * paper, title_at.x() - base.x() + title_width), 0));
}

}  // namespace

std::string SheetScaleText(double scale) {
  return scale == std::round(scale) && scale < 1e15 ? fmt::format("{:.0f}", scale) : fmt::format("{:g}", scale);
}

const char* SheetLayerName(SheetLayer layer) {
  switch (layer) {
    case SheetLayer::kWalls:
      return "WALLS";
    case SheetLayer::kDoors:
      return "DOORS";
    case SheetLayer::kWindows:
      return "WINDOWS";
    case SheetLayer::kDimensions:
      return "DIMENSIONS";
    case SheetLayer::kText:
      return "TEXT";
    case SheetLayer::kOverlay:
      return "OVERLAY";
    case SheetLayer::kCheck:
      return "CHECK_BEFORE_USE";
    case SheetLayer::kUnreliable:
      return "UNRELIABLE_NOT_A_MEASUREMENT";
  }
  return "?";
}

SheetDimensionGeometry DimensionGeometry(const SheetDimension& dim, const SheetDimensionStyle& style) {
  SheetDimensionGeometry g;
  const Vec2& out = dim.out;
  g.line1 = dim.p1 + dim.offset_m * out;
  g.line2 = dim.p2 + dim.offset_m * out;
  const Vec2 dir = (dim.p2 - dim.p1).normalized();
  const double gap = style.extension_gap_m, over = style.overshoot_m;
  g.extension_and_dimension_lines = {{dim.p1 + gap * out, g.line1 + over * out},
                                     {dim.p2 + gap * out, g.line2 + over * out},
                                     {g.line1 - over * dir, g.line2 + over * dir}};
  const Vec2 slash = (dir + out).normalized() * style.tick_m;
  g.ticks = {{g.line1 - slash, g.line1 + slash}, {g.line2 - slash, g.line2 + slash}};
  g.text_angle_rad = ReadableTextAngle(std::atan2(dir.y(), dir.x()));
  const Vec2 up = Perp(Vec2(std::cos(g.text_angle_rad), std::sin(g.text_angle_rad)));
  g.text_at = 0.5 * (g.line1 + g.line2) + style.text_gap_m * up;
  return g;
}

void CheckPlanDrawable(const Plan& plan, const std::string& name) {
  auto fail = [&](const std::string& problem) {
    throw Error(fmt::format("{}: cannot draw the plan: {}", name, problem));
  };
  auto finite = [](const Vec2& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); };
  for (size_t i = 0; i < plan.walls.size(); ++i) {
    const PlanWall& w = plan.walls[i];
    if (!finite(w.start)) fail(fmt::format("walls[{}].start = {} is not finite", i, SheetPointText(w.start)));
    if (!finite(w.end)) fail(fmt::format("walls[{}].end = {} is not finite", i, SheetPointText(w.end)));
    if (w.thickness && !std::isfinite(*w.thickness)) {
      fail(fmt::format("walls[{}].thickness = {} is not finite", i, *w.thickness));
    }
  }
  for (size_t i = 0; i < plan.openings.size(); ++i) {
    const PlanOpening& op = plan.openings[i];
    if (op.wall < 0 || op.wall >= static_cast<int>(plan.walls.size())) {
      fail(fmt::format("openings[{}].wall = {} is not a wall (the plan has {})", i, op.wall, plan.walls.size()));
    }
    if (!finite(op.start)) fail(fmt::format("openings[{}].start = {} is not finite", i, SheetPointText(op.start)));
    if (!finite(op.end)) fail(fmt::format("openings[{}].end = {} is not finite", i, SheetPointText(op.end)));
  }
  for (size_t i = 0; i < plan.rooms.size(); ++i) {
    for (size_t k = 0; k < plan.rooms[i].polygon.size(); ++k) {
      const Vec2& p = plan.rooms[i].polygon[k];
      if (!finite(p)) fail(fmt::format("rooms[{}].polygon[{}] = {} is not finite", i, k, SheetPointText(p)));
    }
  }
}

PlanSheet LayOutPlanSheet(const Plan& plan, const DrawingOptions& options) {
  return LayOutPlanSheet(plan, options, options.scale);
}

PlanSheet LayOutPlanSheet(const Plan& plan, const DrawingOptions& options, double scale) {
  options.Check();
  CheckArgument(std::isfinite(scale) && scale > 0,
                fmt::format("LayOutPlanSheet: scale = {}, must be finite and > 0", scale));
  CheckPlanDrawable(plan, "plan");
  const double paper = scale / options.scale;
  const LayoutContext c{.plan = plan, .o = options, .paper = paper, .text_height_m = options.text_height_m * paper};
  PlanSheet sheet;
  sheet.scale = scale;
  const SheetDimensionStyle unit_style;
  sheet.dimension_style = {.text_height_m = c.text_height_m,
                           .extension_gap_m = unit_style.extension_gap_m * paper,
                           .overshoot_m = unit_style.overshoot_m * paper,
                           .tick_m = unit_style.tick_m * paper,
                           .text_gap_m = unit_style.text_gap_m * paper};
  for (const PlanWall& w : plan.walls) {
    sheet.Grow(w.start);
    sheet.Grow(w.end);
  }
  for (const PlanRoom& room : plan.rooms) {
    for (const Vec2& p : room.polygon) sheet.Grow(p);
  }
  if (sheet.Empty()) sheet.Grow(Vec2::Zero());  // Nothing to draw: the title block alone.
  AddWalls(sheet, c);
  AddOpenings(sheet, c);
  AddWallDimensions(sheet, c);
  AddRoomDimensions(sheet, c);
  AddRoomLabels(sheet, c);
  AddScaleBarAndTitle(sheet, c);
  // Margin.
  sheet.lo -= Vec2(0.3, 0.3) * paper;
  sheet.hi += Vec2(0.3, 0.3) * paper;
  return sheet;
}

PaperDrawing FlattenPaperView(const PlanSheet& sheet) {
  PaperDrawing paper;
  const SheetDimensionStyle& style = sheet.dimension_style;
  for (const SheetPrimitive& primitive : sheet.primitives) {
    if (!InView(primitive.views, SheetView::kPaper)) continue;
    if (const auto* path = std::get_if<SheetPath>(&primitive.shape)) {
      (path->closed ? paper.polygons : paper.lines).push_back(*path);
    } else if (const auto* arc = std::get_if<SheetArc>(&primitive.shape)) {
      paper.arcs.push_back(*arc);
    } else if (const auto* text = std::get_if<SheetText>(&primitive.shape)) {
      paper.texts.push_back(*text);
    } else if (const auto* dots = std::get_if<SheetDots>(&primitive.shape)) {
      paper.dots.push_back(*dots);
    } else if (const auto* dim = std::get_if<SheetDimension>(&primitive.shape)) {
      const SheetDimensionGeometry g = DimensionGeometry(*dim, style);
      for (const auto& [a, b] : g.extension_and_dimension_lines) {
        paper.lines.push_back(SheetSegment(a, b, style.line_mm, style.colour));
      }
      for (const auto& [a, b] : g.ticks) paper.lines.push_back(SheetSegment(a, b, style.tick_mm, style.colour));
      paper.texts.push_back({g.text_at, g.text_angle_rad, style.text_height_m, 0.5,
                             dim->value_text + dim->tolerance_text, false, style.colour});
    }
  }
  return paper;
}

}  // namespace asbuilt
