#include "asbuilt/plan/sheet_svg.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace asbuilt {
namespace {

std::string SvgHex(const SheetColour& c) {
  auto v = [](double x) { return static_cast<int>(std::lround(std::clamp(x, 0.0, 1.0) * 255)); };
  return fmt::format("#{:02x}{:02x}{:02x}", v(c.r), v(c.g), v(c.b));
}

std::string SvgEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// ` stroke="…" stroke-width="…"` (and its dashes), or ` stroke="none"`;
// `mm`: world metres per paper mm.
std::string SvgStroke(const std::optional<SheetStroke>& stroke, double mm) {
  if (!stroke) return " stroke=\"none\"";
  std::string s = fmt::format(" stroke=\"{}\" stroke-width=\"{:.4f}\"", SvgHex(stroke->colour), stroke->width_mm * mm);
  if (stroke->dash_m > 0) s += fmt::format(" stroke-dasharray=\"{:.4f}\"", stroke->dash_m);
  return s;
}

double SvgWrapPositive(double a) {
  a = std::fmod(a, 2 * kPi);
  return a < 0 ? a + 2 * kPi : a;
}

}  // namespace

std::string SheetToSvg(const PlanSheet& sheet) {
  const PaperDrawing paper = FlattenPaperView(sheet);
  const double w = sheet.Width(), h = sheet.Height();
  // Paper millimetres → world metres at this scale.
  const double mm = sheet.scale / 1000.0;
  auto X = [&](const Vec2& p) { return p.x() - sheet.lo.x(); };
  auto Y = [&](const Vec2& p) { return sheet.hi.y() - p.y(); };
  auto points = [&](const std::vector<Vec2>& ps) {
    std::string s;
    for (const Vec2& p : ps) s += fmt::format("{:.4f},{:.4f} ", X(p), Y(p));
    return s;
  };
  std::string s;
  s += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  s += fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.1f}mm\" height=\"{:.1f}mm\" "
      "viewBox=\"0 0 {:.4f} {:.4f}\">\n",
      w / mm, h / mm, w, h);
  s += "<!-- asbuilt as-built floor plan; 1 user unit = 1 m; walls are inner face lines -->\n";
  s += fmt::format("<rect x=\"0\" y=\"0\" width=\"{:.4f}\" height=\"{:.4f}\" fill=\"#ffffff\"/>\n", w, h);
  s += "<g id=\"walls\" stroke-linejoin=\"miter\">\n";
  for (const SheetPath& poly : paper.polygons) {
    s += fmt::format("<polygon points=\"{}\" fill=\"{}\"{}/>\n", points(poly.points),
                     poly.fill ? SvgHex(*poly.fill) : "none", SvgStroke(poly.stroke, mm));
  }
  if (!paper.dots.empty()) {
    s += "</g>\n<g id=\"dots\">\n";
    for (const SheetDots& dots : paper.dots) {
      for (const Vec2& p : dots.centres) {
        s += fmt::format("<circle cx=\"{:.4f}\" cy=\"{:.4f}\" r=\"{:.4f}\" fill=\"{}\"/>\n", X(p), Y(p),
                         dots.radius_mm * mm, SvgHex(dots.colour));
      }
    }
  }
  s += "</g>\n<g id=\"lines\" stroke-linecap=\"butt\">\n";
  for (const SheetPath& l : paper.lines) {
    if (l.points.size() == 2) {
      const Vec2 &a = l.points[0], &b = l.points[1];
      s += fmt::format("<line x1=\"{:.4f}\" y1=\"{:.4f}\" x2=\"{:.4f}\" y2=\"{:.4f}\"{}/>\n", X(a), Y(a), X(b), Y(b),
                       SvgStroke(l.stroke, mm));
    } else {
      s += fmt::format("<polyline points=\"{}\" fill=\"none\"{}/>\n", points(l.points), SvgStroke(l.stroke, mm));
    }
  }
  s += "</g>\n<g id=\"arcs\" fill=\"none\">\n";
  for (const SheetArc& a : paper.arcs) {
    Vec2 p0 = a.centre + a.radius_m * Vec2(std::cos(a.from_rad), std::sin(a.from_rad));
    Vec2 p1 = a.centre + a.radius_m * Vec2(std::cos(a.to_rad), std::sin(a.to_rad));
    double sweep = SvgWrapPositive(a.to_rad - a.from_rad);
    // World counter-clockwise is clockwise in SVG's y-down frame: sweep-flag 0.
    s += fmt::format("<path d=\"M {:.4f} {:.4f} A {:.4f} {:.4f} 0 {} 0 {:.4f} {:.4f}\"{}/>\n", X(p0), Y(p0), a.radius_m,
                     a.radius_m, sweep > kPi ? 1 : 0, X(p1), Y(p1), SvgStroke(a.stroke, mm));
  }
  s += "</g>\n<g id=\"text\" font-family=\"DejaVu Sans, Arial, sans-serif\">\n";
  for (const SheetText& t : paper.texts) {
    const char* anchor = t.anchor < 0.25 ? "start" : (t.anchor > 0.75 ? "end" : "middle");
    s += fmt::format(
        "<text x=\"{:.4f}\" y=\"{:.4f}\" font-size=\"{:.4f}\" text-anchor=\"{}\" fill=\"{}\"{} "
        "transform=\"rotate({:.3f} {:.4f} {:.4f})\">{}</text>\n",
        X(t.at), Y(t.at), t.height_m * 1.35, anchor, SvgHex(t.colour), t.bold ? " font-weight=\"bold\"" : "",
        -RadToDeg(t.angle_rad), X(t.at), Y(t.at), SvgEscape(t.text));
  }
  s += "</g>\n</svg>\n";
  return s;
}

}  // namespace asbuilt
