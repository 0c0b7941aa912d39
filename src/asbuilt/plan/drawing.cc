#include "asbuilt/plan/drawing.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <cairo-pdf.h>
#include <cairo.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/plan/dxf.h"
#include "asbuilt/plan/reconstruct.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

// ---- The sheet: what to draw, in world metres (y up). -------------------

struct Colour {
  double r = 0, g = 0, b = 0;
};
const Colour kBlack{0, 0, 0};
const Colour kWall{0.22, 0.22, 0.22};
const Colour kDim{0.1, 0.1, 0.35};
const Colour kWhite{1, 1, 1};
const Colour kGlass{0.2, 0.45, 0.75};

struct SheetPolygon {
  std::vector<Vec2> points;
  Colour fill;
  Colour stroke;
  double stroke_mm = 0.35;  // On paper.
};
struct SheetLine {
  Vec2 a, b;
  double width_mm = 0.18;
  Colour colour;
};
struct SheetArc {
  Vec2 centre;
  double radius = 0;
  double from_rad = 0, to_rad = 0;  // Counter-clockwise.
  double width_mm = 0.13;
  Colour colour;
  bool dashed = false;
};
struct SheetText {
  Vec2 at;               // Baseline anchor.
  double angle_rad = 0;  // Of the baseline, counter-clockwise.
  double height_m = 0.13;
  double anchor = 0.5;   // 0 left, 0.5 centre, 1 right.
  std::string text;
  bool bold = false;
  Colour colour;
};
struct Sheet {
  std::vector<SheetPolygon> polygons;
  std::vector<SheetLine> lines;
  std::vector<SheetArc> arcs;
  std::vector<SheetText> texts;
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 hi = Vec2::Constant(-std::numeric_limits<double>::infinity());
  double scale = 50.0;  // Drawn at 1:scale.

  void Grow(const Vec2& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool Empty() const { return !(lo.x() <= hi.x() && lo.y() <= hi.y()); }
  double Width() const { return hi.x() - lo.x(); }
  double Height() const { return hi.y() - lo.y(); }
};

// A mitre farther from the wall corner than this many wall thicknesses (two
// walls folding back on each other) is drawn as a bevel instead; 4 is SVG's
// default stroke-miterlimit, i.e. corners sharper than about 29°.
constexpr double kMitreLimit = 4.0;

double WrapPositive(double a) {
  a = std::fmod(a, 2 * kPi);
  return a < 0 ? a + 2 * kPi : a;
}
// Whether `p` lies inside `polygon` (even-odd rule).
bool Inside(const std::vector<Vec2>& polygon, const Vec2& p) {
  bool inside = false;
  for (size_t k = 0, m = polygon.size() - 1; k < polygon.size(); m = k++) {
    const Vec2& a = polygon[k];
    const Vec2& b = polygon[m];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y())) {
      inside = !inside;
    }
  }
  return inside;
}

// Largest length of the 1-2-5 series (…, 0.5, 1, 2, 5, 10, …) not above x > 0.
double RoundDown125(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {5.0, 2.0, 1.0}) {
    if (m * decade <= x * (1 + 1e-9)) return m * decade;
  }
  return decade;
}

// The next scale denominator of the 1-2-5 series above `scale` > 0
// (50 → 100 → 200 → 500 → 1000 …).
double NextCoarserScale(double scale) {
  const double base = std::pow(10.0, std::floor(std::log10(scale)) - 1);
  for (double decade : {1.0, 10.0, 100.0}) {
    for (double m : {1.0, 2.0, 5.0}) {
      if (m * decade * base > scale * (1 + 1e-9)) return m * decade * base;
    }
  }
  return 1000 * base;
}

// A scale denominator as written in "1:N": 50, 200, 1000000.
std::string ScaleText(double scale) {
  return scale == std::round(scale) && scale < 1e15 ? fmt::format("{:.0f}", scale) : fmt::format("{:g}", scale);
}

std::string FormatPoint(const Vec2& p) { return fmt::format("({}, {})", p.x(), p.y()); }

// Throws Error naming `name` unless every coordinate the drawing uses is
// finite and every opening's wall exists.
void CheckDrawable(const Plan& plan, const std::string& name) {
  auto fail = [&](const std::string& problem) {
    throw Error(fmt::format("{}: cannot draw the plan: {}", name, problem));
  };
  auto finite = [](const Vec2& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); };
  for (size_t i = 0; i < plan.walls.size(); ++i) {
    const PlanWall& w = plan.walls[i];
    if (!finite(w.start)) fail(fmt::format("walls[{}].start = {} is not finite", i, FormatPoint(w.start)));
    if (!finite(w.end)) fail(fmt::format("walls[{}].end = {} is not finite", i, FormatPoint(w.end)));
    if (w.thickness && !std::isfinite(*w.thickness)) {
      fail(fmt::format("walls[{}].thickness = {} is not finite", i, *w.thickness));
    }
  }
  for (size_t i = 0; i < plan.openings.size(); ++i) {
    const PlanOpening& op = plan.openings[i];
    if (op.wall < 0 || op.wall >= static_cast<int>(plan.walls.size())) {
      fail(fmt::format("openings[{}].wall = {} is not a wall (the plan has {})", i, op.wall, plan.walls.size()));
    }
    if (!finite(op.start)) fail(fmt::format("openings[{}].start = {} is not finite", i, FormatPoint(op.start)));
    if (!finite(op.end)) fail(fmt::format("openings[{}].end = {} is not finite", i, FormatPoint(op.end)));
  }
  for (size_t i = 0; i < plan.rooms.size(); ++i) {
    for (size_t k = 0; k < plan.rooms[i].polygon.size(); ++k) {
      const Vec2& p = plan.rooms[i].polygon[k];
      if (!finite(p)) fail(fmt::format("rooms[{}].polygon[{}] = {} is not finite", i, k, FormatPoint(p)));
    }
  }
}

// A dimension from a to b, its line offset by `offset` along `out` (unit),
// extension lines from the measured points, 45° ticks, text above the line.
// `paper`: how many times the annotation is larger in the world than at
// options.scale (scale / options.scale), so that it keeps its paper size.
void AddDimension(Sheet& sheet, const Vec2& a, const Vec2& b, const Vec2& out, double offset,
                  const std::string& text, double paper, const DrawingOptions& o) {
  const double gap = 0.05 * paper, overshoot = 0.08 * paper, tick = 0.07 * paper;
  const double text_height_m = o.text_height_m * paper;
  Vec2 da = a + offset * out, db = b + offset * out;
  Vec2 dir = (db - da).normalized();
  sheet.lines.push_back({a + gap * out, da + overshoot * out, 0.13, kDim});
  sheet.lines.push_back({b + gap * out, db + overshoot * out, 0.13, kDim});
  sheet.lines.push_back({da - overshoot * dir, db + overshoot * dir, 0.13, kDim});
  Vec2 slash = (dir + out).normalized() * tick;
  sheet.lines.push_back({da - slash, da + slash, 0.35, kDim});
  sheet.lines.push_back({db - slash, db + slash, 0.35, kDim});
  double angle = ReadableTextAngle(std::atan2(dir.y(), dir.x()));
  Vec2 up = Perp(Vec2(std::cos(angle), std::sin(angle)));
  sheet.texts.push_back({0.5 * (da + db) + 0.04 * paper * up, angle, text_height_m, 0.5, text, false, kDim});
  sheet.Grow(da + (overshoot + text_height_m + 0.05 * paper) * out);
  sheet.Grow(db + (overshoot + text_height_m + 0.05 * paper) * out);
}

// The sheet for a drawing at 1:scale. Walls and openings are drawn to their
// world size; the annotation (text, dimension spacing and ticks, scale bar,
// title block, margin) is sized for paper at options.scale and grows by
// scale / options.scale, so it keeps that paper size. The plan must have
// passed CheckDrawable.
Sheet LayOut(const Plan& plan, const DrawingOptions& o, double scale) {
  Sheet sheet;
  sheet.scale = scale;
  const double paper = scale / o.scale;
  const double text_height_m = o.text_height_m * paper;
  const int n = static_cast<int>(plan.walls.size());
  for (const PlanWall& w : plan.walls) {
    sheet.Grow(w.start);
    sheet.Grow(w.end);
  }
  for (const PlanRoom& room : plan.rooms) {
    for (const Vec2& p : room.polygon) sheet.Grow(p);
  }
  if (sheet.Empty()) sheet.Grow(Vec2::Zero());  // Nothing to draw: the title block alone.
  // Outer corners: mitre of neighbouring walls' outer faces when the walls
  // join (wall i ends where wall i+1 starts), else a square end; a bevel
  // where the mitre would reach beyond kMitreLimit thicknesses.
  auto outward = [&](int i) -> Vec2 { return -Perp((plan.walls[i].end - plan.walls[i].start).normalized()); };
  auto joined = [&](int i, int j) { return (plan.walls[i].end - plan.walls[j].start).norm() < 1e-6; };
  std::vector<Vec2> outer_start(n), outer_end(n);
  std::vector<bool> bevel_after(n, false);  // Bevel between wall i and wall i+1.
  for (int i = 0; i < n; ++i) {
    const PlanWall& w = plan.walls[i];
    outer_start[i] = w.start + DrawnThickness(w, o) * outward(i);
    outer_end[i] = w.end + DrawnThickness(w, o) * outward(i);
  }
  for (int i = 0; i < n && n >= 2; ++i) {
    int j = (i + 1) % n;
    if (!joined(i, j)) continue;
    Vec2 da = plan.walls[i].end - plan.walls[i].start, db = plan.walls[j].end - plan.walls[j].start;
    double den = Cross(da, db);
    if (den != 0) {
      double s = Cross(outer_start[j] - outer_start[i], db) / den;
      Vec2 x = outer_start[i] + s * da;
      double th =
          std::max(std::abs(DrawnThickness(plan.walls[i], o)), std::abs(DrawnThickness(plan.walls[j], o)));
      if ((x - plan.walls[i].end).norm() <= kMitreLimit * th) {  // False for NaN too.
        outer_end[i] = outer_start[j] = x;
        continue;
      }
    }
    // Collinear and going on: the square ends already meet. Folding back: bevel.
    if (da.dot(db) < 0) bevel_after[i] = true;
  }

  // Walls, cut at openings.
  for (int i = 0; i < n; ++i) {
    const PlanWall& w = plan.walls[i];
    double len = w.Length();
    if (len <= 0) continue;
    Vec2 d = (w.end - w.start) / len, out = outward(i);
    double th = DrawnThickness(w, o);
    for (auto [t0, t1] : WallPiecesBetweenOpenings(plan, i)) {
      Vec2 i0 = w.start + t0 * d, i1 = w.start + t1 * d;
      Vec2 o0 = t0 <= 1e-9 ? outer_start[i] : i0 + th * out;
      Vec2 o1 = t1 >= len - 1e-9 ? outer_end[i] : i1 + th * out;
      // Poché outlined in its own colour (no seams at the mitred corners), then the
      // cut lines of the two faces; jambs are drawn with the openings.
      sheet.polygons.push_back({{i0, i1, o1, o0}, kWall, kWall, 0.1});  // Self-coloured edge hides seams.
      sheet.lines.push_back({i0, i1, 0.5, kBlack});
      sheet.lines.push_back({o0, o1, 0.5, kBlack});
      if (t0 <= 1e-9 && !joined((i + n - 1) % n, i)) sheet.lines.push_back({i0, o0, 0.5, kBlack});
      if (t1 >= len - 1e-9 && !joined(i, (i + 1) % n)) sheet.lines.push_back({i1, o1, 0.5, kBlack});
      sheet.Grow(o0);
      sheet.Grow(o1);
    }
  }
  for (int i = 0; i < n; ++i) {
    if (!bevel_after[i]) continue;
    const Vec2& a = outer_end[i];
    const Vec2& b = outer_start[(i + 1) % n];
    sheet.polygons.push_back({{plan.walls[i].end, a, b}, kWall, kWall, 0.1});
    sheet.lines.push_back({a, b, 0.5, kBlack});
  }

  // Openings.
  for (const PlanOpening& op : plan.openings) {
    const PlanWall& w = plan.walls[op.wall];
    Vec2 d = (w.end - w.start).normalized(), out = outward(op.wall), in = -out;
    double th = DrawnThickness(w, o);
    Vec2 a = op.start, b = op.end;
    if (d.dot(b - a) < 0) std::swap(a, b);
    // Jambs.
    sheet.lines.push_back({a, a + th * out, 0.35, kBlack});
    sheet.lines.push_back({b, b + th * out, 0.35, kBlack});
    double width = (b - a).norm();
    if (op.kind == OpeningKind::kDoor) {
      // Leaf open at 90° into the room, hinged at the start jamb, and its swing.
      Vec2 leaf_end = a + width * in;
      Vec2 leaf_side = 0.04 * d;
      sheet.polygons.push_back({{a, a + leaf_side, leaf_end + leaf_side, leaf_end}, kWhite, kBlack, 0.25});
      double from = std::atan2(d.y(), d.x());
      double to = std::atan2(in.y(), in.x());
      if (WrapPositive(to - from) > kPi) std::swap(from, to);
      sheet.arcs.push_back({a, width, from, to, 0.13, kBlack, false});
      sheet.Grow(leaf_end);
    } else {
      // Wall faces across the opening and a double glass line in the middle.
      sheet.lines.push_back({a, b, 0.13, kBlack});
      sheet.lines.push_back({a + th * out, b + th * out, 0.13, kBlack});
      sheet.lines.push_back({a + (0.5 * th - 0.015) * out, b + (0.5 * th - 0.015) * out, 0.18, kGlass});
      sheet.lines.push_back({a + (0.5 * th + 0.015) * out, b + (0.5 * th + 0.015) * out, 0.18, kGlass});
    }
  }

  // Dimension strings outside each wall: a chain through the openings (when
  // it has any) and the overall inner length.
  for (int i = 0; i < n; ++i) {
    const PlanWall& w = plan.walls[i];
    double len = w.Length();
    if (len <= 0) continue;
    Vec2 d = (w.end - w.start) / len, out = outward(i);
    double th = DrawnThickness(w, o);
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
        std::string text = DimensionText(seg, op ? op->width_sigma_m : std::nullopt, o);
        AddDimension(sheet, w.start + ts[k] * d, w.start + ts[k + 1] * d, out, th + 0.4 * paper, text, paper, o);
      }
      overall_offset = th + 0.85 * paper;
    }
    AddDimension(sheet, w.start, w.end, out, overall_offset, DimensionText(len, w.length_sigma_m, o), paper, o);
  }

  // Overall dimensions of rooms that are not rectangles, in the frame of the
  // longest wall.
  for (const PlanRoom& room : plan.rooms) {
    if (room.polygon.size() <= 4 || n == 0) continue;
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
    for (const PlanWall& w : plan.walls) max_th = std::max(max_th, DrawnThickness(w, o));
    double off = max_th + 1.3 * paper;
    // Only where no single wall already gives the overall size.
    auto covered = [&](double size) {
      for (const PlanWall& w : plan.walls) {
        if (std::abs(w.Length() - size) < 0.005) return true;
      }
      return false;
    };
    if (!covered(u1 - u0)) {
      AddDimension(sheet, u0 * u + v0 * v, u1 * u + v0 * v, -v, off, DimensionText(u1 - u0, std::nullopt, o), paper,
                   o);
    }
    if (!covered(v1 - v0)) {
      AddDimension(sheet, u0 * u + v1 * v, u0 * u + v0 * v, -u, off, DimensionText(v1 - v0, std::nullopt, o), paper,
                   o);
    }
  }

  // Room area at the polygon's centroid (or the mean of its corners when the
  // centroid falls outside, as in some L shapes, or the polygon has no area).
  for (const PlanRoom& room : plan.rooms) {
    if (room.polygon.size() < 3) continue;
    Vec2 c = Vec2::Zero(), mean = Vec2::Zero();
    double a = 0;
    for (size_t k = 0; k < room.polygon.size(); ++k) {
      const Vec2& p = room.polygon[k];
      const Vec2& q = room.polygon[(k + 1) % room.polygon.size()];
      a += Cross(p, q);
      c += Cross(p, q) * (p + q);
      mean += p;
    }
    mean /= static_cast<double>(room.polygon.size());
    c /= 3 * a;
    if (!std::isfinite(c.x()) || !std::isfinite(c.y()) || !Inside(room.polygon, c)) c = mean;
    std::string area = fmt::format("{:.2f} m²", room.area_m2);
    if (o.show_uncertainty && room.area_sigma_m2) {
      area = fmt::format("{:.2f} ± {:.2f} m²", room.area_m2, std::max(0.01, *room.area_sigma_m2));
    }
    sheet.texts.push_back({c + Vec2(0, 0.05 * paper), 0, 1.4 * text_height_m, 0.5, "ROOM", true, kBlack});
    sheet.texts.push_back({c - Vec2(0, 0.22 * paper), 0, 1.2 * text_height_m, 0.5, area, false, kBlack});
  }

  // Scale bar (four alternating blocks of a round length, 0.5 m at
  // options.scale) and title block under the plan, stating the scale drawn at.
  const double block = RoundDown125(0.5 * paper);
  Vec2 base(sheet.lo.x(), sheet.lo.y() - 0.45 * paper);
  for (int k = 0; k < 4; ++k) {
    Vec2 p = base + Vec2(block * k, 0);
    sheet.polygons.push_back({{p, p + Vec2(block, 0), p + Vec2(block, 0.08 * paper), p + Vec2(0, 0.08 * paper)},
                              k % 2 ? kWhite : kBlack, kBlack, 0.18});
  }
  for (int m = 0; m <= 2; ++m) {
    sheet.texts.push_back({base + Vec2(2 * block * m, 0.14 * paper), 0, 0.8 * text_height_m, 0.5,
                           fmt::format("{:g} m", 2 * block * m), false, kBlack});
  }
  std::string note = fmt::format("dimensions in mm, inner faces; 1:{}", ScaleText(scale));
  if (scale != o.scale) note += fmt::format(" (reduced from 1:{} to fit)", ScaleText(o.scale));
  const Vec2 title_at = base + Vec2(4 * block + 0.3 * paper, 0.0);
  // Text width estimate: 0.6 em per character (UTF-8 bytes overcount).
  auto text_width = [&](const std::string& text, double height) { return 0.6 * 1.35 * height * text.size(); };
  double title_width = text_width(note, 0.8 * text_height_m);
  if (!o.title.empty()) {
    sheet.texts.push_back({title_at, 0, 1.2 * text_height_m, 0, o.title, true, kBlack});
    sheet.texts.push_back({title_at - Vec2(0, 0.2 * paper), 0, 0.8 * text_height_m, 0, note, false, kBlack});
    title_width = std::max(title_width, text_width(o.title, 1.2 * text_height_m));
  } else {
    sheet.texts.push_back({title_at, 0, 0.8 * text_height_m, 0, note, false, kBlack});
  }
  sheet.Grow(base - Vec2(0, 0.35 * paper));
  sheet.Grow(base + Vec2(std::max(6.5 * paper, title_at.x() - base.x() + title_width), 0));
  // Margin.
  sheet.lo -= Vec2(0.3, 0.3) * paper;
  sheet.hi += Vec2(0.3, 0.3) * paper;
  return sheet;
}

// The sheet at the first scale of options.scale, then the 1-2-5 series, at
// which `size(sheet)` (its longest side in the limit's unit) is within
// `limit`. Where the annotation alone exceeds the limit no scale fits; the
// sheet returned then is the coarsest tried (its size still above `limit`).
// Throws Error naming `name` if the sheet's extent overflows.
template <typename Size>
Sheet FitSheet(const Plan& plan, const DrawingOptions& o, double limit, const Size& size, const std::string& name) {
  double scale = o.scale;
  Sheet sheet = LayOut(plan, o, scale);
  double now = size(sheet);
  while (std::isfinite(now) && now > limit) {
    // The plan shrinks as 1/scale on paper, the annotation not at all, so
    // at least scale · now / limit is needed.
    double next = NextCoarserScale(scale);
    while (next < scale * now / limit) next = NextCoarserScale(next);
    Sheet coarser = LayOut(plan, o, next);
    double then = size(coarser);
    if (!(then < 0.99 * now)) break;  // Only the annotation is left.
    scale = next;
    sheet = std::move(coarser);
    now = then;
  }
  if (!std::isfinite(now)) {
    throw Error(fmt::format("{}: cannot draw the plan: its extent ({} x {} m) is not finite", name, sheet.Width(),
                            sheet.Height()));
  }
  return sheet;
}

// Longest side of the SVG/PDF page, paper mm.
double PageSideMm(const Sheet& sheet) { return std::max(sheet.Width(), sheet.Height()) * 1000.0 / sheet.scale; }

// PNG pixels per world metre at the sheet's scale (the paper resolution of
// png_px_per_m at options.scale kept).
double PngPxPerM(const Sheet& sheet, const DrawingOptions& o) { return o.png_px_per_m * o.scale / sheet.scale; }

// Logs that `path` is drawn at a coarser scale than asked for, if it is.
void WarnIfReduced(const Sheet& sheet, const DrawingOptions& o, const fs::path& path, const std::string& limit) {
  if (sheet.scale == o.scale) return;
  spdlog::warn("{}: at 1:{} the drawing would exceed {}; drawn at 1:{} (the sheet is {:.0f} x {:.0f} m)",
               path.string(), ScaleText(o.scale), limit, ScaleText(sheet.scale), sheet.Width(), sheet.Height());
}

Sheet PageSheet(const Plan& plan, const DrawingOptions& o, const std::string& name) {
  CheckDrawable(plan, name);
  Sheet sheet = FitSheet(plan, o, o.max_page_side_mm, PageSideMm, name);
  if (PageSideMm(sheet) > o.max_page_side_mm) {
    throw Error(fmt::format("{}: cannot draw the plan: its annotation alone needs {:.0f} mm, more than "
                            "DrawingOptions.max_page_side_mm = {}",
                            name, PageSideMm(sheet), o.max_page_side_mm));
  }
  return sheet;
}

Sheet PngSheet(const Plan& plan, const DrawingOptions& o, const std::string& name) {
  CheckDrawable(plan, name);
  auto side_px = [&](const Sheet& sheet) { return std::max(sheet.Width(), sheet.Height()) * PngPxPerM(sheet, o); };
  return FitSheet(plan, o, o.max_png_side_px, side_px, name);
}

// ---- SVG ------------------------------------------------------------------

std::string Hex(const Colour& c) {
  auto v = [](double x) { return static_cast<int>(std::lround(std::clamp(x, 0.0, 1.0) * 255)); };
  return fmt::format("#{:02x}{:02x}{:02x}", v(c.r), v(c.g), v(c.b));
}

std::string XmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// ---- cairo (PDF, PNG) -----------------------------------------------------

// Draws the sheet on a cairo context already scaled so that one world metre
// is `unit` device units, with y flipped.
void DrawCairo(cairo_t* cr, const Sheet& sheet, double unit, double mm_to_device) {
  auto X = [&](const Vec2& p) { return (p.x() - sheet.lo.x()) * unit; };
  auto Y = [&](const Vec2& p) { return (sheet.hi.y() - p.y()) * unit; };
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_MITER);
  for (const SheetPolygon& poly : sheet.polygons) {
    cairo_new_path(cr);
    for (size_t k = 0; k < poly.points.size(); ++k) {
      (k == 0 ? cairo_move_to : cairo_line_to)(cr, X(poly.points[k]), Y(poly.points[k]));
    }
    cairo_close_path(cr);
    cairo_set_source_rgb(cr, poly.fill.r, poly.fill.g, poly.fill.b);
    if (poly.stroke_mm <= 0) {
      cairo_fill(cr);
      continue;
    }
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, poly.stroke.r, poly.stroke.g, poly.stroke.b);
    cairo_set_line_width(cr, poly.stroke_mm * mm_to_device);
    cairo_stroke(cr);
  }
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  for (const SheetLine& l : sheet.lines) {
    cairo_set_source_rgb(cr, l.colour.r, l.colour.g, l.colour.b);
    cairo_set_line_width(cr, l.width_mm * mm_to_device);
    cairo_move_to(cr, X(l.a), Y(l.a));
    cairo_line_to(cr, X(l.b), Y(l.b));
    cairo_stroke(cr);
  }
  for (const SheetArc& a : sheet.arcs) {
    cairo_set_source_rgb(cr, a.colour.r, a.colour.g, a.colour.b);
    cairo_set_line_width(cr, a.width_mm * mm_to_device);
    cairo_new_path(cr);
    // y is flipped: counter-clockwise in the world is clockwise on the device.
    cairo_arc_negative(cr, X(a.centre), Y(a.centre), a.radius * unit, -a.from_rad, -a.to_rad);
    cairo_stroke(cr);
  }
  for (const SheetText& t : sheet.texts) {
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                           t.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, t.height_m * unit * 1.35);  // Cap height ≈ 0.74 em.
    cairo_text_extents_t ext;
    cairo_text_extents(cr, t.text.c_str(), &ext);
    cairo_save(cr);
    cairo_translate(cr, X(t.at), Y(t.at));
    cairo_rotate(cr, -t.angle_rad);
    cairo_move_to(cr, -t.anchor * ext.x_advance, 0);
    cairo_set_source_rgb(cr, t.colour.r, t.colour.g, t.colour.b);
    cairo_show_text(cr, t.text.c_str());
    cairo_restore(cr);
  }
}

void CheckCairo(cairo_status_t status, const fs::path& path) {
  if (status != CAIRO_STATUS_SUCCESS) {
    throw Error(fmt::format("{}: cannot write: {}", path.string(), cairo_status_to_string(status)));
  }
}

}  // namespace

void DrawingOptions::Check() const {
  CheckArgument(nominal_thickness_m > 0,
                fmt::format("DrawingOptions.nominal_thickness_m = {}, must be > 0", nominal_thickness_m));
  CheckArgument(std::isfinite(scale) && scale > 0,
                fmt::format("DrawingOptions.scale = {}, must be finite and > 0", scale));
  CheckArgument(png_px_per_m > 0 && png_px_per_m <= 2000,
                fmt::format("DrawingOptions.png_px_per_m = {}, must be in (0, 2000]", png_px_per_m));
  CheckArgument(text_height_m > 0, fmt::format("DrawingOptions.text_height_m = {}, must be > 0", text_height_m));
  CheckArgument(significant_sigma_m >= 0,
                fmt::format("DrawingOptions.significant_sigma_m = {}, must be >= 0", significant_sigma_m));
  CheckArgument(max_page_side_mm > 0 && max_page_side_mm <= 5080,
                fmt::format("DrawingOptions.max_page_side_mm = {}, must be in (0, 5080]", max_page_side_mm));
  CheckArgument(max_png_side_px >= 16 && max_png_side_px <= 32767,
                fmt::format("DrawingOptions.max_png_side_px = {}, must be in [16, 32767]", max_png_side_px));
}

double DrawnThickness(const PlanWall& wall, const DrawingOptions& options) {
  return wall.thickness.value_or(options.nominal_thickness_m);
}

double ReadableTextAngle(double angle) {
  while (angle > kPi / 2 + 1e-9) angle -= kPi;
  while (angle <= -kPi / 2 + 1e-9) angle += kPi;
  return angle;
}

std::string DimensionText(double length_m, std::optional<double> sigma_m, const DrawingOptions& options) {
  std::string text = fmt::format("{}", static_cast<long>(std::lround(length_m * 1000)));
  if (options.show_uncertainty && sigma_m && *sigma_m >= options.significant_sigma_m) {
    text += fmt::format(" ±{}", std::max(1L, static_cast<long>(std::lround(*sigma_m * 1000))));
  }
  return text;
}

namespace {

// The SVG document of a sheet.
std::string SvgDocument(const Sheet& sheet) {
  const double w = sheet.Width(), h = sheet.Height();
  // Paper millimetres → world metres at this scale.
  const double mm = sheet.scale / 1000.0;
  auto X = [&](const Vec2& p) { return p.x() - sheet.lo.x(); };
  auto Y = [&](const Vec2& p) { return sheet.hi.y() - p.y(); };
  std::string s;
  s += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  s += fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.1f}mm\" height=\"{:.1f}mm\" "
      "viewBox=\"0 0 {:.4f} {:.4f}\">\n",
      w / mm, h / mm, w, h);
  s += "<!-- asbuilt as-built floor plan; 1 user unit = 1 m; walls are inner face lines -->\n";
  s += fmt::format("<rect x=\"0\" y=\"0\" width=\"{:.4f}\" height=\"{:.4f}\" fill=\"#ffffff\"/>\n", w, h);
  s += "<g id=\"walls\" stroke-linejoin=\"miter\">\n";
  for (const SheetPolygon& poly : sheet.polygons) {
    std::string pts;
    for (const Vec2& p : poly.points) pts += fmt::format("{:.4f},{:.4f} ", X(p), Y(p));
    if (poly.stroke_mm <= 0) {
      s += fmt::format("<polygon points=\"{}\" fill=\"{}\" stroke=\"none\"/>\n", pts, Hex(poly.fill));
    } else {
      s += fmt::format("<polygon points=\"{}\" fill=\"{}\" stroke=\"{}\" stroke-width=\"{:.4f}\"/>\n", pts,
                       Hex(poly.fill), Hex(poly.stroke), poly.stroke_mm * mm);
    }
  }
  s += "</g>\n<g id=\"lines\" stroke-linecap=\"butt\">\n";
  for (const SheetLine& l : sheet.lines) {
    s += fmt::format("<line x1=\"{:.4f}\" y1=\"{:.4f}\" x2=\"{:.4f}\" y2=\"{:.4f}\" stroke=\"{}\" "
                     "stroke-width=\"{:.4f}\"/>\n",
                     X(l.a), Y(l.a), X(l.b), Y(l.b), Hex(l.colour), l.width_mm * mm);
  }
  s += "</g>\n<g id=\"arcs\" fill=\"none\">\n";
  for (const SheetArc& a : sheet.arcs) {
    Vec2 p0 = a.centre + a.radius * Vec2(std::cos(a.from_rad), std::sin(a.from_rad));
    Vec2 p1 = a.centre + a.radius * Vec2(std::cos(a.to_rad), std::sin(a.to_rad));
    double sweep = WrapPositive(a.to_rad - a.from_rad);
    // World counter-clockwise is clockwise in SVG's y-down frame: sweep-flag 0.
    s += fmt::format("<path d=\"M {:.4f} {:.4f} A {:.4f} {:.4f} 0 {} 0 {:.4f} {:.4f}\" stroke=\"{}\" "
                     "stroke-width=\"{:.4f}\"/>\n",
                     X(p0), Y(p0), a.radius, a.radius, sweep > kPi ? 1 : 0, X(p1), Y(p1), Hex(a.colour),
                     a.width_mm * mm);
  }
  s += "</g>\n<g id=\"text\" font-family=\"DejaVu Sans, Arial, sans-serif\">\n";
  for (const SheetText& t : sheet.texts) {
    const char* anchor = t.anchor < 0.25 ? "start" : (t.anchor > 0.75 ? "end" : "middle");
    s += fmt::format(
        "<text x=\"{:.4f}\" y=\"{:.4f}\" font-size=\"{:.4f}\" text-anchor=\"{}\" fill=\"{}\"{} "
        "transform=\"rotate({:.3f} {:.4f} {:.4f})\">{}</text>\n",
        X(t.at), Y(t.at), t.height_m * 1.35, anchor, Hex(t.colour), t.bold ? " font-weight=\"bold\"" : "",
        -RadToDeg(t.angle_rad), X(t.at), Y(t.at), XmlEscape(t.text));
  }
  s += "</g>\n</svg>\n";
  return s;
}

}  // namespace

std::string PlanToSvg(const Plan& plan, const DrawingOptions& options) {
  options.Check();
  return SvgDocument(PageSheet(plan, options, "plan"));
}

double PlanPageScale(const Plan& plan, const DrawingOptions& options) {
  options.Check();
  return PageSheet(plan, options, "plan").scale;
}

double PlanPngScale(const Plan& plan, const DrawingOptions& options) {
  options.Check();
  return PngSheet(plan, options, "plan").scale;
}

void WritePlanSvg(const Plan& plan, const fs::path& path, const DrawingOptions& options) {
  options.Check();
  Sheet sheet = PageSheet(plan, options, path.string());
  WarnIfReduced(sheet, options, path, fmt::format("{} mm", options.max_page_side_mm));
  WriteFileAtomic(path, SvgDocument(sheet));
}

void WritePlanPdf(const Plan& plan, const fs::path& path, const DrawingOptions& options) {
  options.Check();
  Sheet sheet = PageSheet(plan, options, path.string());
  WarnIfReduced(sheet, options, path, fmt::format("{} mm", options.max_page_side_mm));
  // Points per world metre at the paper scale (1 pt = 1/72 in).
  const double unit = 1000.0 / sheet.scale / 25.4 * 72.0;
  const double mm = 72.0 / 25.4;
  AtomicFile file(path);
  cairo_surface_t* surface =
      cairo_pdf_surface_create(file.temp_path().c_str(), sheet.Width() * unit, sheet.Height() * unit);
  cairo_t* cr = cairo_create(surface);
  DrawCairo(cr, sheet, unit, mm);
  cairo_show_page(cr);
  cairo_status_t status = cairo_status(cr);
  cairo_destroy(cr);
  cairo_surface_finish(surface);
  if (status == CAIRO_STATUS_SUCCESS) status = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  CheckCairo(status, path);
  file.Commit();
}

void WritePlanPng(const Plan& plan, const fs::path& path, const DrawingOptions& options) {
  options.Check();
  Sheet sheet = PngSheet(plan, options, path.string());
  WarnIfReduced(sheet, options, path, fmt::format("{} px", options.max_png_side_px));
  double unit = PngPxPerM(sheet, options);
  // Where the annotation alone is larger than the cap, a lower resolution.
  unit = std::min(unit, options.max_png_side_px / std::max(sheet.Width(), sheet.Height()));
  // Line widths: paper mm at the drawing scale, but at least ~1 px.
  const double mm = std::max(unit * sheet.scale / 1000.0, 1.0);
  auto pixels = [&](double extent_m) {
    return std::clamp(static_cast<int>(std::ceil(extent_m * unit - 1e-6)), 1, options.max_png_side_px);
  };
  const int width = pixels(sheet.Width()), height = pixels(sheet.Height());
  AtomicFile file(path);
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  cairo_t* cr = cairo_create(surface);
  DrawCairo(cr, sheet, unit, mm);
  cairo_status_t status = cairo_status(cr);
  cairo_destroy(cr);
  if (status == CAIRO_STATUS_SUCCESS) status = cairo_surface_write_to_png(surface, file.temp_path().c_str());
  cairo_surface_destroy(surface);
  CheckCairo(status, path);
  file.Commit();
}

void WritePlanFiles(const Plan& plan, const fs::path& folder, const DrawingOptions& options,
                    const IfcOptions& ifc) {
  options.Check();
  ifc.Check();
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw Error(fmt::format("{}: cannot create folder: {}", folder.string(), ec.message()));
  WritePlan(plan, folder / "plan.json");
  WritePlanSvg(plan, folder / "plan.svg", options);
  WritePlanDxf(plan, folder / "plan.dxf", options);
  WritePlanPdf(plan, folder / "plan.pdf", options);
  WritePlanPng(plan, folder / "plan.png", options);
  WritePlanIfc(plan, folder / "plan.ifc", ifc);
}

}  // namespace asbuilt
