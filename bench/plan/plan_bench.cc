// bench_plan: floor plans from class points — speed (100k points) and
// accuracy (sampled rooms over many seeds; Blender rooms from exact labels).
// Writes bench/results/plan.md.

#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/formats/capture.h"
#include "asbuilt/formats/points_file.h"
#include "asbuilt/plan/label_points.h"
#include "asbuilt/plan/reconstruct.h"
#include "asbuilt/plan/sample.h"
#include "asbuilt/plan/score.h"
#include "bench/bench_util.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

Plan PolygonPlan(const std::vector<Vec2>& c) {
  Plan plan;
  int n = static_cast<int>(c.size());
  for (int i = 0; i < n; ++i)
    plan.walls.push_back({.start = c[i], .end = c[(i + 1) % n], .thickness = 0.2, .height = 2.7});
  plan.rooms.push_back({.polygon = c, .area_m2 = PolygonArea(c)});
  return plan;
}

void AddOpening(Plan& plan, OpeningKind kind, int wall, double offset, double width, double height, double sill) {
  const PlanWall& w = plan.walls[wall];
  Vec2 d = (w.end - w.start).normalized();
  plan.openings.push_back({.kind = kind,
                           .wall = wall,
                           .start = w.start + offset * d,
                           .end = w.start + (offset + width) * d,
                           .width = width,
                           .height = height,
                           .sill = sill});
}

Plan Rotated(Plan plan, double deg, Vec2 shift) {
  Eigen::Rotation2Dd r(DegToRad(deg));
  auto f = [&](const Vec2& p) -> Vec2 { return r * p + shift; };
  for (PlanWall& w : plan.walls) {
    w.start = f(w.start);
    w.end = f(w.end);
  }
  for (PlanOpening& o : plan.openings) {
    o.start = f(o.start);
    o.end = f(o.end);
  }
  for (PlanRoom& room : plan.rooms)
    for (Vec2& p : room.polygon) p = f(p);
  return plan;
}

struct Room {
  std::string name;
  Plan plan;
};

std::vector<Room> Rooms() {
  Plan rect = PolygonPlan({{0, 0}, {4.5, 0}, {4.5, 3.6}, {0, 3.6}});
  AddOpening(rect, OpeningKind::kDoor, 0, 0.4, 0.9, 2.1, 0.0);
  AddOpening(rect, OpeningKind::kWindow, 1, 0.9, 1.2, 1.4, 0.9);
  AddOpening(rect, OpeningKind::kWindow, 2, 1.2, 1.6, 1.4, 0.9);
  Plan l = PolygonPlan({{0, 0}, {6, 0}, {6, 2.6}, {2.6, 2.6}, {2.6, 5}, {0, 5}});
  AddOpening(l, OpeningKind::kDoor, 5, 0.6, 0.9, 2.1, 0.0);
  AddOpening(l, OpeningKind::kWindow, 0, 2.8, 1.5, 1.4, 0.9);
  AddOpening(l, OpeningKind::kWindow, 4, 0.7, 1.2, 1.4, 0.9);
  Plan trap = PolygonPlan({{0, 0}, {5, 0}, {4, 4}, {0, 4}});
  AddOpening(trap, OpeningKind::kDoor, 3, 1.0, 0.8, 2.0, 0.0);
  AddOpening(trap, OpeningKind::kWindow, 1, 1.0, 1.2, 1.2, 1.0);
  // Eight walls, two corners cut out; every wall visible from the centre.
  Plan u = PolygonPlan({{0, 0}, {5.5, 0}, {5.5, 1}, {7, 1}, {7, 5}, {1.2, 5}, {1.2, 4}, {0, 4}});
  AddOpening(u, OpeningKind::kDoor, 0, 3.0, 1.0, 2.1, 0.0);
  AddOpening(u, OpeningKind::kWindow, 4, 1.5, 1.5, 1.4, 0.9);
  return {{"rectangle 4.5 × 3.6", rect},
          {"rectangle rotated 23°", Rotated(rect, 23, {1.5, -2})},
          {"L, 6 walls", l},
          {"L rotated −61°", Rotated(l, -61, {-3, 4})},
          {"trapezoid (non-Manhattan)", Rotated(trap, 7, {0, 0})},
          {"8 walls, two corners cut", u}};
}

struct Pool {
  int walls_truth = 0, walls_matched = 0, walls_predicted = 0;
  int openings_truth = 0, openings_matched = 0, openings_predicted = 0;
  RelativeErrors length, width;
  std::vector<double> area;
  void Add(const PlanScore& s) {
    walls_truth += s.walls.truth;
    walls_matched += s.walls.matched;
    walls_predicted += s.walls.predicted;
    openings_truth += s.doors.truth + s.windows.truth;
    openings_matched += s.doors.matched + s.windows.matched;
    openings_predicted += s.doors.predicted + s.windows.predicted;
    length.values.insert(length.values.end(), s.wall_length.values.begin(), s.wall_length.values.end());
    width.values.insert(width.values.end(), s.opening_width.values.begin(), s.opening_width.values.end());
    if (s.area_relative_error) area.push_back(*s.area_relative_error);
  }
};

std::string Pct(std::optional<double> v) { return v ? fmt::format("{:.2f} %", 100 * *v) : "n/a"; }

std::string Row(const std::string& name, const Pool& p) {
  RelativeErrors area{p.area};
  return fmt::format("| {} | {}/{} ({}) | {} | {} | {}/{} | {} | {} | {} |\n", name, p.walls_matched, p.walls_truth,
                     p.walls_predicted, Pct(p.length.Median()), Pct(p.length.Max()), p.openings_matched,
                     p.openings_truth, Pct(p.width.Median()), Pct(p.width.Max()), Pct(area.Median()));
}

}  // namespace
}  // namespace asbuilt

int main(int argc, char** argv) {
  using namespace asbuilt;
  std::string md = "## plan — floor plans from class points\n\n";

  // ---- Speed: 100k points ----
  Room room = Rooms()[2];  // The L room.
  SampleOptions dense{.wall_points_per_m2 = 1400, .opening_points_per_m2 = 1500};
  std::vector<ClassPoint> points = SamplePointsFromPlan(room.plan, dense, 7);
  fs::path tmp = fs::temp_directory_path() / "asbuilt_bench_plan_points.txt";
  WritePoints(points, tmp);
  PlanOptions options{.viewpoint_m = SampleViewpoint(room.plan, dense)};
  PlanResult result;
  double t_plan = bench::MedianSeconds(5, [&] { result = ReconstructPlan(points, options); });
  double t_read = bench::MedianSeconds(3, [&] { ReadPoints(tmp); });
  // Reference: the least work any method must do, one pass of a weighted
  // 2-D moment accumulation over all points.
  double sink = 0;
  double t_ref = bench::MedianSeconds(5, [&] {
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    for (const ClassPoint& p : points) {
      Eigen::Vector3d h(p.position_m.x(), p.position_m.y(), 1.0);
      m += h * h.transpose() / (p.sigma_m * p.sigma_m + 1e-6);
    }
    sink += m(0, 0);
  });
  PlanScore speed_score = ScorePlan(result.plan, room.plan);
  md += fmt::format(
      "Speed: {} points (L room, noisy, 5 % outliers), {} hardware threads, single-threaded "
      "reconstruction.\n\n"
      "| step | median | vs reference |\n|---|---|---|\n"
      "| ReconstructPlan ({} walls, {} openings) | {:.3f} s | {:.0f}× |\n"
      "| ReadPoints of the same points as text ({:.1f} MB) | {:.3f} s | {:.0f}× |\n"
      "| reference: one weighted moment pass over all points | {:.4f} s | 1× |\n\n"
      "Target: plan from 100k points < 1 s — **{}** ({:.3f} s). Peak RSS {:.0f} MiB. "
      "Result: {}.\n\n",
      points.size(), std::thread::hardware_concurrency(), result.summary.walls, result.summary.openings, t_plan,
      t_plan / t_ref, fs::file_size(tmp) / 1e6, t_read, t_read / t_ref, t_ref, t_plan < 1.0 ? "met" : "NOT met", t_plan,
      bench::PeakRssMiB(), speed_score.ToString());
  fs::remove(tmp);
  (void)sink;

  // ---- Accuracy on sampled rooms ----
  const int seeds = 20;
  md += fmt::format(
      "Accuracy on rooms sampled with `SamplePointsFromPlan` ({} seeds each; noise σ = 3 mm + 4 mm·d² along the "
      "viewing ray, 10 % of that across; 5 % outliers; door/window labels 7/5 cm wider than the clear opening, as "
      "in the Blender rooms). Walls: matched/truth (predicted); errors are relative.\n\n"
      "| room | walls | length median | length max | openings | width median | width max | area median |\n"
      "|---|---|---|---|---|---|---|---|\n",
      seeds);
  Pool all;
  for (const Room& r : Rooms()) {
    Pool pool;
    for (int seed = 1; seed <= seeds; ++seed) {
      SampleOptions so;
      std::vector<ClassPoint> pts = SamplePointsFromPlan(r.plan, so, seed);
      PlanOptions po{.viewpoint_m = SampleViewpoint(r.plan, so), .seed = static_cast<std::uint64_t>(seed)};
      try {
        PlanScore s = ScorePlan(ReconstructPlan(pts, po).plan, r.plan);
        pool.Add(s);
        all.Add(s);
      } catch (const Error& e) {
        fmt::print(stderr, "{} seed {}: {}\n", r.name, seed, e.what());
      }
    }
    md += Row(r.name, pool);
  }
  md += Row("**all**", all);
  md += "\nTargets (issue 8): wall length median ≤ 1 %, max ≤ 3 %; opening width median ≤ 2 %; wall recall 100 %.\n\n";

  // ---- Blender rooms from exact labels ----
  fs::path data = fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public";
  if (fs::exists(data)) {
    md +=
        "Blender rooms (`shared/data/blender-rooms-public`), class points back-projected from the exact label "
        "and depth maps of all 12 frames (every 2nd pixel): the upper bound of the stereo survey.\n\n"
        "| room | points | time | walls | length median | length max | openings | width median | width max | "
        "area |\n|---|---|---|---|---|---|---|---|---|---|\n";
    Pool blender;
    for (const char* name : {"p01_rect_1door_2win", "p02_L_shape"}) {
      Capture capture = ReadCapture(data / name / "capture.json");
      std::vector<ClassPoint> pts = PointsFromLabelledDepth(capture, {.stride_px = 2});
      PlanOptions po{.viewpoint_m = capture.frames[0].position_m};
      PlanResult r;
      double t = bench::MedianSeconds(3, [&] { r = ReconstructPlan(pts, po); });
      PlanScore s = ScorePlan(r.plan, ReadPlan(data / name / "truth.json"));
      blender.Add(s);
      md += fmt::format("| {} | {} | {:.2f} s | {}/{} ({}) | {} | {} | {}/{} | {} | {} | {} |\n", name, pts.size(), t,
                        s.walls.matched, s.walls.truth, s.walls.predicted, Pct(s.wall_length.Median()),
                        Pct(s.wall_length.Max()), s.doors.matched + s.windows.matched, s.doors.truth + s.windows.truth,
                        Pct(s.opening_width.Median()), Pct(s.opening_width.Max()), Pct(s.area_relative_error));
      for (const OpeningMatch& m : s.opening_matches) {
        md += fmt::format("|  ↳ {} {} | | | | | | | {:.3f} m vs {:.3f} m | {:+.2f} % | |\n", OpeningKindName(m.kind),
                          m.truth, m.predicted_width_m, m.truth_width_m,
                          100 * (m.predicted_width_m - m.truth_width_m) / m.truth_width_m);
      }
    }
    md += Row("**both rooms** (pooled; columns as in the sampled table)", blender);
    md +=
        "\nOpening widths depend on how much of the casing is seen: p02's door stands open and its leaf "
        "hides part of the casing, and one of its windows is partly hidden by furniture. With every 3rd pixel "
        "(the unit test) those two deviate by up to 3.5 %; walls stay within a few millimetres.\n";
  }
  bench::WriteSection(bench::ResultsPath(argc, argv, "plan"), md);
  return 0;
}
