#include "asbuilt/pipeline/demo.h"

#include <chrono>

#include <fmt/format.h>

#include "asbuilt/render/capture_render.h"
#include "asbuilt/scene/scene_json.h"
#include "asbuilt/scene/scene_text.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace fs = std::filesystem;

void DemoOptions::Check() const {
  CheckArgument(views >= 1, fmt::format("DemoOptions.views = {}, must be >= 1", views));
  CheckArgument(width_px >= 64 && height_px >= 48,
                fmt::format("DemoOptions size {}x{}, must be at least 64x48", width_px, height_px));
  CheckArgument(samples_per_pixel >= 1,
                fmt::format("DemoOptions.samples_per_pixel = {}, must be >= 1", samples_per_pixel));
  survey.Check();
}

std::string DemoSummary::BriefReport() const {
  return fmt::format("demo: {}; rendered in {:.1f} s; survey: {}", scene_brief, render_seconds, survey.BriefReport());
}

std::string ComparisonTable(const Plan& truth, const PlanScore& score) {
  std::string out = fmt::format("{:<18} {:>12} {:>12} {:>9}\n", "", "measured (m)", "true (m)", "error");
  // Walls are named by the side of the room they lie on (north = +Y).
  for (const WallMatch& m : score.wall_matches) {
    const PlanWall& t = truth.walls[m.truth];
    Vec2 mid = 0.5 * (t.start + t.end);
    Vec2 centre = Vec2::Zero();
    for (const PlanWall& w : truth.walls) centre += 0.5 * (w.start + w.end);
    centre /= std::max<std::size_t>(1, truth.walls.size());
    Vec2 d = mid - centre;
    const char* side =
        std::abs(d.x()) > std::abs(d.y()) ? (d.x() > 0 ? "east" : "west") : (d.y() > 0 ? "north" : "south");
    out += fmt::format("{:<18} {:>12.3f} {:>12.3f} {:>8.2f}%\n", fmt::format("wall {} ({})", m.truth, side),
                       m.predicted_length_m, m.truth_length_m, 100 * m.RelativeLengthError());
  }
  for (const OpeningMatch& m : score.opening_matches) {
    out += fmt::format("{:<18} {:>12.3f} {:>12.3f} {:>8.2f}%\n",
                       fmt::format("{} {} width", OpeningKindName(m.kind), m.truth), m.predicted_width_m,
                       m.truth_width_m, 100 * m.RelativeWidthError());
  }
  if (score.area_relative_error) {
    out += fmt::format("{:<18} {:>12.2f} {:>12.2f} {:>8.2f}%\n", "room area (m²)", *score.predicted_area_m2,
                       *score.truth_area_m2, 100 * *score.area_relative_error);
  }
  int missed_walls = score.walls.truth - score.walls.matched;
  int missed_openings = score.doors.truth + score.windows.truth - score.doors.matched - score.windows.matched;
  if (missed_walls > 0 || missed_openings > 0) {
    out += fmt::format("not found: {} walls, {} openings\n", missed_walls, missed_openings);
  }
  return out;
}

DemoSummary RunDemo(const fs::path& out_dir, const DemoOptions& options, const ProgressCallback& progress) {
  options.Check();
  DemoSummary summary;
  summary.out_dir = out_dir;

  SceneTextResult text = SceneFromText(options.sentence, {.seed = options.seed});
  summary.scene_brief = text.BriefReport();
  Scene scene = text.scene;
  scene.seed = options.seed;
  WriteScene(scene, out_dir / "scene.json");

  auto start = std::chrono::steady_clock::now();
  CaptureRenderOptions render;
  render.views = options.views;
  render.width_px = options.width_px;
  render.height_px = options.height_px;
  render.render.samples_per_pixel = options.samples_per_pixel;
  render.render.seed = options.seed;
  render.resume = false;
  RenderCapture(scene, out_dir / "capture", render, progress);
  summary.render_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  SurveyResult survey = RunSurvey(out_dir / "capture" / "capture.json", out_dir / "survey", options.survey, progress);
  summary.survey = survey.summary;
  if (survey.summary.score) {
    Plan truth = ReadPlan(out_dir / "capture" / "truth.json");
    summary.comparison = ComparisonTable(truth, *survey.summary.score);
  }
  return summary;
}

}  // namespace asbuilt
