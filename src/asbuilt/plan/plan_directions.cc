#include "asbuilt/plan/plan_directions.h"

#include <algorithm>
#include <numeric>

#include <spdlog/spdlog.h>

#include "asbuilt/plan/plan_lines.h"

namespace asbuilt {
namespace {

// WidenForBend tests a line for a bend when each half has this many points.
constexpr int kMinBendHalfPoints = 10;

// Weighted circular mean of angles with period 2π/k (k = 2: lines, k = 4: a
// Manhattan frame), in [0, 2π/k).
double CircularMean(const std::vector<std::pair<double, double>>& angle_weight, int k) {
  double s = 0, c = 0;
  for (auto [a, w] : angle_weight) {
    s += w * std::sin(k * a);
    c += w * std::cos(k * a);
  }
  double m = std::atan2(s, c) / k;
  return m < 0 ? m + 2 * kPi / k : m;
}

// PlanOptions::bend_sigmas: a line's angle σ covers how far its parts
// disagree with it. Its points are split in two halves at the median along
// the line; when a half fits a direction more than bend_sigmas of its own σ
// off the whole line's, the line's σ becomes at least that difference. A
// bend (a "V" of two pieces) and a step (two parallel pieces side by side,
// which one line fits askew) both show.
void WidenForBend(const std::vector<WallPoint>& pts, WallLine& line, const PlanOptions& o) {
  if (o.bend_sigmas <= 0 || line.members.size() < 2 * kMinBendHalfPoints) return;
  std::vector<double> along;  // Each member's position along the line, in members' order.
  along.reserve(line.members.size());
  for (int i : line.members) along.push_back(line.Dir().dot(pts[i].p - line.c));
  std::vector<double> sorted = along;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double mid = sorted[sorted.size() / 2];
  const auto a = TlsDirection(
      pts, line.members, [&](size_t k) { return along[k] < mid; }, o.max_independent_points);
  const auto b = TlsDirection(
      pts, line.members, [&](size_t k) { return along[k] >= mid; }, o.max_independent_points);
  if (!a || !b) return;
  const double before = line.var_theta;
  for (const auto& [theta, var] : {*a, *b}) {
    const double off = std::abs(AngleDiffModPi(theta, line.theta));
    if (off > o.bend_sigmas * std::sqrt(var)) line.var_theta = std::max(line.var_theta, off * off);
  }
  if (line.var_theta > before) {
    spdlog::debug(
        "plan: line ({:.3f}, {:.3f}) → ({:.3f}, {:.3f}) θ {:.2f}° is bent: halves {:.2f}°, {:.2f}°; σ {:.3f}° → "
        "{:.2f}°",
        line.Start().x(), line.Start().y(), line.End().x(), line.End().y(), RadToDeg(line.theta), RadToDeg(a->first),
        RadToDeg(b->first), RadToDeg(std::sqrt(before)), RadToDeg(std::sqrt(line.var_theta)));
  }
}

// The lines' angles clustered within snap_max_deg, the best supported lines
// first; each cluster's direction is the 1/var θ-weighted circular mean.
std::vector<Direction> ClusterDirections(const std::vector<WallLine>& lines, const PlanOptions& o) {
  auto weight = [](const WallLine& l) { return 1.0 / (l.var_theta + 1e-12); };
  std::vector<int> order(lines.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return lines[a].votes > lines[b].votes; });
  std::vector<std::vector<std::pair<double, double>>> clusters;
  std::vector<double> centre;
  for (int i : order) {
    double th = lines[i].theta;
    int found = -1;
    for (size_t c = 0; c < centre.size(); ++c) {
      if (std::abs(AngleDiffModPi(th, centre[c])) < DegToRad(o.snap_max_deg)) found = static_cast<int>(c);
    }
    if (found < 0) {
      clusters.push_back({{th, weight(lines[i])}});
      centre.push_back(th);
    } else {
      clusters[found].push_back({th, weight(lines[i])});
      centre[found] = CircularMean(clusters[found], 2);
    }
  }
  std::vector<Direction> dirs;
  for (size_t c = 0; c < clusters.size(); ++c) {
    Direction d{CircularMean(clusters[c], 2), 0};
    for (auto [a, w] : clusters[c]) d.sum_w += w;
    dirs.push_back(d);
  }
  return dirs;
}

// The first pair of directions (in order) 90° apart within the data (within
// snap_sigmas of their σ, and manhattan_max_deg or, when their σ is wider,
// that σ up to manhattan_snap_max_deg) becomes a Manhattan frame: both are
// replaced by its two axes, each with their pooled weight. Returns the axes'
// indices into `dirs` (none: no frame).
std::vector<int> FormManhattanFrame(std::vector<Direction>& dirs, const PlanOptions& o) {
  for (size_t a = 0; a < dirs.size(); ++a) {
    for (size_t b = a + 1; b < dirs.size(); ++b) {
      double off = std::abs(std::abs(AngleDiffModPi(dirs[a].theta, dirs[b].theta)) - kPi / 2);
      const double sigma = std::sqrt(dirs[a].Var() + dirs[b].Var());
      const double tol = std::max(DegToRad(o.manhattan_always_deg), o.snap_sigmas * sigma);
      // A pair known to within a degree or so that is 3° off square is a
      // room built so; a pair whose σ is wider than that (a bent line's,
      // alone in its direction) cannot tell, and is squared up to its 1σ.
      const double cap = std::max(DegToRad(o.manhattan_max_deg), std::min(DegToRad(o.manhattan_snap_max_deg), sigma));
      if (off < cap && off <= tol) {
        double frame = CircularMean({{dirs[a].theta, dirs[a].sum_w}, {dirs[b].theta, dirs[b].sum_w}}, 4);
        double sw = dirs[a].sum_w + dirs[b].sum_w;
        Direction da{frame, sw}, db{std::fmod(frame + kPi / 2, kPi), sw};
        dirs[a] = da;
        dirs[b] = db;
        return {static_cast<int>(a), static_cast<int>(b)};
      }
    }
  }
  return {};
}

// In a Manhattan frame, a line beyond manhattan_snap_max_deg and up to
// noisy_snap_max_deg off an axis snaps onto it when the axis explains its
// points within their own noise (χ² up by less than one per point), or when
// snap_sigmas of its σ (widened for a bend) take in the axis: a far plain
// wall's stereo, smeared along its rays, is cut by sequential RANSAC into
// pieces fitted 15–25° off; a slanted wall measured to centimetres does not
// pass. Returns whether it snapped.
bool SnapNoisyLineToAxis(const std::vector<WallPoint>& pts, WallLine& line, const std::vector<Direction>& dirs,
                         const std::vector<int>& frame_axes, const PlanOptions& o) {
  for (const int axis : frame_axes) {
    const double diff = AngleDiffModPi(line.theta, dirs[axis].theta);
    if (std::abs(diff) <= DegToRad(o.manhattan_snap_max_deg) || std::abs(diff) > DegToRad(o.noisy_snap_max_deg)) {
      continue;
    }
    WallLine snapped = FitWallLine(pts, line.members, line.theta - diff, o.max_independent_points, o.max_gap_m);
    if (snapped.chi2 - line.chi2 < static_cast<double>(line.members.size()) ||
        std::abs(diff) <= o.snap_sigmas * std::sqrt(line.var_theta)) {
      spdlog::debug(
          "plan: a noisy line {:.1f}° ±{:.1f}° off the frame snapped onto it: ({:.3f}, {:.3f}) → ({:.3f}, {:.3f})",
          RadToDeg(diff), RadToDeg(std::sqrt(line.var_theta)), line.Start().x(), line.Start().y(), line.End().x(),
          line.End().y());
      snapped.var_theta = dirs[axis].Var();
      line = std::move(snapped);
      return true;
    }
  }
  return false;
}

// Snaps a line onto the first direction its fit agrees with: in a Manhattan
// frame any within manhattan_snap_max_deg (rooms are built square, and a
// wall seen in part, past furniture, fits a few degrees off with a σ that
// counts only its points' noise); otherwise within snap_sigmas of the
// combined σ, bounded to [snap_min_deg, snap_max_deg].
void SnapLineToDirection(const std::vector<WallPoint>& pts, WallLine& line, const DirectionFrame& frame,
                         const PlanOptions& o) {
  for (const Direction& d : frame.directions) {
    double diff = AngleDiffModPi(line.theta, d.theta);
    double tol =
        frame.manhattan
            ? DegToRad(o.manhattan_snap_max_deg)
            : std::min(DegToRad(o.snap_max_deg),
                       std::max(DegToRad(o.snap_min_deg), o.snap_sigmas * std::sqrt(line.var_theta + d.Var())));
    if (std::abs(diff) <= tol) {
      WallLine snapped = FitWallLine(pts, line.members, line.theta - diff, o.max_independent_points, o.max_gap_m);
      snapped.var_theta = d.Var();
      line = std::move(snapped);
      return;
    }
  }
}

}  // namespace

SnappedLines SnapToDominantDirections(const WallPoints& walls, std::vector<WallLine> lines, const PlanOptions& o) {
  const std::vector<WallPoint>& pts = walls.points;
  for (WallLine& line : lines) WidenForBend(pts, line, o);
  DirectionFrame frame;
  frame.directions = ClusterDirections(lines, o);
  const std::vector<int> frame_axes = FormManhattanFrame(frame.directions, o);
  frame.manhattan = !frame_axes.empty();
  frame.axes = frame_axes;
  for (WallLine& line : lines) {
    if (!SnapNoisyLineToAxis(pts, line, frame.directions, frame_axes, o)) SnapLineToDirection(pts, line, frame, o);
  }
  MergeCollinearLines(pts, lines, o);
  return {std::move(lines), std::move(frame)};
}

}  // namespace asbuilt
