#ifndef ASBUILT_PLAN_PLAN_WALL_LINE_H_
#define ASBUILT_PLAN_PLAN_WALL_LINE_H_

// What the plan stages share (internal to plan/; the public entry point is
// plan/reconstruct.h): wall points in plan, wall lines fitted to them by
// weighted total least squares, and the angle arithmetic of undirected lines.
// Plan frame: the world's (x, y) in metres, +z up; angles in radians,
// counter-clockwise from +x.
//
// The stages, in the order ReconstructPlan runs them:
//   plan_points.h       class points → wall points, opening points, vertex points
//   plan_lines.h        wall points → wall lines (RANSAC, competitive refit, merge)
//   plan_directions.h   dominant directions, Manhattan frame, snapping
//   plan_ring.h         lines → a closed ring of walls around the viewpoint
//   plan_uncertainty.h  ± of the ring's wall lengths and area
//   plan_openings.h     door/window points → openings on the ring's walls

#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "asbuilt/geometry/rig.h"
#include "asbuilt/plan/plan_options.h"

namespace asbuilt {

// A wall point in plan, with what the line fits need of it.
struct WallPoint {
  Vec2 p;        // Position in plan, m.
  double z;      // Height above the floor, m.
  double w;      // Fit weight 1/σ², m⁻².
  double sigma;  // Position σ, m.
  double thr;    // Inlier band half-width, m: min(max_inlier_distance_m, max(epsilon_m, inlier_sigmas·σ)).
  double vote;   // Support it lends a line: min(1, (vote_sigma_m/σ)²), or 1 (PlanOptions::vote_sigma_m).
  bool contact;  // A floor/ceiling contact (PointSource::kContact).
};

// All wall points of a plan, indexed by the lines' `members`.
struct WallPoints {
  std::vector<WallPoint> points;
  // Votes weigh precision only when there are floor/ceiling contacts to
  // protect; otherwise every vote is 1 and the plain algorithm runs.
  bool weigh_votes = false;
  // A line with at least this many votes is never dropped as sparse, small or
  // hidden (5 × min_wall_points with contacts; ∞ without).
  double strong_line_votes = std::numeric_limits<double>::infinity();

  // Σ of all points' votes, summed in order.
  double TotalVotes() const;
};

// Unit direction and left normal of a line at angle `theta`.
inline Vec2 DirOf(double theta) { return Vec2(std::cos(theta), std::sin(theta)); }
inline Vec2 NormalOf(double theta) { return Vec2(-std::sin(theta), std::cos(theta)); }

// Difference of two undirected line angles, wrapped to (−π/2, π/2].
inline double AngleDiffModPi(double a, double b) {
  double d = std::fmod(a - b, kPi);
  if (d > kPi / 2) d -= kPi;
  if (d <= -kPi / 2) d += kPi;
  return d;
}

// An angle wrapped to (−π, π].
inline double WrapAngle(double a) {
  a = std::fmod(a, 2 * kPi);
  if (a > kPi) a -= 2 * kPi;
  if (a <= -kPi) a += 2 * kPi;
  return a;
}

// Quantile q ∈ [0, 1] of sorted values, linear interpolation; 0 when empty.
double SortedQuantile(const std::vector<double>& sorted, double q);

// Σ of the votes of points[idx[i]].
double Votes(const std::vector<WallPoint>& points, const std::vector<int>& idx);

// Sorted positions `ts` (non-empty) counted in bins of `bin_m` starting at
// ts.front() (the last bin also takes ts.back()).
struct BinnedPositions {
  double t0 = 0.0;
  double bin_m = 0.0;
  std::vector<int> counts;
  // The count of a well-filled bin: the 75th percentile of the non-empty
  // bins' counts.
  int WellFilled() const;
};
BinnedPositions BinPositions(const std::vector<double>& ts, double bin_m);

// Dense runs of sorted positions `ts` along a line (m), as index ranges
// [begin, end). Positions are binned (10 cm); a bin is part of the wall when
// it holds at least two positions and a tenth of a well-filled bin (the 75th
// percentile) or, where less, of the fullest bin within `max_gap`: sparse
// outliers that happen to fall in the band neither bridge gaps nor stretch a
// dense wall, and a wall that thins out with distance keeps its far end.
// Runs break at stretches longer than `max_gap` (m)
// without such bins. Few points (< 100): plain gaps between consecutive
// points.
std::vector<std::pair<size_t, size_t>> DenseRuns(const std::vector<double>& ts, double max_gap);

// A wall line: direction θ through a weighted centroid c; ρ is the offset
// along the normal (the centroid carries it). var_* are the fit's variances.
// A line runs from Start() to End(); the room lies on its left once the ring
// is oriented (plan_ring.h).
struct WallLine {
  Vec2 c = Vec2::Zero();
  double theta = 0;
  double var_theta = 0;         // rad².
  double var_rho = 0;           // m².
  double t_min = 0, t_max = 0;  // Extent of its points along the direction, from c, m.
  std::vector<int> members;     // Indices into WallPoints::points.
  double votes = 0;             // Σ of the members' votes: the line's support.
  double chi2 = 0;              // Σ w·r² of the members about the line.
  double sum_w = 0;             // Σ w of the members.
  double z_top = 0;             // 99.5th percentile of the members' heights, m.
  bool inferred = false;        // A connecting wall with no points of its own.

  Vec2 Dir() const { return DirOf(theta); }
  Vec2 Normal() const { return NormalOf(theta); }
  Vec2 Start() const { return c + t_min * Dir(); }
  Vec2 End() const { return c + t_max * Dir(); }
  double Distance(const Vec2& p) const { return Normal().dot(p - c); }  // Signed, m; > 0 on the left.
};

// The direction of the weighted total-least-squares line through the points
// points[idx[k]] for which `keep(k)` holds, with its variance (reduced χ²,
// correlation cap: see FitWallLine), as (θ, var θ); nullopt with fewer than
// 2 of them.
template <typename Keep>
std::optional<std::pair<double, double>> TlsDirection(const std::vector<WallPoint>& pts, const std::vector<int>& idx,
                                                      Keep&& keep, int max_independent) {
  double sw = 0;
  int count = 0;
  Vec2 c = Vec2::Zero();
  for (size_t k = 0; k < idx.size(); ++k) {
    if (!keep(k)) continue;
    sw += pts[idx[k]].w;
    c += pts[idx[k]].w * pts[idx[k]].p;
    ++count;
  }
  if (count < 2) return std::nullopt;
  c /= sw;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (size_t k = 0; k < idx.size(); ++k) {
    if (!keep(k)) continue;
    Vec2 d = pts[idx[k]].p - c;
    cov += pts[idx[k]].w * d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
  const Vec2 dir = es.eigenvectors().col(1);
  // The smaller eigenvalue is the weighted χ², the larger Σ w·t².
  const double chi2 = std::max(es.eigenvalues()(0), 0.0), swt2 = std::max(es.eigenvalues()(1), 1e-12);
  const double reduced = count > 2 ? chi2 / (count - 2) : 1.0;
  const double correlation = std::max(1.0, static_cast<double>(count) / max_independent);
  return std::pair{std::atan2(dir.y(), dir.x()), reduced / swt2 * correlation};
}

// Weighted total least squares on points[idx] (at least one point); with
// `fixed_theta` only the offset is estimated (var_theta = 0). Variances are
// scaled by the reduced χ² and by the correlation cap max(1, n /
// max_independent) (dense points are not independent measurements). The
// extent [t_min, t_max] is that of the longest dense run (DenseRuns with
// `max_gap`); `members` = idx, all of them.
WallLine FitWallLine(const std::vector<WallPoint>& pts, std::vector<int> idx, std::optional<double> fixed_theta,
                     int max_independent, double max_gap);

// Where the two lines cross; nullopt when they are parallel.
std::optional<Vec2> IntersectLines(const WallLine& a, const WallLine& b);

// Two pieces of one wall: within 3° and each through the other's band
// (max(2ε, 3σ of their offsets)); or, up to 10° apart, the shorter one lies
// whole in the longer one's band (a short piece's angle is loosely fixed).
bool CollinearLines(const WallLine& a, const WallLine& b, const PlanOptions& o);
// The half-width of the band CollinearLines asks each line to lie in: max(2ε, 3σ of their offsets), m.
double CollinearTolerance(const WallLine& a, const WallLine& b, const PlanOptions& o);

// Debug log of `lines` (ends, θ ± σ, ρ σ, point count) under the heading `stage`.
void LogWallLines(const char* stage, const std::vector<WallLine>& lines);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_PLAN_WALL_LINE_H_
