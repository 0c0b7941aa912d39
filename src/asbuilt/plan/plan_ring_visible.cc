#include "asbuilt/plan/plan_ring_visible.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace asbuilt {
namespace {

constexpr int kVisibleBins = 360;              // Bearing bins around the viewpoint (1°).
constexpr double kVisibleMinRangeM = 0.3;      // A wall nearer than this along a ray is not one.
constexpr double kVisibleMaxRangeM = 30.0;     // Nor one farther.
constexpr double kVisibleJumpCorners = 3.0;    // A jump costs this many corners.
constexpr int kVisiblePeaksPerDirection = 24;  // Offset peaks kept per dominant direction.
// A point seen beyond a candidate counts against it with this share of its
// vote: an opaque wall hides what lies behind it.
constexpr double kVisibleBeyondWeight = 1.0;
constexpr double kVisibleInf = std::numeric_limits<double>::infinity();

// An infinite candidate line n·x = rho, n = NormalOf(theta).
struct VisibleCandidate {
  double theta = 0;
  bool off_axis = false;  // In a Manhattan frame, along neither axis.
  double var_theta = 0;
  double rho = 0;
  Vec2 Normal() const { return NormalOf(theta); }
};

double BinBearing(int b) { return (b + 0.5) * 2 * kPi / kVisibleBins - kPi; }

int BearingBin(const Vec2& d) {
  const double a = std::atan2(d.y(), d.x());
  const int b = static_cast<int>(std::floor((a + kPi) / (2 * kPi) * kVisibleBins));
  return std::clamp(b, 0, kVisibleBins - 1);
}

// Range along the ray from `view` in unit direction `u` to the line n·x =
// rho, or ∞.
double RayRange(const Vec2& n, double rho, const Vec2& view, const Vec2& u) {
  const double denom = n.dot(u);
  if (std::abs(denom) < 1e-9) return kVisibleInf;
  const double t = (rho - n.dot(view)) / denom;
  return t >= kVisibleMinRangeM && t <= kVisibleMaxRangeM ? t : kVisibleInf;
}

// The same at bearing `a`.
double RayRange(const VisibleCandidate& c, const Vec2& view, double a) {
  return RayRange(c.Normal(), c.rho, view, Vec2(std::cos(a), std::sin(a)));
}

// Peaks of the wall points' offsets along the normal of direction `theta`:
// votes within ±epsilon_m, at least min_wall_points, at least 2·epsilon_m
// apart, the strongest kVisiblePeaksPerDirection.
std::vector<VisibleCandidate> OffsetPeaks(const std::vector<WallPoint>& pts, const Direction& dir,
                                          const PlanOptions& o) {
  const Vec2 n = NormalOf(dir.theta);
  std::vector<std::pair<double, double>> offsets;  // (n·p, vote)
  for (const WallPoint& p : pts) offsets.push_back({n.dot(p.p), p.vote});
  std::sort(offsets.begin(), offsets.end());
  std::vector<std::pair<double, double>> windows;  // (mean offset, votes) per point's window.
  size_t lo = 0, hi = 0;
  double votes = 0, weighted = 0;
  for (size_t i = 0; i < offsets.size(); ++i) {
    while (hi < offsets.size() && offsets[hi].first <= offsets[i].first + o.epsilon_m) {
      votes += offsets[hi].second;
      weighted += offsets[hi].second * offsets[hi].first;
      ++hi;
    }
    while (offsets[lo].first < offsets[i].first - o.epsilon_m) {
      votes -= offsets[lo].second;
      weighted -= offsets[lo].second * offsets[lo].first;
      ++lo;
    }
    if (votes >= o.min_wall_points) windows.push_back({weighted / votes, votes});
  }
  std::sort(windows.begin(), windows.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  std::vector<VisibleCandidate> peaks;
  for (const auto& [rho, v] : windows) {
    if (static_cast<int>(peaks.size()) >= kVisiblePeaksPerDirection) break;
    bool near = false;
    for (const VisibleCandidate& c : peaks) near = near || std::abs(c.rho - rho) < 2 * o.epsilon_m;
    if (!near) peaks.push_back({.theta = dir.theta, .var_theta = dir.Var(), .rho = rho});
  }
  return peaks;
}

std::vector<VisibleCandidate> VisibleCandidates(const WallPoints& walls, const std::vector<WallLine>& lines,
                                                const DirectionFrame& frame, const PlanOptions& o) {
  std::vector<VisibleCandidate> out;
  for (const WallLine& l : lines) {
    bool off_axis = frame.manhattan;
    for (int a : frame.axes) {
      off_axis = off_axis && std::abs(AngleDiffModPi(l.theta, frame.directions[a].theta)) > DegToRad(1.0);
    }
    out.push_back({.theta = l.theta, .off_axis = off_axis, .var_theta = l.var_theta, .rho = l.Normal().dot(l.c)});
  }
  const size_t from_lines = out.size();
  for (const Direction& d : frame.directions) {
    for (const VisibleCandidate& p : OffsetPeaks(walls.points, d, o)) {
      bool known = false;
      for (size_t k = 0; k < from_lines && !known; ++k) {
        const double dtheta = AngleDiffModPi(out[k].theta, p.theta);
        // Same line whichever way it runs: compare offsets along one normal.
        const double rho = std::cos(out[k].theta - p.theta) > 0 ? out[k].rho : -out[k].rho;
        known = std::abs(dtheta) < DegToRad(0.5) && std::abs(rho - p.rho) < o.epsilon_m;
      }
      if (!known) out.push_back(p);
    }
  }
  return out;
}

// The bearing from `view` at which candidates a and b meet, when they may
// meet in a corner there (both on the frame's axes, not parallel, within
// range); nullopt otherwise.
std::optional<double> CornerBearing(const VisibleCandidate& a, const VisibleCandidate& b, const Vec2& view) {
  if (a.off_axis || b.off_axis) return std::nullopt;
  const Vec2 na = a.Normal(), nb = b.Normal();
  const double det = na.x() * nb.y() - na.y() * nb.x();
  if (std::abs(det) <= 1e-6) return std::nullopt;
  const Vec2 x((a.rho * nb.y() - b.rho * na.y()) / det, (na.x() * b.rho - nb.x() * a.rho) / det);
  const Vec2 d = x - view;
  if (d.norm() > kVisibleMaxRangeM) return std::nullopt;
  return std::atan2(d.y(), d.x());
}

// Whether a change between two candidates that meet at `bearing` is a corner
// at the boundary before bin b0 (they meet within a bin and a half of it),
// not a jump.
bool CornerAtBoundary(double bearing, int b0) {
  const double boundary = BinBearing(b0) - kPi / kVisibleBins;
  return std::abs(WrapAngle(bearing - boundary)) <= 1.5 * 2 * kPi / kVisibleBins;
}

// One candidate per bin (Viterbi along bins start, start + 1, … around the
// circle), the first bin's candidate fixed when `first` ≥ 0 and the change
// back to it paid at the end.
std::vector<int> DecodeBins(const std::vector<std::vector<double>>& score,
                            const std::vector<std::vector<double>>& change,
                            const std::vector<std::vector<char>>& corner_at, int start, int first, double corner) {
  const int n = static_cast<int>(score.front().size());
  std::vector<double> best(n), next(n);
  std::vector<std::vector<int>> from(kVisibleBins, std::vector<int>(n, -1));
  for (int k = 0; k < n; ++k) best[k] = (first < 0 || k == first) ? score[start][k] : -kVisibleInf;
  for (int s = 1; s < kVisibleBins; ++s) {
    const int b = (start + s) % kVisibleBins;
    for (int k = 0; k < n; ++k) {
      next[k] = -kVisibleInf;
      if (score[b][k] == -kVisibleInf) continue;
      for (int j = 0; j < n; ++j) {
        if (best[j] == -kVisibleInf) continue;
        const double cost = j == k ? 0.0 : (corner_at[b][j * n + k] ? corner : change[j][k]);
        if (best[j] - cost > next[k]) {
          next[k] = best[j] - cost;
          from[s][k] = j;
        }
      }
      next[k] += score[b][k];
    }
    best.swap(next);
  }
  int k = -1;
  double top = -kVisibleInf;
  for (int j = 0; j < n; ++j) {
    const double close = first < 0 || j == first ? 0.0 : (corner_at[start][j * n + first] ? corner : change[j][first]);
    if (best[j] - close > top) top = best[j] - close, k = j;
  }
  std::vector<int> label(kVisibleBins, -1);
  for (int s = kVisibleBins - 1; s >= 0 && k >= 0; --s) {
    label[(start + s) % kVisibleBins] = k;
    k = s > 0 ? from[s][k] : -1;
  }
  return label;
}

}  // namespace

std::vector<WallLine> SelectVisibleLines(const WallPoints& walls, std::vector<WallLine> lines,
                                         const DirectionFrame& frame, const PlanOptions& o) {
  if (!o.viewpoint_m || walls.points.empty()) return lines;
  const Vec2 view = o.viewpoint_m->head<2>();
  const std::vector<WallPoint>& pts = walls.points;
  const std::vector<VisibleCandidate> cands = VisibleCandidates(walls, lines, frame, o);
  const int n = static_cast<int>(cands.size());
  if (n < 2) return lines;

  // Votes each candidate holds per bin (−∞ where its ray misses it).
  std::vector<std::vector<double>> score(kVisibleBins, std::vector<double>(n, 0.0));
  std::vector<double> bin_votes(kVisibleBins, 0.0);
  std::vector<int> bin_of(pts.size());
  std::vector<Vec2> normals;
  for (const VisibleCandidate& c : cands) normals.push_back(c.Normal());
  for (size_t i = 0; i < pts.size(); ++i) {
    bin_of[i] = BearingBin(pts[i].p - view);
    bin_votes[bin_of[i]] += pts[i].vote;
    const Vec2 ray = pts[i].p - view;
    const double range = ray.norm();
    const double bearing = std::atan2(ray.y(), ray.x());
    const Vec2 u(std::cos(bearing), std::sin(bearing));
    for (int k = 0; k < n; ++k) {
      if (std::abs(normals[k].dot(pts[i].p) - cands[k].rho) < pts[i].thr) {
        score[bin_of[i]][k] += pts[i].vote;
      } else if (range > RayRange(normals[k], cands[k].rho, view, u) + pts[i].thr) {
        score[bin_of[i]][k] -= kVisibleBeyondWeight * pts[i].vote;  // Seen through it.
      }
    }
  }
  for (int b = 0; b < kVisibleBins; ++b) {
    bool any = false;
    for (int k = 0; k < n; ++k) {
      if (!std::isfinite(RayRange(cands[k], view, BinBearing(b)))) score[b][k] = -kVisibleInf;
      any = any || score[b][k] > -kVisibleInf;
    }
    // A bearing that meets no candidate (a camera outside the room, looking
    // out through its doorway) says nothing: any wall may carry through it,
    // rather than the decode failing and the rule turning off for the whole
    // room — on or off as one more candidate, at the vote threshold, covered
    // that bearing or not.
    if (!any) std::fill(score[b].begin(), score[b].end(), 0.0);
  }
  // A corner costs a typical bin's votes.
  std::vector<double> filled;
  for (double v : bin_votes) {
    if (v > 0) filled.push_back(v);
  }
  if (filled.empty()) return lines;
  std::nth_element(filled.begin(), filled.begin() + filled.size() / 2, filled.end());
  const double corner = filled[filled.size() / 2];
  const double jump = kVisibleJumpCorners * corner;
  std::vector<std::vector<double>> change(n, std::vector<double>(n, jump));
  std::vector<std::vector<char>> corner_at(kVisibleBins, std::vector<char>(n * n, 0));
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < n; ++k) {
      if (j == k) continue;
      const std::optional<double> bearing = CornerBearing(cands[j], cands[k], view);
      if (!bearing) continue;
      for (int b = 0; b < kVisibleBins; ++b) corner_at[b][j * n + k] = CornerAtBoundary(*bearing, b);
    }
  }

  // Around the circle: a free pass, then again from the middle of its
  // longest run with that run's candidate fixed, so the seam is no change.
  std::vector<int> label = DecodeBins(score, change, corner_at, 0, -1, corner);
  int best_start = 0, best_len = 0;
  for (int b = 0; b < kVisibleBins; ++b) {
    int len = 0;
    while (len < kVisibleBins && label[(b + len) % kVisibleBins] == label[b]) ++len;
    if (len > best_len) best_len = len, best_start = (b + len / 2) % kVisibleBins;
  }
  if (label[best_start] < 0) return lines;
  label = DecodeBins(score, change, corner_at, best_start, label[best_start], corner);

  // Runs of one candidate → lines refitted on their inliers in those bins.
  std::vector<std::vector<int>> members_in_bin(kVisibleBins);
  for (size_t i = 0; i < pts.size(); ++i) members_in_bin[bin_of[i]].push_back(static_cast<int>(i));
  std::vector<WallLine> out;
  for (int s = 0; s < kVisibleBins;) {
    const int b0 = (best_start + s) % kVisibleBins;
    const int k = label[b0];
    int len = 0;
    while (s + len < kVisibleBins && label[(best_start + s + len) % kVisibleBins] == k) ++len;
    std::vector<int> idx;
    for (int t = 0; t < len && k >= 0; ++t) {
      for (int i : members_in_bin[(b0 + t) % kVisibleBins]) {
        if (std::abs(normals[k].dot(pts[i].p) - cands[k].rho) < pts[i].thr) idx.push_back(i);
      }
    }
    s += len;
    if (idx.empty() || Votes(pts, idx) < o.min_wall_points) continue;
    WallLine l = FitWallLine(pts, std::move(idx), cands[k].theta, o.max_independent_points, o.max_gap_m);
    l.var_theta = cands[k].var_theta;
    out.push_back(std::move(l));
  }
  spdlog::debug(
      "plan: one viewpoint: {} candidates, {} lines by bearing "
      "(corner cost {:.1f} votes)",
      n, out.size(), corner);
  if (out.size() < 2) return lines;
  LogWallLines("visible lines", out);
  return out;
}

}  // namespace asbuilt
