#include "asbuilt/plan/reconstruct.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/plan/plan_directions.h"
#include "asbuilt/plan/plan_lines.h"
#include "asbuilt/plan/plan_openings.h"
#include "asbuilt/plan/plan_points.h"
#include "asbuilt/plan/plan_ring.h"
#include "asbuilt/plan/plan_stages.h"
#include "asbuilt/plan/plan_uncertainty.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

std::string SourceName(const std::string& points_source) { return points_source.empty() ? "plan" : points_source; }

// Fewer than 2 × min_wall_points wall points: none at all means nothing was
// labelled or matched (Error; survey fails on it, no outputs); a few are an
// input problem (InputError; `asbuilt plan` exits 1, survey reports a note
// while still writing points and report).
void RequireEnoughWallPoints(int wall_points, const PlanOptions& o, const std::string& points_source) {
  if (wall_points >= 2 * o.min_wall_points) return;
  if (wall_points == 0) {
    throw Error(
        fmt::format("{}: 0 wall points, need at least {} (2 × PlanOptions.min_wall_points): no wall was "
                    "labelled, or no wall pixel had a valid disparity",
                    SourceName(points_source), 2 * o.min_wall_points));
  }
  throw InputError(SourceName(points_source), "",
                   fmt::format("{} wall points, need at least {} (2 × PlanOptions.min_wall_points)", wall_points,
                               2 * o.min_wall_points));
}

// The points do not support a plan with fewer than two wall lines: an input
// problem (InputError), which survey reports as a note while still writing
// points and report.
void RequireTwoLines(int lines, int wall_points, const std::string& points_source) {
  if (lines >= 2) return;
  throw InputError(SourceName(points_source), "",
                   fmt::format("found {} wall line(s) in {} wall points; need at least 2 "
                               "(try a larger --epsilon-m or fewer --min-wall-points)",
                               lines, wall_points));
}

// The plan's walls (corner to corner, as high as the highest wall's 99.5th
// percentile of its points' heights when that exceeds 1 m) and its room
// polygon, with their ±. A polygon running clockwise (the viewpoint was
// outside the room's kernel) is reported with its area's absolute value
// and a warning.
Plan PlanFromRing(const Ring& ring, const RingSigmas& sigmas, const std::vector<Vec2>* given_corners) {
  const std::vector<Vec2> corners = given_corners ? *given_corners : RingCorners(ring.walls);
  const int n = static_cast<int>(corners.size());
  double height = 0;
  for (const WallLine& l : ring.walls) height = std::max(height, l.z_top);
  Plan plan;
  for (int i = 0; i < n; ++i) {
    PlanWall w;
    w.start = corners[i];
    w.end = corners[(i + 1) % n];
    if (height > 1.0) w.height = height;
    w.length_sigma_m = sigmas.wall_length_m[i];
    plan.walls.push_back(w);
  }
  PlanRoom room;
  room.polygon = corners;
  room.area_m2 = PolygonArea(corners);
  if (room.area_m2 < 0) {
    spdlog::warn("plan: room polygon runs clockwise around the viewpoint; the ordering may be wrong");
    room.area_m2 = -room.area_m2;
  }
  room.area_sigma_m2 = sigmas.area_m2;
  plan.rooms.push_back(room);
  return plan;
}

// Wall inliers, outliers and the 1/σ²-weighted rms residual of the ring's
// members about their lines.
void SummarizeResiduals(const WallPoints& walls, const Ring& ring, PlanSummary& s) {
  double chi = 0, sw = 0;
  int inl = 0;
  for (const WallLine& l : ring.walls) {
    for (int k : l.members) {
      double r = l.Distance(walls.points[k].p);
      chi += walls.points[k].w * r * r;
      sw += walls.points[k].w;
      ++inl;
    }
  }
  s.wall_inliers = inl;
  s.outliers = s.wall_points - inl;
  s.rms_residual_m = sw > 0 ? std::sqrt(chi / sw) : -1;
}

}  // namespace

std::string PlanSummary::BriefReport() const {
  std::vector<double> sorted;
  for (double d : dominant_directions_deg) {
    d = std::fmod(std::fmod(d, 180.0) + 180.0, 180.0);
    sorted.push_back(d >= 179.95 ? 0.0 : d);
  }
  std::sort(sorted.begin(), sorted.end());
  std::string dirs;
  for (double d : sorted) dirs += fmt::format("{}{:.1f}°", dirs.empty() ? "" : "/", d);
  return fmt::format(
      "{} walls ({} inferred), {} openings{}, {}, {}, {}directions {}, {} of {} wall points on walls, rms {}, "
      "{:.3f} s",
      walls, inferred_walls, openings,
      door_leaves > 0 ? fmt::format(" ({} door width(s) from an open leaf)", door_leaves) : std::string(),
      closed ? "closed" : "NOT closed", area_m2 >= 0 ? fmt::format("{:.2f} m²", area_m2) : std::string("no area"),
      manhattan ? "Manhattan frame, " : "", dirs.empty() ? "none" : dirs, wall_inliers, wall_points,
      rms_residual_m >= 0 ? fmt::format("{:.3f} m", rms_residual_m) : std::string("n/a"), seconds);
}

std::vector<std::pair<double, double>> WallPiecesBetweenOpenings(const Plan& plan, int wall) {
  const PlanWall& w = plan.walls.at(wall);
  double length = w.Length();
  Vec2 dir = (w.end - w.start) / std::max(length, 1e-12);
  std::vector<std::pair<double, double>> cuts;
  for (const PlanOpening& o : plan.openings) {
    if (o.wall != wall) continue;
    double a = dir.dot(o.start - w.start), b = dir.dot(o.end - w.start);
    if (a > b) std::swap(a, b);
    cuts.push_back({std::clamp(a, 0.0, length), std::clamp(b, 0.0, length)});
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<std::pair<double, double>> pieces;
  double at = 0;
  for (auto [a, b] : cuts) {
    if (a > at + 1e-9) pieces.push_back({at, a});
    at = std::max(at, b);
  }
  if (length > at + 1e-9) pieces.push_back({at, length});
  return pieces;
}

RingStages FitRingStages(const std::vector<ClassPoint>& points, const PlanOptions& options,
                         const std::string& points_source) {
  RingStages out;
  PlanSummary& s = out.summary;
  s.input_points = static_cast<int>(points.size());

  // 1. Planarize.
  out.planar = PlanarizePoints(points, options);
  s.wall_points = static_cast<int>(out.planar.walls.points.size());
  s.door_points = out.planar.door_points;
  s.window_points = out.planar.window_points;
  RequireEnoughWallPoints(s.wall_points, options, points_source);

  // 2. Lines.
  FittedLines fitted = FindWallLines(out.planar.walls, options);
  s.lines_found = fitted.ransac_lines;

  // 3. Dominant directions, Manhattan frame, snapping.
  SnappedLines snapped = SnapToDominantDirections(out.planar.walls, std::move(fitted.lines), options);
  s.manhattan = snapped.frame.manhattan;
  for (const Direction& d : snapped.frame.directions) s.dominant_directions_deg.push_back(RadToDeg(d.theta));
  RequireTwoLines(static_cast<int>(snapped.lines.size()), s.wall_points, points_source);
  out.frame = snapped.frame;

  // 4. Close the room around the viewpoint.
  out.ring = CloseRoom(out.planar.walls, std::move(snapped.lines), out.planar.vertices, snapped.frame, options);
  return out;
}

PlanResult PlanFromRingStages(const RingStages& stages, const Ring& ring, const PlanOptions& options,
                              const std::vector<Vec2>* corners, bool skip_openings) {
  PlanResult result;
  PlanSummary& s = result.summary;
  s = stages.summary;
  s.inferred_walls = ring.inferred_walls;
  s.closed = ring.walls.size() >= 3;
  s.wall_inferred.clear();
  for (const WallLine& l : ring.walls) s.wall_inferred.push_back(l.inferred);

  // 5. Walls and room with their ±.
  result.plan = PlanFromRing(ring, PropagateRingSigmas(stages.planar.walls, ring.walls, options), corners);
  s.walls = static_cast<int>(result.plan.walls.size());
  s.area_m2 = result.plan.rooms[0].area_m2;
  SummarizeResiduals(stages.planar.walls, ring, s);
  if (skip_openings) return result;

  // 6. Openings on the walls.
  FoundOpenings openings =
      FindOpenings(stages.planar.openings, result.plan.walls, ring.viewpoint, options, &stages.planar.walls);
  result.plan.openings = std::move(openings.openings);
  s.door_leaves = openings.door_leaves;
  s.openings = static_cast<int>(result.plan.openings.size());
  return result;
}

PlanResult ReconstructPlan(const std::vector<ClassPoint>& points, const PlanOptions& options,
                           const std::string& points_source) {
  options.Check();
  const auto start_time = std::chrono::steady_clock::now();
  const RingStages stages = FitRingStages(points, options, points_source);
  PlanResult result = PlanFromRingStages(stages, stages.ring, options);
  result.summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return result;
}

}  // namespace asbuilt
