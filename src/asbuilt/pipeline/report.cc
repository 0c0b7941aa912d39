#include "asbuilt/pipeline/report.h"

#include <cmath>

#include <fmt/format.h>

#include "asbuilt/util/base64.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {

constexpr char kStyle[] = R"css(
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;margin:0;color:#1d2330;background:#f5f6f8}
header{background:#1d2330;color:#fff;padding:18px 28px}
header h1{margin:0;font-size:22px}
header p{margin:6px 0 0;color:#c8cfdb;font-size:14px}
main{padding:10px 28px 40px;max-width:1400px}
section{background:#fff;border-radius:8px;box-shadow:0 1px 3px rgba(0,0,0,.08);padding:16px 20px;margin:18px 0}
h2{font-size:18px;margin:0 0 12px}
table{border-collapse:collapse;font-size:13px}
th,td{padding:4px 10px;border-bottom:1px solid #e3e6eb;text-align:right}
th{background:#f0f2f5;text-align:center}
td.l,th.l{text-align:left}
.good{color:#137333}.warn{color:#b06000}.bad{color:#c5221f}
.grid{display:grid;grid-template-columns:repeat(auto-fill,minmax(330px,1fr));gap:14px}
figure{margin:0}figure img{width:100%;border-radius:4px;display:block}
figcaption{font-size:12px;color:#5f6673;margin-top:4px}
.frame{display:grid;grid-template-columns:repeat(3,1fr);gap:6px;margin-bottom:12px}
.frame img{width:100%;border-radius:3px}
.plan img{max-width:100%;border:1px solid #e3e6eb;border-radius:4px;background:#fff}
.notes li{margin:3px 0}
.kpi{display:flex;gap:26px;flex-wrap:wrap}.kpi div{font-size:13px;color:#5f6673}.kpi b{display:block;font-size:22px;color:#1d2330}
)css";

std::string Img(const std::string& bytes, const char* mime, const std::string& alt) {
  if (bytes.empty()) return "<p><i>(not available)</i></p>";
  return fmt::format("<img alt=\"{}\" src=\"data:{};base64,{}\">", HtmlEscape(alt), mime, Base64Encode(bytes));
}

std::string Percent(std::optional<double> v) { return v ? fmt::format("{:.2f} %", 100.0 * *v) : "–"; }

// Class for a relative error against the method's targets (≤ 2 % good, ≤ 5 % fair).
const char* ErrorClass(double rel) { return rel <= 0.02 ? "good" : rel <= 0.05 ? "warn" : "bad"; }

std::string Sigma(const std::optional<double>& s) { return s ? fmt::format(" ± {:.3f}", *s) : ""; }

std::string WallTable(const SurveyReport& r) {
  std::string rows;
  for (std::size_t i = 0; i < r.plan.walls.size(); ++i) {
    const PlanWall& w = r.plan.walls[i];
    std::string truth_cells = "<td>–</td><td>–</td>";
    if (r.summary.score) {
      for (const WallMatch& m : r.summary.score->wall_matches) {
        if (m.predicted != static_cast<int>(i)) continue;
        double rel = m.RelativeLengthError();
        truth_cells =
            fmt::format("<td>{:.3f}</td><td class=\"{}\">{:.2f} %</td>", m.truth_length_m, ErrorClass(rel), 100 * rel);
      }
    }
    rows += fmt::format(
        "<tr><td>{}</td><td>({:.3f}, {:.3f})</td><td>({:.3f}, {:.3f})</td><td><b>{:.3f}</b>{}</td>{}</tr>\n", i,
        w.start.x(), w.start.y(), w.end.x(), w.end.y(), w.Length(), Sigma(w.length_sigma_m), truth_cells);
  }
  return fmt::format(
      "<table><tr><th>wall</th><th>start (m)</th><th>end (m)</th><th>length (m) ± 1σ</th>"
      "<th>truth (m)</th><th>error</th></tr>\n{}</table>",
      rows);
}

std::string OpeningTable(const SurveyReport& r) {
  if (r.plan.openings.empty()) return "<p>No doors or windows measured.</p>";
  std::string rows;
  for (std::size_t i = 0; i < r.plan.openings.size(); ++i) {
    const PlanOpening& o = r.plan.openings[i];
    std::string truth_cells = "<td>–</td><td>–</td>";
    if (r.summary.score) {
      for (const OpeningMatch& m : r.summary.score->opening_matches) {
        if (m.predicted != static_cast<int>(i)) continue;
        double rel = m.RelativeWidthError();
        truth_cells =
            fmt::format("<td>{:.3f}</td><td class=\"{}\">{:.2f} %</td>", m.truth_width_m, ErrorClass(rel), 100 * rel);
      }
    }
    rows +=
        fmt::format("<tr><td class=\"l\">{} {}</td><td>{}</td><td><b>{:.3f}</b>{}</td><td>{}</td><td>{}</td>{}</tr>\n",
                    OpeningKindName(o.kind), i, o.wall, o.width, Sigma(o.width_sigma_m),
                    o.height ? fmt::format("{:.3f}{}", *o.height, Sigma(o.height_sigma_m)) : "–",
                    o.sill ? fmt::format("{:.3f}{}", *o.sill, Sigma(o.sill_sigma_m)) : "–", truth_cells);
  }
  return fmt::format(
      "<table><tr><th class=\"l\">opening</th><th>wall</th><th>width (m) ± 1σ</th><th>height (m)</th>"
      "<th>sill (m)</th><th>truth width (m)</th><th>error</th></tr>\n{}</table>",
      rows);
}

std::string ScoreSection(const SurveyReport& r) {
  if (!r.summary.score) {
    return "<section><h2>Accuracy</h2><p>No truth plan was given, so nothing is scored. "
           "Pass <code>--truth truth.json</code> (or put truth.json beside capture.json) to "
           "compare.</p></section>";
  }
  const PlanScore& s = *r.summary.score;
  auto row = [](const std::string& what, const std::string& value) {
    return fmt::format("<tr><td class=\"l\">{}</td><td class=\"l\">{}</td></tr>\n", what, value);
  };
  std::string rows;
  rows += row("walls", HtmlEscape(s.walls.ToString()));
  rows += row("wall length error", HtmlEscape(s.wall_length.ToString()));
  rows += row("doors", HtmlEscape(s.doors.ToString()));
  rows += row("windows", HtmlEscape(s.windows.ToString()));
  rows += row("opening width error", HtmlEscape(s.opening_width.ToString()));
  rows += row("room area", s.area_relative_error
                               ? fmt::format("{:.2f} m² measured vs {:.2f} m² true ({:.2f} %)", *s.predicted_area_m2,
                                             *s.truth_area_m2, 100 * *s.area_relative_error)
                               : std::string("–"));
  return fmt::format(
      "<section><h2>Accuracy against the truth plan</h2><table>{}</table>"
      "<p style=\"font-size:12px;color:#5f6673\">A wall matches a truth wall when its line is within "
      "10° and its endpoints lie on average within 0.25 m of the truth line; an opening matches one "
      "of the same kind whose centre is within 0.3 m.</p></section>",
      rows);
}

}  // namespace

std::string HtmlEscape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
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
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

namespace {

// First in the report: can the plan be used, and which walls to check.
std::string VerdictSection(const PlanVerdict& v) {
  const char* css = v.verdict == Verdict::kGood ? "good" : v.verdict == Verdict::kCheck ? "warn" : "bad";
  const char* headline = v.verdict == Verdict::kGood    ? "Good: the evidence supports this plan"
                         : v.verdict == Verdict::kCheck ? "Check before use: parts of this plan rest on weak evidence"
                                                        : "Unreliable: this plan is not a measurement";
  std::string html = fmt::format(
      "<section class=\"verdict\" id=\"verdict\"><h2>Verdict</h2><p class=\"{}\"><b>{}</b> (confidence {:.2f})</p>",
      css, headline, v.confidence);
  if (!v.reasons.empty()) {
    html += "<ul>";
    for (const std::string& r : v.reasons) html += fmt::format("<li>{}</li>", HtmlEscape(r));
    html += "</ul>";
  }
  std::string walls;
  for (std::size_t w = 0; w < v.walls.size(); ++w) {
    const WallVerdict& wv = v.walls[w];
    if (wv.verdict == Verdict::kGood) continue;
    walls += fmt::format("<tr><td>{}</td><td class=\"l {}\">{}</td><td class=\"l\">{}</td></tr>", w,
                         wv.verdict == Verdict::kCheck ? "warn" : "bad", VerdictName(wv.verdict), HtmlEscape(wv.Why()));
  }
  if (!walls.empty()) {
    html += "<table><tr><th>wall</th><th class=\"l\">verdict</th><th class=\"l\">why</th></tr>" + walls + "</table>";
  }
  return html + "</section>\n";
}

}  // namespace

std::string SurveyReportHtml(const SurveyReport& r) {
  const SurveySummary& s = r.summary;
  std::string html;
  html += fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
      "<title>{}</title><style>{}</style></head><body>\n",
      HtmlEscape(r.title), kStyle);
  html +=
      fmt::format("<header><h1>{}</h1><p>{}</p></header><main>\n", HtmlEscape(r.title), HtmlEscape(s.BriefReport()));

  html += VerdictSection(s.verdict);

  // Key figures.
  double area = s.plan.area_m2;
  html += "<section><h2>Summary</h2><div class=\"kpi\">";
  html += fmt::format(
      "<div><b>{}</b>frames</div><div><b>{}</b>points</div><div><b>{}</b>walls</div>"
      "<div><b>{}</b>openings</div><div><b>{}</b>room area</div><div><b>{:.1f} s</b>total</div>",
      s.frames, s.points, r.plan.walls.size(), r.plan.openings.size(),
      area > 0 ? fmt::format("{:.2f} m²", area) : std::string("–"), s.seconds);
  if (s.score) {
    html +=
        fmt::format("<div><b>{}</b>wall length error (median)</div><div><b>{}</b>opening width error (median)</div>",
                    Percent(s.score->wall_length.Median()), Percent(s.score->opening_width.Median()));
  }
  html += fmt::format("</div><p>Labels from: {}.</p>", HtmlEscape(s.labels_source));
  if (!s.wall_cue.empty()) {
    html += fmt::format("<p>Walls: {}{}.</p>", HtmlEscape(s.wall_cue),
                        std::isfinite(s.ceiling_height_m) ? fmt::format("; ceiling height {:.3f} ± {:.3f} m",
                                                                        s.ceiling_height_m, s.ceiling_height_sigma_m)
                                                          : "");
  }
  if (!s.wall_cues.empty()) {
    html += "<details open><summary>Which cue placed each wall</summary><ul>";
    for (const std::string& c : s.wall_cues) html += fmt::format("<li>{}</li>", HtmlEscape(c));
    html += "</ul></details>";
  }
  if (!s.notes.empty()) {
    html += "<ul class=\"notes\">";
    for (const std::string& n : s.notes) html += fmt::format("<li class=\"warn\">{}</li>", HtmlEscape(n));
    html += "</ul>";
  }
  html += "</section>\n";

  // The plan and the points.
  html += "<section><h2>Floor plan</h2><div class=\"grid\" style=\"grid-template-columns:2fr 1fr\">";
  html += fmt::format(
      "<figure class=\"plan\">{}<figcaption>The measured plan (plan.svg; also plan.dxf, plan.ifc, "
      "plan.pdf, plan.json).</figcaption></figure>",
      r.plan_svg.empty() ? std::string("<p><i>(no plan could be drawn)</i></p>")
                         : Img(r.plan_svg, "image/svg+xml", "floor plan"));
  html += fmt::format(
      "<figure>{}<figcaption>Top-down view of the measured class points (wall grey, "
      "door orange, window blue), the fitted walls and the rig position{}.</figcaption></figure>",
      Img(r.points_plot_png, "image/png", "class points"), r.truth ? "; the truth plan dashed green" : "");
  html += "</div></section>\n";

  if (!r.layout_jpeg.empty()) {
    html += fmt::format(
        "<section><h2>The panorama's layout</h2><figure>{}<figcaption>The room's floor edge (red) and "
        "ceiling edge (green) found from the panorama's own edges with the segmenter's labels as a "
        "guide ({}); the views' labels were redrawn on it (docs/survey.md \"The layout of a "
        "panorama\").</figcaption></figure></section>\n",
        Img(r.layout_jpeg, "image/jpeg", "panorama layout"), HtmlEscape(r.layout_caption));
  }
  html += "<section><h2>Walls</h2>" + WallTable(r) + "</section>\n";
  html += "<section><h2>Doors and windows</h2>" + OpeningTable(r) + "</section>\n";
  html += ScoreSection(r);

  // Stage timings.
  html += "<section><h2>Stage timings</h2><table><tr><th class=\"l\">stage</th><th>seconds</th><th>share</th></tr>";
  for (const StageTiming& t : s.stages) {
    html += fmt::format("<tr><td class=\"l\">{}</td><td>{:.2f}</td><td>{:.0f} %</td></tr>", HtmlEscape(t.stage),
                        t.seconds, s.seconds > 0 ? 100 * t.seconds / s.seconds : 0.0);
  }
  html += fmt::format("<tr><th class=\"l\">total</th><th>{:.2f}</th><th></th></tr></table></section>\n", s.seconds);

  // Frames.
  html +=
      "<section><h2>Frames</h2><p>Each row: the left image, its segmentation (wall, door, window) "
      "and the disparity (warm = near, black = no match).</p>\n";
  for (const ReportFrame& f : r.frames) {
    html += fmt::format(
        "<h3 style=\"font-size:14px;margin:10px 0 4px\">frame {} · yaw {:.1f}° · {}</h3>"
        "<div class=\"frame\">{}{}{}</div>\n",
        f.index, f.yaw_deg, HtmlEscape(f.cues), Img(f.left_jpeg, "image/jpeg", "left image"),
        Img(f.overlay_jpeg, "image/jpeg", "segmentation"), Img(f.disparity_jpeg, "image/jpeg", "disparity"));
  }
  if (static_cast<int>(r.frames.size()) < s.frames) {
    html += fmt::format("<p>{} more frames not shown.</p>", s.frames - static_cast<int>(r.frames.size()));
  }
  html += "</section>\n";
  html +=
      fmt::format("<footer style=\"padding:0 28px 20px;font-size:12px;color:#5f6673\">asbuilt · capture {}</footer>",
                  HtmlEscape(r.capture_path.string()));
  html += "</main></body></html>\n";
  return html;
}

void WriteSurveyReport(const SurveyReport& report, const std::filesystem::path& path) {
  WriteFileAtomic(path, SurveyReportHtml(report));
}

}  // namespace asbuilt
