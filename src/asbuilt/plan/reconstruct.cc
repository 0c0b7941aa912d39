#include "asbuilt/plan/reconstruct.h"

#include <algorithm>
#include <limits>
#include <chrono>
#include <cmath>
#include <functional>
#include <numeric>
#include <numbers>
#include <random>
#include <unordered_map>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "asbuilt/util/error.h"
#include <spdlog/spdlog.h>

namespace asbuilt {
namespace {

Vec2 DirOf(double theta) { return Vec2(std::cos(theta), std::sin(theta)); }
Vec2 NormalOf(double theta) { return Vec2(-std::sin(theta), std::cos(theta)); }

// Difference of two undirected line angles, wrapped to (−π/2, π/2].
double AngleDiffModPi(double a, double b) {
  double d = std::fmod(a - b, kPi);
  if (d > kPi / 2) d -= kPi;
  if (d <= -kPi / 2) d += kPi;
  return d;
}

double WrapAngle(double a) {  // To (−π, π].
  a = std::fmod(a, 2 * kPi);
  if (a > kPi) a -= 2 * kPi;
  if (a <= -kPi) a += 2 * kPi;
  return a;
}

// Quantile of sorted values, linear interpolation.
double Quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  double pos = q * (sorted.size() - 1);
  size_t i = static_cast<size_t>(std::floor(pos));
  size_t j = std::min(i + 1, sorted.size() - 1);
  return sorted[i] + (pos - i) * (sorted[j] - sorted[i]);
}

// Dense runs of sorted positions along a line, as index ranges [begin, end).
// Positions are binned (10 cm); a bin is part of the wall when it holds at
// least a tenth of a well-filled bin (the 75th percentile), so that sparse
// outliers that happen to fall in the band neither bridge gaps nor stretch a
// wall. Runs break at stretches longer than `max_gap` without such bins.
// Few points (< 100): plain gaps between consecutive points.
std::vector<std::pair<size_t, size_t>> DenseRuns(const std::vector<double>& ts, double max_gap) {
  std::vector<std::pair<size_t, size_t>> runs;
  if (ts.empty()) return runs;
  if (ts.size() < 100) {
    size_t begin = 0;
    for (size_t i = 1; i <= ts.size(); ++i) {
      if (i < ts.size() && ts[i] - ts[i - 1] <= max_gap) continue;
      runs.push_back({begin, i});
      begin = i;
    }
    return runs;
  }
  const double bin = 0.1;
  const double t0 = ts.front();
  const int nbins = static_cast<int>((ts.back() - t0) / bin) + 1;
  std::vector<int> counts(nbins, 0);
  for (double t : ts) counts[std::min(nbins - 1, static_cast<int>((t - t0) / bin))]++;
  std::vector<int> filled;
  for (int c : counts) {
    if (c > 0) filled.push_back(c);
  }
  std::sort(filled.begin(), filled.end());
  const double level = std::max(2.0, 0.1 * filled[filled.size() * 3 / 4]);
  int run_first = -1, run_last = -1;
  auto emit = [&]() {
    if (run_first < 0) return;
    double lo = t0 + run_first * bin, hi = t0 + (run_last + 1) * bin;
    size_t b = std::lower_bound(ts.begin(), ts.end(), lo) - ts.begin();
    size_t e = std::upper_bound(ts.begin(), ts.end(), hi) - ts.begin();
    if (e > b) runs.push_back({b, e});
  };
  for (int i = 0; i < nbins; ++i) {
    if (counts[i] < level) continue;
    if (run_first >= 0 && (i - run_last - 1) * bin > max_gap) {
      emit();
      run_first = -1;
    }
    if (run_first < 0) run_first = i;
    run_last = i;
  }
  emit();
  return runs;
}

// Extent of an opening's label along one axis from sorted positions: 2 cm
// bins, grown from the densest bin while bins hold at least `rel_level` of a
// well-filled bin (the 75th percentile; at least 2 points), across gaps of at
// most `max_gap`. Partly occluded stretches (furniture in front of a window)
// still count, sparse strays do not. Edges are the outermost points of the
// outermost bins.
std::pair<double, double> BinnedExtent(const std::vector<double>& ts, double rel_level, double max_gap) {
  const double bin = 0.02;
  const double t0 = ts.front();
  const int nbins = static_cast<int>((ts.back() - t0) / bin) + 1;
  std::vector<int> counts(nbins, 0);
  for (double t : ts) counts[std::min(nbins - 1, static_cast<int>((t - t0) / bin))]++;
  std::vector<int> filled;
  for (int c : counts) {
    if (c > 0) filled.push_back(c);
  }
  std::sort(filled.begin(), filled.end());
  const double level = std::max(2.0, rel_level * filled[filled.size() * 3 / 4]);
  const int peak = static_cast<int>(std::max_element(counts.begin(), counts.end()) - counts.begin());
  const int max_skip = static_cast<int>(max_gap / bin);
  int lo = peak, hi = peak;
  for (int i = peak - 1, skipped = 0; i >= 0 && skipped <= max_skip; --i) {
    if (counts[i] >= level) {
      lo = i;
      skipped = 0;
    } else {
      ++skipped;
    }
  }
  for (int i = peak + 1, skipped = 0; i < nbins && skipped <= max_skip; ++i) {
    if (counts[i] >= level) {
      hi = i;
      skipped = 0;
    } else {
      ++skipped;
    }
  }
  double a = *std::lower_bound(ts.begin(), ts.end(), t0 + lo * bin - 1e-12);
  double b = *(std::upper_bound(ts.begin(), ts.end(), t0 + (hi + 1) * bin) - 1);
  return {a, b};
}

// An opening's two edges along its wall, with their variances.
struct EdgePair {
  double a = 0, b = 0;
  double var_a = 0, var_b = 0;
  bool from_boundary_a = false, from_boundary_b = false;
};

// Edges of one opening from its label-edge (boundary) positions, sorted,
// given the extent [a, b] of all its points: boundary positions in the lower
// half of [a, b] belong to edge a, those in the upper half to edge b. An edge
// with at least `min_boundary_points` becomes the median of its positions,
// with a variance from their spread (MAD); the other edge keeps the extent's.
EdgePair BoundaryEdges(const std::vector<double>& ts, double a, double b, double extent_var,
                       const PlanOptions& o) {
  EdgePair out{a, b, extent_var, extent_var, false, false};
  const double mid = 0.5 * (a + b);
  const std::vector<double> lo(ts.begin(), std::lower_bound(ts.begin(), ts.end(), mid));
  const std::vector<double> hi(std::lower_bound(ts.begin(), ts.end(), mid), ts.end());
  auto median_var = [](const std::vector<double>& v) {
    const double m = Quantile(v, 0.5);
    std::vector<double> dev;
    for (double x : v) dev.push_back(std::abs(x - m));
    std::sort(dev.begin(), dev.end());
    const double sigma = 1.4826 * Quantile(dev, 0.5);
    // The median of n points: about 1.25 σ/√n; label edges of one frame's
    // neighbouring rows are correlated, so count at most 50 as independent;
    // the edge itself is only known to half a pixel (about 2 mm at 3 m).
    const double n = std::min<double>(v.size(), 50.0);
    return std::pair{m, 1.57 * sigma * sigma / n + 0.002 * 0.002};
  };
  if (static_cast<int>(lo.size()) >= o.min_boundary_points) {
    std::tie(out.a, out.var_a) = median_var(lo);
    out.from_boundary_a = true;
  }
  if (static_cast<int>(hi.size()) >= o.min_boundary_points) {
    std::tie(out.b, out.var_b) = median_var(hi);
    out.from_boundary_b = true;
  }
  return out;
}

// An opening's point projected onto its host wall.
struct OpeningPoint {
  double t;  // Along the wall from its start.
  double z;
  double sigma;
  bool boundary;  // A label edge on the wall surface (PointSource::kBoundary).
};

// Two openings on one wall closer than `opening_gap_m` (windows either side
// of a 20 cm pier) fall into one group. The pier shows as a gap in the
// openings' own points with label edges on the wall at both of its ends;
// an occluder in front of one opening leaves a gap too, but no wall edges
// at it. Splits `group` (sorted by t) at such gaps.
std::vector<std::vector<OpeningPoint>> SplitAtPiers(const std::vector<OpeningPoint>& group,
                                                    const PlanOptions& o) {
  constexpr double kMinPier = 0.06, kReach = 0.05;
  std::vector<double> inner, edges;
  for (const OpeningPoint& g : group) (g.boundary ? edges : inner).push_back(g.t);
  auto count_in = [&](double lo, double hi) {
    return std::lower_bound(edges.begin(), edges.end(), hi) - std::lower_bound(edges.begin(), edges.end(), lo);
  };
  std::vector<double> cuts;
  for (size_t k = 1; k < inner.size(); ++k) {
    const double lo = inner[k - 1], hi = inner[k], mid = 0.5 * (lo + hi);
    if (hi - lo < kMinPier) continue;
    if (count_in(lo - kReach, mid) >= o.min_boundary_points && count_in(mid, hi + kReach) >= o.min_boundary_points) {
      cuts.push_back(mid);
    }
  }
  std::vector<std::vector<OpeningPoint>> out(cuts.size() + 1);
  for (const OpeningPoint& g : group) {
    out[std::upper_bound(cuts.begin(), cuts.end(), g.t) - cuts.begin()].push_back(g);
  }
  return out;
}

// An open door leaf in plan: door points in front of the wall along one
// line that meets the wall inside one of `hinge_windows` (t ranges along the
// wall) at 15°–165° and does not run along a viewing ray (depth noise smears
// a patch of points along its rays); RANSAC with a 2 cm band, then a total
// least squares refit. `width` is the leaf's extent from where its line
// meets the wall to its free end (98th percentile). nullopt when no such
// line is seen whole.
struct Leaf {
  double t_hinge = 0;
  double width = 0;
  std::vector<Vec2> inliers;

  // The leaf's reach from a hinge known on the wall (98th percentile).
  double WidthFrom(const Vec2& hinge) const {
    std::vector<double> r;
    for (const Vec2& p : inliers) r.push_back((p - hinge).norm());
    std::sort(r.begin(), r.end());
    return Quantile(r, 0.98);
  }
};
std::optional<Leaf> FindLeaf(std::vector<Vec2> pts, const Vec2& wall_start, const Vec2& wall_dir,
                             const std::vector<std::pair<double, double>>& hinge_windows,
                             const std::optional<Vec2>& viewpoint, bool front_only, const PlanOptions& o) {
  // front_only: a leaf hides what lies behind it from the rig: keep, per 0.5° of
  // bearing from the viewpoint, the door points within 6 cm of the nearest
  // tenth (what a glass leaf lets the cameras see lies behind it; the tenth,
  // not the nearest, because stereo depth scatters by centimetres).
  if (front_only && viewpoint && !pts.empty()) {
    constexpr double kBinRad = 0.5 * std::numbers::pi / 180.0;
    std::unordered_map<long, std::vector<double>> ranges;
    auto bin = [&](const Vec2& p) {
      return static_cast<long>(std::floor(std::atan2(p.y() - viewpoint->y(), p.x() - viewpoint->x()) / kBinRad));
    };
    for (const Vec2& p : pts) ranges[bin(p)].push_back((p - *viewpoint).norm());
    std::unordered_map<long, double> front;
    for (auto& [b, r] : ranges) {
      std::sort(r.begin(), r.end());
      front[b] = Quantile(r, 0.1);
    }
    std::erase_if(pts, [&](const Vec2& p) { return (p - *viewpoint).norm() > front[bin(p)] + 0.06; });
  }
  if (static_cast<int>(pts.size()) < o.leaf_min_points) return std::nullopt;
  constexpr double kBand = 0.02;
  const double min_sin = std::sin(DegToRad(15.0)), min_ray_sin = std::sin(DegToRad(10.0));
  const Vec2 n_wall(-wall_dir.y(), wall_dir.x());
  // Where the line through p along d meets the wall, as t; NaN if it may not
  // be a leaf.
  auto hinge_t = [&](const Vec2& p, const Vec2& d) {
    if (std::abs(d.x() * wall_dir.y() - d.y() * wall_dir.x()) < min_sin) return static_cast<double>(NAN);
    if (viewpoint) {
      const Vec2 ray = (p - *viewpoint).normalized();
      if (std::abs(d.x() * ray.y() - d.y() * ray.x()) < min_ray_sin) return static_cast<double>(NAN);
    }
    const Vec2 h = p - n_wall.dot(p - wall_start) / n_wall.dot(d) * d;
    const double t = wall_dir.dot(h - wall_start);
    for (const auto& [lo, hi] : hinge_windows) {
      if (t >= lo && t <= hi) return t;
    }
    return static_cast<double>(NAN);
  };
  std::mt19937_64 rng(o.seed + 17);
  std::uniform_int_distribution<std::size_t> pick(0, pts.size() - 1);
  std::vector<int> best;
  for (int it = 0; it < 500; ++it) {
    const Vec2 p = pts[pick(rng)], q = pts[pick(rng)];
    if ((q - p).norm() < 0.2) continue;
    const Vec2 d = (q - p).normalized(), n(-d.y(), d.x());
    if (!std::isfinite(hinge_t(p, d))) continue;
    std::vector<int> in;
    for (int i = 0; i < static_cast<int>(pts.size()); ++i) {
      if (std::abs(n.dot(pts[i] - p)) <= kBand) in.push_back(i);
    }
    if (in.size() > best.size()) best = std::move(in);
  }
  if (static_cast<int>(best.size()) < o.leaf_min_points) return std::nullopt;
  Vec2 c = Vec2::Zero();
  for (int i : best) c += pts[i];
  c /= best.size();
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (int i : best) cov += (pts[i] - c) * (pts[i] - c).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const Vec2 d = eig.eigenvectors().col(1);
  Leaf leaf;
  leaf.t_hinge = hinge_t(c, d);
  if (!std::isfinite(leaf.t_hinge)) return std::nullopt;
  const Vec2 hinge = wall_start + leaf.t_hinge * wall_dir;
  std::vector<double> from_hinge;
  for (int i : best) from_hinge.push_back(std::abs(d.dot(pts[i] - hinge)));
  std::sort(from_hinge.begin(), from_hinge.end());
  leaf.width = Quantile(from_hinge, 0.98);
  for (int i : best) leaf.inliers.push_back(pts[i]);
  const double span = leaf.width - Quantile(from_hinge, 0.01);
  spdlog::debug("plan: open leaf: {} of {} points, hinge at t = {:.3f}, width {:.3f} m, {:.3f} m of it seen",
                best.size(), pts.size(), leaf.t_hinge, leaf.width, span);
  // The free end must be seen, and most of the leaf with it.
  if (span < 0.5 * leaf.width) return std::nullopt;
  return leaf;
}

struct Pt {
  Vec2 p;
  double z;
  double w;      // 1/σ².
  double sigma;
  double thr;    // Inlier band half-width.
  double vote;   // Support it lends a line: min(1, (vote_sigma/σ)²).
  bool contact;  // A floor/ceiling contact (PointSource::kContact).
};

// A line with this many times min_wall_points votes is a wall however sparse
// it is next to the densest one, and however small a share of all votes (a
// far wall's contacts against a near wall's dense points).
constexpr double kStrongLineVotes = 5.0;
constexpr double kInf = std::numeric_limits<double>::infinity();
// Sequential RANSAC stops after this many hypotheses in a row gave no wall:
// each failure removes a clutter patch (points by a corner, furniture), and a
// far wall's few precise contacts may come only after several.
constexpr int kMaxRansacFailures = 12;
// WidenForBend tests a line for a bend when each half has this many points.
constexpr int kMinBendHalfPoints = 10;

double Votes(const std::vector<Pt>& pts, const std::vector<int>& idx) {
  double v = 0;
  for (int i : idx) v += pts[i].vote;
  return v;
}

// A wall line: direction θ through a weighted centroid c; ρ is the offset
// along the normal (the centroid carries it). var_* are the fit's variances.
struct Line {
  Vec2 c = Vec2::Zero();
  double theta = 0;
  double var_theta = 0;
  double var_rho = 0;
  double t_min = 0, t_max = 0;  // Extent of its points along the direction, from c.
  std::vector<int> members;
  double votes = 0;  // Σ of the members' votes: the line's support.
  double chi2 = 0;
  double sum_w = 0;
  double z_top = 0;
  bool inferred = false;

  Vec2 Dir() const { return DirOf(theta); }
  Vec2 Normal() const { return NormalOf(theta); }
  Vec2 Start() const { return c + t_min * Dir(); }
  Vec2 End() const { return c + t_max * Dir(); }
  double Distance(const Vec2& p) const { return Normal().dot(p - c); }
};

// The direction of the weighted total-least-squares line through the points
// idx[i] for which `keep(i)` holds, with its variance (reduced χ², correlation
// cap: see FitLine); nullopt with fewer than 2 of them.
template <typename Keep>
std::optional<std::pair<double, double>> TlsDirection(const std::vector<Pt>& pts, const std::vector<int>& idx,
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

// Weighted total least squares on `idx`; with `fixed_theta` only the offset
// is estimated. Variances are scaled by the reduced χ² and by the correlation
// cap (dense points are not independent measurements).
Line FitLine(const std::vector<Pt>& pts, std::vector<int> idx, std::optional<double> fixed_theta,
             int max_independent, double max_gap) {
  Line line;
  double sw = 0;
  Vec2 c = Vec2::Zero();
  for (int i : idx) {
    sw += pts[i].w;
    c += pts[i].w * pts[i].p;
  }
  c /= sw;
  if (fixed_theta) {
    line.theta = *fixed_theta;
  } else if (const auto free = TlsDirection(pts, idx, [](size_t) { return true; }, max_independent)) {
    line.theta = free->first;
  }
  line.c = c;
  Vec2 dir = line.Dir(), n = line.Normal();
  double chi2 = 0, swt2 = 0;
  std::vector<double> ts;
  ts.reserve(idx.size());
  for (int i : idx) {
    Vec2 d = pts[i].p - c;
    double r = n.dot(d), t = dir.dot(d);
    chi2 += pts[i].w * r * r;
    swt2 += pts[i].w * t * t;
    ts.push_back(t);
  }
  std::sort(ts.begin(), ts.end());
  const int count = static_cast<int>(idx.size());
  std::pair<size_t, size_t> main_run{0, ts.size()};
  for (auto r : DenseRuns(ts, max_gap)) {
    if (r.second - r.first > main_run.second - main_run.first || main_run.second - main_run.first == ts.size()) {
      main_run = r;
    }
  }
  double reduced = count > 2 ? chi2 / (count - 2) : 1.0;
  double correlation = std::max(1.0, static_cast<double>(count) / max_independent);
  line.var_rho = reduced / sw * correlation;
  line.var_theta = fixed_theta ? 0.0 : reduced / std::max(swt2, 1e-12) * correlation;
  line.t_min = ts[main_run.first];
  line.t_max = ts[main_run.second - 1];
  line.chi2 = chi2;
  line.sum_w = sw;
  std::vector<double> zs;
  zs.reserve(idx.size());
  for (int i : idx) zs.push_back(pts[i].z);
  std::sort(zs.begin(), zs.end());
  line.z_top = Quantile(zs, 0.995);
  line.votes = Votes(pts, idx);
  line.members = std::move(idx);
  return line;
}

std::optional<Vec2> Intersect(const Line& a, const Line& b) {
  double den = Cross(a.Dir(), b.Dir());
  if (std::abs(den) < 1e-9) return std::nullopt;
  double s = Cross(b.c - a.c, b.Dir()) / den;
  return a.c + s * a.Dir();
}

// A room vertex: a wall–wall corner column (PointSource::kVertex), seen in
// one or more frames.
struct Vertex {
  Vec2 p = Vec2::Zero();
  double sigma = 0;
  int points = 0;
};

// Vertex points of all frames, clustered greedily (most precise first) within
// max(15 cm, 3σ); each cluster at the 1/σ²-weighted mean of its points, with
// σ from their σ and their spread.
std::vector<Vertex> ClusterVertices(std::vector<std::pair<Vec2, double>> pts) {
  std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  struct Acc {
    Vec2 sum = Vec2::Zero();
    double w = 0;
    std::vector<Vec2> members;
    Vec2 Mean() const { return sum / w; }
  };
  std::vector<Acc> acc;
  for (const auto& [p, sigma] : pts) {
    Acc* home = nullptr;
    for (Acc& a : acc) {
      if ((a.Mean() - p).norm() <= std::max(0.15, 3 * sigma)) {
        home = &a;
        break;
      }
    }
    if (!home) home = &acc.emplace_back();
    home->sum += p / (sigma * sigma);
    home->w += 1 / (sigma * sigma);
    home->members.push_back(p);
  }
  std::vector<Vertex> out;
  for (const Acc& a : acc) {
    const Vec2 m = a.Mean();
    double spread = 0;
    for (const Vec2& p : a.members) spread += (p - m).squaredNorm();
    spread /= static_cast<double>(a.members.size());
    out.push_back({m, std::sqrt(1 / a.w + spread), static_cast<int>(a.members.size())});
  }
  return out;
}

// Whether the ray from `view` to `p` passes through segment [s0, s1] before
// reaching p, by more than `margin` (p lies behind the segment).
bool BehindSegment(const Vec2& view, const Vec2& p, const Vec2& s0, const Vec2& s1, double margin) {
  const Vec2 r = p - view, e = s1 - s0;
  const double den = Cross(r, e);
  if (std::abs(den) < 1e-12) return false;
  const double along_ray = Cross(s0 - view, e) / den;  // Fraction of the way to p.
  const double along_seg = Cross(s0 - view, r) / den;
  return along_seg >= -0.02 && along_seg <= 1.02 && along_ray > 0 && along_ray < 1 - margin / r.norm();
}

// Sequential RANSAC over the wall points: returns lines with their members.
// Two passes: the floor/ceiling contacts alone first (precise, few, and on
// walls only — a far wall's few hundred must not wait for luck among a near
// wall's hundred thousand dense points), then every point not taken.
std::vector<Line> FindLines(const std::vector<Pt>& pts, const PlanOptions& o, bool contacts, std::mt19937_64& rng) {
  std::vector<Line> lines;
  double best_density = 0;  // Votes per metre of the densest wall so far.
  double total_votes = 0;
  for (const Pt& p : pts) total_votes += p.vote;
  std::vector<bool> taken(pts.size(), false);
  // Without contacts the plain algorithm: counts, no exemptions, 4 failures.
  const double strong = contacts ? kStrongLineVotes * o.min_wall_points : kInf;
  const int max_failures = contacts ? kMaxRansacFailures : 4;
  for (int pass = 0; pass < 2; ++pass) {
  std::vector<int> remaining;
  for (int k = 0; k < static_cast<int>(pts.size()); ++k) {
    if (!taken[k] && (pass == 1 || pts[k].contact)) remaining.push_back(k);
  }
  int failures = 0;
  while (static_cast<int>(remaining.size()) >= o.min_wall_points && lines.size() < 64 && failures < max_failures) {
    // Score hypotheses on a random subset.
    std::vector<int> subset = remaining;
    int m = std::min<int>(subset.size(), o.ransac_subset_points);
    for (int i = 0; i < m; ++i) {
      std::uniform_int_distribution<int> pick(i, static_cast<int>(subset.size()) - 1);
      std::swap(subset[i], subset[pick(rng)]);
    }
    subset.resize(m);
    // Hypotheses from points drawn by their votes: a few hundred precise
    // contacts among thousands of noisy dense points still get paired.
    std::vector<double> subset_votes;
    subset_votes.reserve(m);
    for (int k : subset) subset_votes.push_back(pts[k].vote);
    std::discrete_distribution<int> pick(subset_votes.begin(), subset_votes.end());
    double best = 0;
    Vec2 best_n = Vec2::UnitY();
    double best_rho = 0;
    for (int it = 0; it < o.ransac_iterations; ++it) {
      const Vec2& a = pts[subset[pick(rng)]].p;
      const Vec2& b = pts[subset[pick(rng)]].p;
      Vec2 d = b - a;
      if (d.norm() < 0.1) continue;
      Vec2 n = Vec2(-d.y(), d.x()).normalized();
      double rho = n.dot(a);
      double count = 0;
      for (int k : subset) count += std::abs(n.dot(pts[k].p) - rho) < pts[k].thr ? pts[k].vote : 0.0;
      if (count > best) {
        best = count;
        best_n = n;
        best_rho = rho;
      }
    }
    double expected = best * remaining.size() / m;
    if (expected < o.min_wall_points) break;

    // Inliers among all remaining points, refined twice by least squares.
    std::vector<int> inliers;
    auto collect = [&](const Vec2& n, double rho) {
      inliers.clear();
      for (int k : remaining) {
        if (std::abs(n.dot(pts[k].p) - rho) < pts[k].thr) inliers.push_back(k);
      }
    };
    collect(best_n, best_rho);
    for (int refine = 0; refine < 2 && Votes(pts, inliers) >= o.min_wall_points; ++refine) {
      Line fit = FitLine(pts, inliers, std::nullopt, o.max_independent_points, o.max_gap_m);
      collect(fit.Normal(), fit.Normal().dot(fit.c));
    }
    if (Votes(pts, inliers) < o.min_wall_points) {
      ++failures;
      // Drop the hypothesis' points so the next round looks elsewhere.
      std::vector<bool> drop(pts.size(), false);
      for (int k : inliers) drop[k] = true;
      std::erase_if(remaining, [&](int k) { return drop[k]; });
      continue;
    }

    // Split the inliers into dense runs along the line; points outside every
    // run are strays (outliers in the band) and leave the pool too.
    Line fit = FitLine(pts, inliers, std::nullopt, o.max_independent_points, o.max_gap_m);
    Vec2 dir = fit.Dir();
    std::sort(inliers.begin(), inliers.end(), [&](int a, int b) {
      return dir.dot(pts[a].p - fit.c) < dir.dot(pts[b].p - fit.c);
    });
    std::vector<double> ts;
    for (int k : inliers) ts.push_back(dir.dot(pts[k].p - fit.c));
    bool accepted = false;
    for (auto [b, e] : DenseRuns(ts, o.max_gap_m)) {
      std::vector<int> run(inliers.begin() + b, inliers.begin() + e);
      const double run_votes = Votes(pts, run);
      if (run_votes < o.min_wall_points) continue;
      Line piece = FitLine(pts, run, std::nullopt, o.max_independent_points, o.max_gap_m);
      if (piece.t_max - piece.t_min < o.min_wall_length_m) continue;
      // Outliers that happen to line up are far sparser than any wall.
      // (Density is judged only for weakly supported lines: a near wall's
      // dense points outnumber a far wall's contacts by 100 per metre.)
      double density = run_votes / (piece.t_max - piece.t_min);
      if (density < o.min_relative_density * best_density && run_votes < strong) {
        continue;
      }
      if (run_votes < o.min_wall_fraction * total_votes && run_votes < strong) continue;
      best_density = std::max(best_density, density);
      for (int k : run) taken[k] = true;
      lines.push_back(std::move(piece));
      accepted = true;
    }
    failures = accepted ? 0 : failures + 1;
    std::vector<bool> drop(pts.size(), false);
    for (int k : inliers) drop[k] = true;
    std::erase_if(remaining, [&](int k) { return drop[k]; });
  }
  }
  return lines;
}

// Each point to the line it fits best (within the band and the line's
// extent), then refit; removes the bias of points near corners that the first
// line to be found took from its neighbour.
void CompetitiveRefit(const std::vector<Pt>& pts, std::vector<Line>& lines, const PlanOptions& o) {
  for (int round = 0; round < 2; ++round) {
    std::vector<std::vector<int>> members(lines.size());
    for (int k = 0; k < static_cast<int>(pts.size()); ++k) {
      int best = -1;
      double best_r = 0;
      for (int l = 0; l < static_cast<int>(lines.size()); ++l) {
        const Line& line = lines[l];
        Vec2 d = pts[k].p - line.c;
        double r = std::abs(line.Normal().dot(d));
        if (r >= pts[k].thr) continue;
        double t = line.Dir().dot(d);
        if (t < line.t_min - 0.3 || t > line.t_max + 0.3) continue;
        if (best < 0 || r < best_r) {
          best = l;
          best_r = r;
        }
      }
      if (best >= 0) members[best].push_back(k);
    }
    std::vector<Line> refit;
    for (size_t l = 0; l < lines.size(); ++l) {
      if (Votes(pts, members[l]) < o.min_wall_points) continue;
      Line fit = FitLine(pts, std::move(members[l]), std::nullopt, o.max_independent_points, o.max_gap_m);
      if (fit.t_max - fit.t_min < o.min_wall_length_m) continue;
      refit.push_back(std::move(fit));
    }
    lines = std::move(refit);
  }
}

void LogLines(const char* stage, const std::vector<Line>& lines) {
  if (!spdlog::should_log(spdlog::level::debug)) return;
  spdlog::debug("plan: {}: {} lines", stage, lines.size());
  for (const Line& l : lines) {
    spdlog::debug("  ({:.3f}, {:.3f}) → ({:.3f}, {:.3f}) θ {:.3f}° ±{:.4f}° ρ ±{:.4f} m, {} points{}", l.Start().x(),
                  l.Start().y(), l.End().x(), l.End().y(), RadToDeg(l.theta), RadToDeg(std::sqrt(l.var_theta)),
                  std::sqrt(l.var_rho), l.members.size(), l.inferred ? " (inferred)" : "");
  }
}

// Two pieces of one wall: within 3° and each through the other's band; or,
// up to 10° apart, the shorter one lies whole in the longer one's band (a
// short piece's angle is loosely fixed: 0.9 m of a wall beside a door fit
// 3.1° off its 4 m neighbour yet ends within 2.5 cm of its line).
bool Collinear(const Line& a, const Line& b, const PlanOptions& o) {
  const double diff = std::abs(AngleDiffModPi(a.theta, b.theta));
  if (diff > DegToRad(10.0)) return false;
  double tol = std::max(2 * o.epsilon_m, 3 * std::sqrt(a.var_rho + b.var_rho));
  if (diff <= DegToRad(3.0) && std::abs(a.Distance(b.c)) < tol && std::abs(b.Distance(a.c)) < tol) return true;
  const bool a_longer = a.t_max - a.t_min >= b.t_max - b.t_min;
  const Line& longer = a_longer ? a : b;
  const Line& shorter = a_longer ? b : a;
  return std::abs(longer.Distance(shorter.Start())) < tol && std::abs(longer.Distance(shorter.End())) < tol;
}

struct Direction {
  double theta = 0;   // In [0, π).
  double sum_w = 0;   // Σ 1/var_theta of its lines.
  double Var() const { return 1.0 / sum_w; }
};

// Weighted circular mean of angles with period 2π/k (k = 2: lines, k = 4: a
// Manhattan frame).
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
void WidenForBend(const std::vector<Pt>& pts, Line& line, const PlanOptions& o) {
  if (o.bend_sigmas <= 0 || line.members.size() < 2 * kMinBendHalfPoints) return;
  std::vector<double> along;  // Each member's position along the line, in members' order.
  along.reserve(line.members.size());
  for (int i : line.members) along.push_back(line.Dir().dot(pts[i].p - line.c));
  std::vector<double> sorted = along;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double mid = sorted[sorted.size() / 2];
  const auto a = TlsDirection(pts, line.members, [&](size_t k) { return along[k] < mid; }, o.max_independent_points);
  const auto b = TlsDirection(pts, line.members, [&](size_t k) { return along[k] >= mid; }, o.max_independent_points);
  if (!a || !b) return;
  const double before = line.var_theta;
  for (const auto& [theta, var] : {*a, *b}) {
    const double off = std::abs(AngleDiffModPi(theta, line.theta));
    if (off > o.bend_sigmas * std::sqrt(var)) line.var_theta = std::max(line.var_theta, off * off);
  }
  if (line.var_theta > before) {
    spdlog::debug("plan: line ({:.3f}, {:.3f}) → ({:.3f}, {:.3f}) θ {:.2f}° is bent: halves {:.2f}°, {:.2f}°; σ {:.3f}° → {:.2f}°",
                  line.Start().x(), line.Start().y(), line.End().x(), line.End().y(), RadToDeg(line.theta),
                  RadToDeg(a->first), RadToDeg(b->first), RadToDeg(std::sqrt(before)), RadToDeg(std::sqrt(line.var_theta)));
  }
}

// Dominant directions from the lines, a Manhattan frame when supported, and
// snapping of the lines that agree.
std::vector<Direction> SnapDirections(const std::vector<Pt>& pts, std::vector<Line>& lines,
                                      const PlanOptions& o, bool& manhattan) {
  for (Line& line : lines) WidenForBend(pts, line, o);
  auto weight = [](const Line& l) { return 1.0 / (l.var_theta + 1e-12); };
  std::vector<int> order(lines.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return lines[a].votes > lines[b].votes; });
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
  // Manhattan frame: the two strongest directions 90° apart within the data.
  manhattan = false;
  std::vector<int> frame_axes;
  for (size_t a = 0; a < dirs.size() && !manhattan; ++a) {
    for (size_t b = a + 1; b < dirs.size() && !manhattan; ++b) {
      double off = std::abs(std::abs(AngleDiffModPi(dirs[a].theta, dirs[b].theta)) - kPi / 2);
      double tol = std::max(DegToRad(o.manhattan_always_deg), o.snap_sigmas * std::sqrt(dirs[a].Var() + dirs[b].Var()));
      if (off < DegToRad(o.manhattan_max_deg) && off <= tol) {
        double frame = CircularMean({{dirs[a].theta, dirs[a].sum_w}, {dirs[b].theta, dirs[b].sum_w}}, 4);
        double sw = dirs[a].sum_w + dirs[b].sum_w;
        Direction da{frame, sw}, db{std::fmod(frame + kPi / 2, kPi), sw};
        dirs[a] = da;
        dirs[b] = db;
        frame_axes = {static_cast<int>(a), static_cast<int>(b)};
        manhattan = true;
      }
    }
  }
  // Snap each line whose fitted direction agrees with a dominant one. In a
  // Manhattan frame any line within manhattan_snap_max_deg of an axis: rooms are built
  // square, and a wall seen in part, past furniture, fits a few degrees off
  // with a σ that only counts its points' noise (a 2 m wall 4.6° off at
  // ±0.6°), which moves its corners by decimetres; a far wall's smeared
  // stereo fits up to 7° off (bench_rooms seed 12).
  for (Line& line : lines) {
    // In a Manhattan frame, beyond manhattan_snap_max_deg and up to
    // noisy_snap_max_deg off an axis, when the axis explains the line's
    // points within their own noise (χ² up by less than one per point): a
    // far plain wall's stereo, smeared ±20 cm along its rays, is cut by
    // sequential RANSAC into pieces fitted 15–25° off, each its own
    // "direction" (bench_rooms seed 15); a slanted wall measured to
    // centimetres is not. Closer lines snap by the rule below.
    bool on_axis = false;
    for (const int axis : frame_axes) {
      const double diff = AngleDiffModPi(line.theta, dirs[axis].theta);
      if (std::abs(diff) <= DegToRad(o.manhattan_snap_max_deg) || std::abs(diff) > DegToRad(o.noisy_snap_max_deg)) {
        continue;
      }
      Line snapped = FitLine(pts, line.members, line.theta - diff, o.max_independent_points, o.max_gap_m);
      // A bent line (WidenForBend) whose σ takes in the axis snaps too.
      if (snapped.chi2 - line.chi2 < static_cast<double>(line.members.size()) ||
          std::abs(diff) <= o.snap_sigmas * std::sqrt(line.var_theta)) {
        spdlog::debug("plan: a noisy line {:.1f}° ±{:.1f}° off the frame snapped onto it: ({:.3f}, {:.3f}) → ({:.3f}, {:.3f})",
                      RadToDeg(diff), RadToDeg(std::sqrt(line.var_theta)), line.Start().x(), line.Start().y(),
                      line.End().x(), line.End().y());
        snapped.var_theta = dirs[axis].Var();
        line = std::move(snapped);
        on_axis = true;
        break;
      }
    }
    if (on_axis) continue;
    for (const Direction& d : dirs) {
      double diff = AngleDiffModPi(line.theta, d.theta);
      double tol = manhattan ? DegToRad(o.manhattan_snap_max_deg)
                             : std::min(DegToRad(o.snap_max_deg),
                                        std::max(DegToRad(o.snap_min_deg),
                                                 o.snap_sigmas * std::sqrt(line.var_theta + d.Var())));
      if (std::abs(diff) <= tol) {
        Line snapped = FitLine(pts, line.members, line.theta - diff, o.max_independent_points, o.max_gap_m);
        snapped.var_theta = d.Var();
        line = std::move(snapped);
        break;
      }
    }
  }
  return dirs;
}

// Merges collinear lines that are close along their direction too.
void MergeCollinear(const std::vector<Pt>& pts, std::vector<Line>& lines, const PlanOptions& o) {
  bool merged = true;
  while (merged) {
    merged = false;
    for (size_t a = 0; a < lines.size() && !merged; ++a) {
      for (size_t b = a + 1; b < lines.size() && !merged; ++b) {
        Vec2 dir = lines[a].Dir();
        double b0 = dir.dot(lines[b].Start() - lines[a].c), b1 = dir.dot(lines[b].End() - lines[a].c);
        if (b0 > b1) std::swap(b0, b1);
        double gap = std::max(b0 - lines[a].t_max, lines[a].t_min - b1);
        // Two fits of one wall's points (crossing at a small angle through
        // the same stretch) are duplicates even when their angles differ more
        // than collinear pieces may.
        double overlap = std::min(lines[a].t_max, b1) - std::max(lines[a].t_min, b0);
        double shorter = std::min(lines[a].t_max - lines[a].t_min, b1 - b0);
        bool duplicate = std::abs(AngleDiffModPi(lines[a].theta, lines[b].theta)) < DegToRad(15.0) &&
                         overlap > 0.5 * shorter && std::abs(lines[a].Distance(lines[b].c)) < o.max_inlier_distance_m &&
                         std::abs(lines[b].Distance(lines[a].c)) < o.max_inlier_distance_m;
        if (!duplicate && (!Collinear(lines[a], lines[b], o) || gap > o.max_gap_m)) continue;
        std::vector<int> all = lines[a].members;
        all.insert(all.end(), lines[b].members.begin(), lines[b].members.end());
        bool snapped = lines[a].var_theta > 0 && lines[a].votes >= lines[b].votes;
        double keep_var = lines[a].var_theta;
        Line fit = FitLine(pts, std::move(all), std::nullopt, o.max_independent_points, o.max_gap_m);
        if (snapped) {
          fit = FitLine(pts, fit.members, lines[a].theta, o.max_independent_points, o.max_gap_m);
          fit.var_theta = keep_var;
        }
        lines[a] = std::move(fit);
        lines.erase(lines.begin() + b);
        merged = true;
      }
    }
  }
}

}  // namespace

void PlanOptions::Check() const {
  auto positive = [](double v, const char* name) {
    CheckArgument(v > 0 && std::isfinite(v), fmt::format("PlanOptions.{} = {}, must be > 0", name, v));
  };
  auto non_negative = [](double v, const char* name) {
    CheckArgument(v >= 0 && std::isfinite(v), fmt::format("PlanOptions.{} = {}, must be >= 0", name, v));
  };
  positive(epsilon_m, "epsilon_m");
  non_negative(inlier_sigmas, "inlier_sigmas");
  positive(max_inlier_distance_m, "max_inlier_distance_m");
  positive(nominal_sigma_m, "nominal_sigma_m");
  non_negative(shared_sigma_fraction, "shared_sigma_fraction");
  non_negative(shared_stereo_sigma_fraction, "shared_stereo_sigma_fraction");
  CheckArgument(vote_sigma_m > 0 && std::isfinite(vote_sigma_m),
                fmt::format("PlanOptions.vote_sigma_m = {}, must be > 0", vote_sigma_m));
  CheckArgument(min_wall_points >= 3, fmt::format("PlanOptions.min_wall_points = {}, must be >= 3", min_wall_points));
  positive(min_wall_length_m, "min_wall_length_m");
  positive(max_gap_m, "max_gap_m");
  CheckArgument(min_wall_fraction >= 0 && min_wall_fraction < 0.2,
                fmt::format("PlanOptions.min_wall_fraction = {}, must be in [0, 0.2)", min_wall_fraction));
  CheckArgument(min_relative_density >= 0 && min_relative_density < 1,
                fmt::format("PlanOptions.min_relative_density = {}, must be in [0, 1)", min_relative_density));
  CheckArgument(ransac_iterations >= 1,
                fmt::format("PlanOptions.ransac_iterations = {}, must be >= 1", ransac_iterations));
  CheckArgument(ransac_subset_points >= 10,
                fmt::format("PlanOptions.ransac_subset_points = {}, must be >= 10", ransac_subset_points));
  non_negative(snap_sigmas, "snap_sigmas");
  non_negative(snap_max_deg, "snap_max_deg");
  non_negative(manhattan_snap_max_deg, "manhattan_snap_max_deg");
  non_negative(snap_min_deg, "snap_min_deg");
  non_negative(manhattan_max_deg, "manhattan_max_deg");
  non_negative(manhattan_always_deg, "manhattan_always_deg");
  non_negative(noisy_snap_max_deg, "noisy_snap_max_deg");
  non_negative(bend_sigmas, "bend_sigmas");
  CheckArgument(parallel_max_deg > 0 && parallel_max_deg < 90,
                fmt::format("PlanOptions.parallel_max_deg = {}, must be in (0, 90)", parallel_max_deg));
  positive(max_corner_extension_m, "max_corner_extension_m");
  non_negative(door_casing_m, "door_casing_m");
  non_negative(window_casing_m, "window_casing_m");
  non_negative(casing_sigma_m, "casing_sigma_m");
  positive(opening_band_m, "opening_band_m");
  positive(opening_front_m, "opening_front_m");
  positive(opening_gap_m, "opening_gap_m");
  CheckArgument(min_opening_points >= 2,
                fmt::format("PlanOptions.min_opening_points = {}, must be >= 2", min_opening_points));
  CheckArgument(min_boundary_points >= 1,
                fmt::format("PlanOptions.min_boundary_points = {}, must be >= 1", min_boundary_points));
  positive(min_opening_width_m, "min_opening_width_m");
  CheckArgument(edge_level > 0 && edge_level < 1,
                fmt::format("PlanOptions.edge_level = {}, must be in (0, 1)", edge_level));
  CheckArgument(max_independent_points >= 2,
                fmt::format("PlanOptions.max_independent_points = {}, must be >= 2", max_independent_points));
  if (viewpoint_m) {
    CheckArgument(viewpoint_m->allFinite(), "PlanOptions.viewpoint_m must be finite");
  }
}

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
      closed ? "closed" : "NOT closed",
      area_m2 >= 0 ? fmt::format("{:.2f} m²", area_m2) : std::string("no area"), manhattan ? "Manhattan frame, " : "",
      dirs.empty() ? "none" : dirs, wall_inliers, wall_points,
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

PlanResult ReconstructPlan(const std::vector<ClassPoint>& points, const PlanOptions& options,
                           const std::string& points_source) {
  options.Check();
  const auto start_time = std::chrono::steady_clock::now();
  const PlanOptions& o = options;
  PlanResult result;
  PlanSummary& s = result.summary;
  s.input_points = static_cast<int>(points.size());

  // 1. Planarize. Votes weigh points by precision only when there are
  // floor/ceiling contacts to protect; otherwise every point counts one.
  const bool weigh_votes = std::any_of(points.begin(), points.end(), [](const ClassPoint& p) {
    return p.label == LabelClass::kWall && p.source == PointSource::kContact;
  });
  const double strong = weigh_votes ? kStrongLineVotes * o.min_wall_points : kInf;
  std::vector<Pt> walls_pts;
  std::vector<const ClassPoint*> opening_pts;
  std::vector<std::pair<Vec2, double>> vertex_pts;  // Wall–wall corner columns: (x, y), σ.
  for (const ClassPoint& p : points) {
    if (!p.position_m.allFinite()) continue;
    double sigma = p.sigma_m > 0 ? p.sigma_m : o.nominal_sigma_m;
    if (p.label == LabelClass::kWall && p.source == PointSource::kVertex) {
      vertex_pts.emplace_back(p.position_m.head<2>(), sigma);
    } else if (p.label == LabelClass::kWall) {
      double thr = std::min(o.max_inlier_distance_m, std::max(o.epsilon_m, o.inlier_sigmas * sigma));
      const double vote = weigh_votes ? std::min(1.0, (o.vote_sigma_m / sigma) * (o.vote_sigma_m / sigma)) : 1.0;
      walls_pts.push_back({p.position_m.head<2>(), p.position_m.z(), 1.0 / (sigma * sigma), sigma, thr, vote,
                           p.source == PointSource::kContact});
    } else if (p.label == LabelClass::kDoor || p.label == LabelClass::kWindow) {
      opening_pts.push_back(&p);
      (p.label == LabelClass::kDoor ? s.door_points : s.window_points)++;
    }
  }
  s.wall_points = static_cast<int>(walls_pts.size());
  if (s.wall_points < 2 * o.min_wall_points) {
    // None at all: nothing was labelled or matched, and survey fails on it
    // (exit 1, no outputs). A few: an input problem (`asbuilt plan` exits 1)
    // that survey reports as a note while still writing points and report
    // (a real capture the segmenter finds little wall in).
    if (s.wall_points == 0) {
      throw Error(fmt::format("{}: 0 wall points, need at least {} (2 × PlanOptions.min_wall_points): no wall was "
                              "labelled, or no wall pixel had a valid disparity",
                              points_source.empty() ? "plan" : points_source, 2 * o.min_wall_points));
    }
    throw InputError(points_source.empty() ? "plan" : points_source, "",
                     fmt::format("{} wall points, need at least {} (2 × PlanOptions.min_wall_points)", s.wall_points,
                                 2 * o.min_wall_points));
  }

  // 2. Lines.
  std::mt19937_64 rng(o.seed);
  std::vector<Line> lines = FindLines(walls_pts, o, weigh_votes, rng);
  s.lines_found = static_cast<int>(lines.size());
  LogLines("RANSAC", lines);
  CompetitiveRefit(walls_pts, lines, o);
  MergeCollinear(walls_pts, lines, o);
  {
    double best = 0;
    double total_votes = 0;
    for (const Pt& p : walls_pts) total_votes += p.vote;
    for (const Line& l : lines) best = std::max(best, l.votes / std::max(0.1, l.t_max - l.t_min));
    std::erase_if(lines, [&](const Line& l) {
      return (l.votes / std::max(0.1, l.t_max - l.t_min) < o.min_relative_density * best && l.votes < strong) ||
             (l.votes < o.min_wall_fraction * total_votes && l.votes < strong);
    });
  }
  LogLines("refit + merge", lines);

  // 3. Dominant directions, Manhattan frame, snapping.
  std::vector<Direction> dirs = SnapDirections(walls_pts, lines, o, s.manhattan);
  MergeCollinear(walls_pts, lines, o);
  for (const Direction& d : dirs) s.dominant_directions_deg.push_back(RadToDeg(d.theta));
  if (lines.size() < 2) {
    // The points do not support a plan: an input problem (exit 1), and one
    // that survey reports as a note while still writing points and report.
    throw InputError(points_source.empty() ? "plan" : points_source, "",
                     fmt::format("found {} wall line(s) in {} wall points; need at least 2 "
                                 "(try a larger --epsilon-m or fewer --min-wall-points)",
                                 lines.size(), s.wall_points));
  }

  // 4. Order around the viewpoint and close the room.
  Vec2 view = Vec2::Zero();
  if (o.viewpoint_m) {
    view = o.viewpoint_m->head<2>();
  } else {
    double sw = 0;
    for (const Line& l : lines) {
      double len = l.t_max - l.t_min;
      view += len * 0.5 * (l.Start() + l.End());
      sw += len;
    }
    view /= sw;
  }
  struct Ordered {
    Line line;
    double mid_angle;
    double span;
  };
  std::vector<Ordered> ordered;
  for (Line& l : lines) {
    if (Cross(l.Start() - view, l.End() - view) < 0) {  // Make it run counter-clockwise.
      l.theta = WrapAngle(l.theta + kPi);
      std::swap(l.t_min, l.t_max);
      l.t_min = -l.t_min;
      l.t_max = -l.t_max;
    }
    double a0 = std::atan2((l.Start() - view).y(), (l.Start() - view).x());
    double a1 = std::atan2((l.End() - view).y(), (l.End() - view).x());
    double span = WrapAngle(a1 - a0);
    if (span < 0) span += 2 * kPi;
    ordered.push_back({l, WrapAngle(a0 + span / 2), span});
  }
  // Drop lines mostly hidden behind or in front of a much better supported
  // one in the same viewing directions (clutter): visible wall surfaces do not
  // overlap in angle seen from the capture point.
  {
    std::vector<bool> drop(ordered.size(), false);
    for (size_t a = 0; a < ordered.size(); ++a) {
      for (size_t b = 0; b < ordered.size(); ++b) {
        if (a == b || drop[b]) continue;
        double d = std::abs(WrapAngle(ordered[a].mid_angle - ordered[b].mid_angle));
        double overlap = std::min(ordered[a].span, ordered[b].span) / 2 +
                         std::max(ordered[a].span, ordered[b].span) / 2 - d;
        overlap = std::min(overlap, std::min(ordered[a].span, ordered[b].span));
        if (overlap > 0.5 * ordered[a].span &&
            ordered[a].line.votes * 3 < ordered[b].line.votes &&
            ordered[a].line.votes < strong) {
          drop[a] = true;
        }
      }
    }
    std::vector<Ordered> kept;
    for (size_t i = 0; i < ordered.size(); ++i) {
      if (!drop[i]) kept.push_back(std::move(ordered[i]));
    }
    ordered = std::move(kept);
  }
  std::sort(ordered.begin(), ordered.end(),
            [](const Ordered& a, const Ordered& b) { return a.mid_angle < b.mid_angle; });
  spdlog::debug("plan: viewpoint ({:.3f}, {:.3f})", view.x(), view.y());
  std::vector<Line> ring;
  for (Ordered& e : ordered) ring.push_back(std::move(e.line));
  // A line seen between two pieces of one wall and wholly behind that wall's
  // line was seen through the wall's openings (ground contacts outside a
  // window, a neighbouring room through a door): not this room's wall. The
  // pieces then meet and merge below. (One piece alone is no evidence: the
  // end wall of an L's far wing lies behind the line of the cut wall.)
  for (size_t i = 0; ring.size() > 3 && i < ring.size();) {
    const Line& before = ring[(i + ring.size() - 1) % ring.size()];
    const Line& after = ring[(i + 1) % ring.size()];
    const Line& l = ring[i];
    auto behind = [&](const Vec2& p) {
      // Farther from the viewpoint than the wall's line along the ray to p.
      const double den = before.Normal().dot(p - view);
      if (std::abs(den) < 1e-9) return false;
      const double s_line = before.Normal().dot(before.c - view) / den;
      return s_line > 0 && s_line < 1 - 2 * o.epsilon_m / std::max(1e-9, (p - view).norm());
    };
    if (Collinear(before, after, o) && !Collinear(before, l, o) && behind(l.Start()) && behind(l.End()) &&
        l.votes < strong) {
      spdlog::debug("plan: dropped a line seen through a wall's openings: ({:.3f}, {:.3f}) → ({:.3f}, {:.3f})",
                    l.Start().x(), l.Start().y(), l.End().x(), l.End().y());
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
      continue;
    }
    ++i;
  }
  // Room vertices (wall–wall corner columns) confirm corners that the wall
  // points alone leave open: a near plain wall seen only in part (its floor
  // and ceiling edges out of view) still shows where it meets its
  // neighbours. A vertex belongs to a line when it lies in its band
  // (max(10 cm, 3σ)); the one a line reaches first beyond its end (or before
  // its start), up to kVertexReach, is where that line goes on to.
  // Vertices farther than ~6 m (σ > 12 cm) are too loosely placed to decide
  // a corner.
  std::vector<Vertex> vertices = ClusterVertices(vertex_pts);
  std::erase_if(vertices, [](const Vertex& v) { return v.sigma > 0.12; });
  constexpr double kVertexReach = 8.0;
  constexpr double kVertexSlack = 0.1;  // A vertex up to this far inside a line's extent still counts.
  auto on_line = [&](const Line& l, const Vertex& v) {
    return std::abs(l.Distance(v.p)) <= std::max(0.1, 3 * v.sigma);
  };
  auto vertex_after = [&](const Line& l) -> const Vertex* {
    const Vertex* best = nullptr;
    double best_t = kInf;
    for (const Vertex& v : vertices) {
      const double t = l.Dir().dot(v.p - l.c);
      if (on_line(l, v) && t > l.t_max - kVertexSlack && t < l.t_max + kVertexReach && t < best_t) {
        best = &v, best_t = t;
      }
    }
    return best;
  };
  auto vertex_before = [&](const Line& l) -> const Vertex* {
    const Vertex* best = nullptr;
    double best_t = -kInf;
    for (const Vertex& v : vertices) {
      const double t = l.Dir().dot(v.p - l.c);
      if (on_line(l, v) && t < l.t_min + kVertexSlack && t > l.t_min - kVertexReach && t > best_t) {
        best = &v, best_t = t;
      }
    }
    return best;
  };
  if (!vertices.empty()) {
    spdlog::debug("plan: {} room vertices from {} vertex points", vertices.size(), vertex_pts.size());
    for (const Vertex& v : vertices) {
      spdlog::debug("  vertex ({:.3f}, {:.3f}) ±{:.3f} m, {} points", v.p.x(), v.p.y(), v.sigma, v.points);
    }
  }
  // A vertex on the extensions of two lines a few places apart in the ring
  // is their corner; weak lines between them, wholly behind the two walls'
  // extensions to it, were seen through those walls' openings (ground
  // contacts outside a window).
  for (size_t i = 0; ring.size() > 3 && i < ring.size(); ++i) {
    const Vertex* v = vertex_after(ring[i]);
    if (!v) continue;
    bool cut = false;
    for (size_t k = 2; k <= 3 && k + 1 < ring.size() && !cut; ++k) {
      const size_t j = (i + k) % ring.size();
      const Line& a = ring[i];
      const Line& c = ring[j];
      if (std::abs(AngleDiffModPi(a.theta, c.theta)) <= DegToRad(o.parallel_max_deg) || !on_line(c, *v) ||
          c.Dir().dot(v->p - c.c) > c.t_min + kVertexSlack) {
        continue;
      }
      bool hidden = true;
      for (size_t m = 1; m < k && hidden; ++m) {
        const Line& b = ring[(i + m) % ring.size()];
        for (const Vec2& p : {b.Start(), b.End()}) {
          hidden = hidden && b.votes < strong && b.votes < std::min(a.votes, c.votes) &&
                   (BehindSegment(view, p, a.End(), v->p, 2 * o.epsilon_m) ||
                    BehindSegment(view, p, v->p, c.Start(), 2 * o.epsilon_m));
        }
      }
      if (!hidden) continue;
      spdlog::debug("plan: vertex ({:.3f}, {:.3f}) joins two walls across {} line(s) seen through them", v->p.x(),
                    v->p.y(), k - 1);
      ring[i].t_max = std::max(a.t_max, a.Dir().dot(v->p - a.c));
      ring[j].t_min = std::min(c.t_min, c.Dir().dot(v->p - c.c));
      std::vector<size_t> gone;
      for (size_t m = 1; m < k; ++m) gone.push_back((i + m) % ring.size());
      std::sort(gone.rbegin(), gone.rend());
      for (size_t g : gone) ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(g));
      cut = true;
    }
    if (cut) i = static_cast<size_t>(-1);  // Start over (++i → 0).
  }
  // Merge neighbours that continue each other (one wall seen in pieces).
  for (bool merged = true; merged && ring.size() > 2;) {
    merged = false;
    for (size_t i = 0; i < ring.size() && ring.size() > 2; ++i) {
      size_t j = (i + 1) % ring.size();
      if (!Collinear(ring[i], ring[j], o)) continue;
      std::vector<int> all = ring[i].members;
      all.insert(all.end(), ring[j].members.begin(), ring[j].members.end());
      const Line& big = ring[i].votes >= ring[j].votes ? ring[i] : ring[j];
      Line fit = FitLine(walls_pts, std::move(all), big.theta, o.max_independent_points, o.max_gap_m);
      fit.var_theta = big.var_theta;
      ring[i] = std::move(fit);
      ring.erase(ring.begin() + j);
      merged = true;
      break;
    }
  }

  // Corners between neighbours; inferred connecting walls where neighbours
  // are parallel or meet implausibly far from their points.
  const double ext = o.max_corner_extension_m;
  auto plausible = [&](const Line& a, const Line& b, const Vec2& x) {
    double ta = a.Dir().dot(x - a.c), tb = b.Dir().dot(x - b.c);
    return ta > a.t_min && ta < a.t_max + ext && tb < b.t_max && tb > b.t_min - ext;
  };
  std::vector<Line> closed;
  for (size_t i = 0; i < ring.size(); ++i) {
    const Line& a = ring[i];
    const Line& b = ring[(i + 1) % ring.size()];
    closed.push_back(a);
    bool meet = std::abs(AngleDiffModPi(a.theta, b.theta)) > DegToRad(o.parallel_max_deg);
    std::optional<Vec2> x = meet ? Intersect(a, b) : std::nullopt;
    if (x && plausible(a, b, *x)) continue;
    Line& b_copy = i + 1 == ring.size() ? closed.front() : ring[i + 1];  // b, or its copy already closed.
    // A vertex on both lines where they meet: their corner, however far
    // beyond their points.
    if (x) {
      const double ta = a.Dir().dot(*x - a.c), tb = b.Dir().dot(*x - b.c);
      const bool at_corner = std::any_of(vertices.begin(), vertices.end(), [&](const Vertex& v) {
        return on_line(a, v) && on_line(b, v) && (v.p - *x).norm() <= std::max(0.2, 3 * v.sigma);
      });
      if (at_corner && ta > a.t_min && tb < b.t_max) {
        closed.back().t_max = std::max(a.t_max, ta);
        b_copy.t_min = std::min(b.t_min, tb);
        spdlog::debug("plan: a vertex places the corner at ({:.3f}, {:.3f})", x->x(), x->y());
        continue;
      }
    }
    // Connector through the middle of the gap, in the nearest dominant
    // direction to the gap when one is close, else along the gap. Where a
    // line's extension reaches a vertex, the line goes on to it and the
    // connector starts (or ends) there.
    const Vertex* va = vertex_after(a);
    const Vertex* vb = vertex_before(b);
    // A vertex that takes the connector's end farther from the other line's
    // end is some other corner on the line's extension (bench_rooms seed 8,
    // exact labels: the east wall's, 2 m beyond a wall's points, cut off an
    // L's wing), not the one this gap closes.
    const double raw_gap = (b.Start() - a.End()).norm();
    if (va && (b.Start() - va->p).norm() > raw_gap + kVertexSlack) va = nullptr;
    if (vb && (vb->p - a.End()).norm() > raw_gap + kVertexSlack) vb = nullptr;
    Vec2 p = va ? va->p : a.End(), q = vb ? vb->p : b.Start();
    Vec2 gap = q - p;
    if (gap.norm() < 1e-6) gap = b.Dir();
    // Both ends at vertices, the gap running across the dominant directions
    // (more than 20° off the nearest): two walls are missing, not one. The
    // wall turns at each vertex (the dominant direction across a at va,
    // across b at vb, each the one nearer the gap), and the two connectors
    // meet where those lines cross (bench_rooms seed 28: a small room's two
    // near plain walls gave no points; one connector from corner to corner
    // would have cut the room in half).
    // An inferred wall along c's line, pointing along `toward`, from `from` to `to`.
    auto finish = [&](Line& c, const Vec2& from, const Vec2& to, const Vec2& toward) {
      c.inferred = true;
      if (c.Dir().dot(toward) < 0) c.theta = WrapAngle(c.theta + kPi);
      c.t_min = c.Dir().dot(from - c.c);
      c.t_max = c.Dir().dot(to - c.c);
      c.z_top = 0.5 * (a.z_top + b.z_top);
    };
    if (va && vb) {
      const double gap_theta = std::atan2(gap.y(), gap.x());
      auto off = [&](const Direction& d) { return std::abs(AngleDiffModPi(gap_theta, d.theta)); };
      auto turn = [&](const Line& l) -> const Direction* {  // Across l, nearest the gap.
        const Direction* best = nullptr;
        for (const Direction& d : dirs) {
          if (std::abs(AngleDiffModPi(l.theta, d.theta)) <= DegToRad(o.parallel_max_deg)) continue;
          if (!best || off(d) < off(*best)) best = &d;
        }
        return best;
      };
      const Direction* da = turn(a);
      const Direction* db = turn(b);
      if (da && db && std::min(off(*da), off(*db)) > DegToRad(20.0) &&
          std::abs(AngleDiffModPi(da->theta, db->theta)) > DegToRad(o.parallel_max_deg)) {
        Line c1, c2;
        c1.c = p, c1.theta = da->theta, c1.var_theta = da->Var(), c1.var_rho = va->sigma * va->sigma;
        c2.c = q, c2.theta = db->theta, c2.var_theta = db->Var(), c2.var_rho = vb->sigma * vb->sigma;
        const std::optional<Vec2> corner = Intersect(c1, c2);
        if (corner && (*corner - p).dot(gap) > 0 && (q - *corner).dot(gap) > 0) {
          finish(c1, p, *corner, *corner - p);
          finish(c2, *corner, q, q - *corner);
          spdlog::debug("plan: two connectors through vertices ({:.3f}, {:.3f}) → ({:.3f}, {:.3f}), turning at "
                        "({:.3f}, {:.3f})", p.x(), p.y(), q.x(), q.y(), corner->x(), corner->y());
          closed.back().t_max = std::max(a.t_max, a.Dir().dot(p - a.c));
          b_copy.t_min = std::min(b.t_min, b.Dir().dot(q - b.c));
          closed.push_back(c1);
          closed.push_back(c2);
          s.inferred_walls += 2;
          continue;
        }
      }
    }
    Line c;
    c.c = va && !vb ? p : vb && !va ? q : 0.5 * (p + q);
    c.theta = std::atan2(gap.y(), gap.x());
    c.var_theta = DegToRad(5.0) * DegToRad(5.0);
    c.var_rho = 0.05 * 0.05;
    // From a vertex the wall turns: its connector takes the dominant
    // direction nearest the gap's among those across the vertex's own line.
    const Line* turned = va ? &a : vb ? &b : nullptr;
    const Direction* nearest = nullptr;
    for (const Direction& d : dirs) {
      if (turned && std::abs(AngleDiffModPi(turned->theta, d.theta)) <= DegToRad(o.parallel_max_deg)) continue;
      if (!nearest || std::abs(AngleDiffModPi(c.theta, d.theta)) < std::abs(AngleDiffModPi(c.theta, nearest->theta))) {
        nearest = &d;
      }
    }
    if (nearest && std::abs(AngleDiffModPi(c.theta, nearest->theta)) < DegToRad(turned ? 60.0 : 30.0)) {
      c.theta -= AngleDiffModPi(c.theta, nearest->theta);
      c.var_theta = nearest->Var();
    }
    // With neither end at a vertex, a vertex in the gap (between the ends
    // along and across the connector) on neither line is the missing wall's
    // own corner column, seen where the rest of it was hidden: the connector
    // runs through it, not through the gap's middle (bench_rooms seed 8,
    // exact labels: a wardrobe hid all but 0.3 m of an L wing's wall; the
    // middle put it 32 cm off, the vertex 2 cm).
    if (!va && !vb) {
      const Vertex* inside = nullptr;
      for (const Vertex& v : vertices) {
        if (on_line(a, v) || on_line(b, v)) continue;
        const double m = std::max(0.1, 3 * v.sigma);
        auto between = [&](const Vec2& axis) {
          const double t = axis.dot(v.p - p), end = axis.dot(q - p);
          return t >= std::min(0.0, end) - m && t <= std::max(0.0, end) + m;
        };
        if (between(c.Dir()) && between(c.Normal()) && (!inside || v.sigma < inside->sigma)) inside = &v;
      }
      if (inside) {
        spdlog::debug("plan: connector through the vertex ({:.3f}, {:.3f}) in its gap", inside->p.x(), inside->p.y());
        c.c = inside->p;
        c.var_rho = inside->sigma * inside->sigma;
      }
    }
    finish(c, p, q, gap);  // From a towards b.
    if (va || vb) {
      c.var_rho = std::pow(va && vb ? std::min(va->sigma, vb->sigma) : (va ? va : vb)->sigma, 2);
      spdlog::debug("plan: connector through vertices ({}) → ({})",
                    va ? fmt::format("{:.3f}, {:.3f}", va->p.x(), va->p.y()) : "none",
                    vb ? fmt::format("{:.3f}, {:.3f}", vb->p.x(), vb->p.y()) : "none");
    }
    // A connector along a neighbour's own line is that wall seen only in
    // part (its points stop short of the corner, past furniture): the wall
    // goes on to where its line meets the other neighbour — when that is
    // where the other's points end — and no wall is inferred.
    if (x) {
      const double ta = a.Dir().dot(*x - a.c), tb = b.Dir().dot(*x - b.c);
      auto along = [&](const Line& l) { return std::abs(AngleDiffModPi(l.theta, c.theta)) <= DegToRad(3.0); };
      if (along(b) && ta > a.t_min && ta < a.t_max + ext && tb < b.t_min) {
        b_copy.t_min = tb;
        continue;
      }
      if (along(a) && tb > b.t_min - ext && tb < b.t_max && ta > a.t_max) {
        closed.back().t_max = ta;  // a's copy.
        continue;
      }
    }
    if (va) closed.back().t_max = std::max(a.t_max, a.Dir().dot(va->p - a.c));
    if (vb) b_copy.t_min = std::min(b.t_min, b.Dir().dot(vb->p - b.c));
    closed.push_back(c);
    ++s.inferred_walls;
  }
  ring = std::move(closed);
  LogLines("closed ring", ring);
  const int n = static_cast<int>(ring.size());

  // Corner i joins ring[i−1] and ring[i]. Parallel neighbours (possible only
  // around inferred connectors) fall back to the midpoint of their ends.
  auto corners_of = [&](const std::vector<Line>& L) {
    std::vector<Vec2> c(n);
    for (int i = 0; i < n; ++i) {
      const Line& a = L[(i + n - 1) % n];
      const Line& b = L[i];
      std::optional<Vec2> x;
      if (std::abs(AngleDiffModPi(a.theta, b.theta)) > DegToRad(1.0)) x = Intersect(a, b);
      c[i] = x ? *x : 0.5 * (a.End() + b.Start());
    }
    return c;
  };
  std::vector<Vec2> corners = corners_of(ring);
  s.closed = n >= 3;

  // Room height: a high quantile of all wall inliers' heights.
  double height = 0;
  for (const Line& l : ring) height = std::max(height, l.z_top);

  // What a wall's points share does not average out over them
  // (PlanOptions::shared_sigma_fraction, shared_stereo_sigma_fraction).
  for (Line& l : ring) {
    if (l.members.empty()) continue;
    std::vector<double> sigmas;
    sigmas.reserve(l.members.size());
    for (int k : l.members) {
      const Pt& p = walls_pts[k];
      sigmas.push_back((p.contact ? o.shared_sigma_fraction : o.shared_stereo_sigma_fraction) * p.sigma);
    }
    std::nth_element(sigmas.begin(), sigmas.begin() + sigmas.size() / 2, sigmas.end());
    l.var_rho += std::pow(sigmas[sigmas.size() / 2], 2);
  }

  // ± by numerical propagation of each line's (θ, ρ) variances.
  // Propagation works on copies without the member lists (cheap to copy).
  std::vector<Line> light = ring;
  for (Line& l : light) l.members = {};
  auto perturbed = [&](int line, int param, double h) {
    std::vector<Line> L = light;
    if (param == 0) {
      L[line].theta += h;
    } else {
      L[line].c += h * L[line].Normal();
    }
    return L;
  };
  auto variance_of = [&](const std::function<double(const std::vector<Line>&)>& f, const std::vector<int>& lines_used) {
    double var = 0;
    for (int l : lines_used) {
      for (int param = 0; param < 2; ++param) {
        double v = param == 0 ? ring[l].var_theta : ring[l].var_rho;
        if (v <= 0) continue;
        double h = std::max(1e-7, 1e-3 * std::sqrt(v));
        double d = (f(perturbed(l, param, h)) - f(perturbed(l, param, -h))) / (2 * h);
        var += d * d * v;
      }
    }
    return var;
  };

  Plan& plan = result.plan;
  for (int i = 0; i < n; ++i) {
    PlanWall w;
    w.start = corners[i];
    w.end = corners[(i + 1) % n];
    if (height > 1.0) w.height = height;
    auto length = [&, i](const std::vector<Line>& L) {
      std::vector<Vec2> c = corners_of(L);
      return (c[(i + 1) % n] - c[i]).norm();
    };
    w.length_sigma_m = std::sqrt(variance_of(length, {(i + n - 1) % n, i, (i + 1) % n}));
    plan.walls.push_back(w);
  }
  PlanRoom room;
  room.polygon = corners;
  room.area_m2 = PolygonArea(corners);
  if (room.area_m2 < 0) {
    // The viewpoint was outside the room's kernel; report honestly.
    spdlog::warn("plan: room polygon runs clockwise around the viewpoint; the ordering may be wrong");
    room.area_m2 = -room.area_m2;
  }
  std::vector<int> all_lines(n);
  std::iota(all_lines.begin(), all_lines.end(), 0);
  room.area_sigma_m2 = std::sqrt(
      variance_of([&](const std::vector<Line>& L) { return std::abs(PolygonArea(corners_of(L))); }, all_lines));
  plan.rooms.push_back(room);
  s.walls = n;
  s.area_m2 = room.area_m2;

  // Residual statistics.
  {
    double chi = 0, sw = 0;
    int inl = 0;
    for (const Line& l : ring) {
      for (int k : l.members) {
        double r = l.Distance(walls_pts[k].p);
        chi += walls_pts[k].w * r * r;
        sw += walls_pts[k].w;
        ++inl;
      }
    }
    s.wall_inliers = inl;
    s.outliers = s.wall_points - inl;
    s.rms_residual_m = sw > 0 ? std::sqrt(chi / sw) : -1;
  }

  // 5. Openings: host wall, projection, grouping, extent minus casing.
  std::vector<std::vector<OpeningPoint>> per_wall_kind(2 * n);
  // Door points standing in front of each wall: open leaves (FindLeaf).
  std::vector<std::vector<Vec2>> leaf_pts(n);
  for (const ClassPoint* p : opening_pts) {
    if (p->label != LabelClass::kDoor) continue;
    const Vec2 xy = p->position_m.head<2>();
    for (int i = 0; i < n; ++i) {
      const PlanWall& w = plan.walls[i];
      const double len = w.Length();
      if (len < 1e-9) continue;
      const Vec2 d = (w.end - w.start) / len;
      const double r = Vec2(-d.y(), d.x()).dot(xy - w.start), t = d.dot(xy - w.start);
      if (r > o.opening_front_m && r <= o.leaf_max_distance_m && t > -o.leaf_max_distance_m &&
          t < len + o.leaf_max_distance_m) {
        leaf_pts[i].push_back(xy);
      }
    }
  }
  for (const ClassPoint* p : opening_pts) {
    Vec2 xy = p->position_m.head<2>();
    double sigma = p->sigma_m > 0 ? p->sigma_m : o.nominal_sigma_m;
    int best = -1;
    double best_r = 0, best_t = 0;
    for (int i = 0; i < n; ++i) {
      const PlanWall& w = plan.walls[i];
      double len = w.Length();
      if (len < 1e-9) continue;
      Vec2 d = (w.end - w.start) / len;
      Vec2 inward(-d.y(), d.x());
      double r = inward.dot(xy - w.start);  // > 0: in the room.
      // In front of the face only casings and sill boards (a few cm) belong
      // to the opening; farther in are open leaves and clutter.
      // Not widened for noisy points: a casing point scattered farther in
      // is not needed (its ray lands where the ones behind the face do),
      // while an open leaf's points near its hinge, sent along their rays,
      // would widen the door by tens of centimetres.
      if (r > o.opening_front_m || r < -o.opening_band_m) continue;
      double t = d.dot(xy - w.start);
      // Noisy points (error mostly along the viewing ray) are projected
      // along the ray, which cancels that error. Precise points on or in front
      // of the face (casings, sill boards) keep the perpendicular projection,
      // which is exact for them, while precise points behind the face (glass,
      // jamb linings, a recessed leaf) go along the ray to where the opening
      // cuts the face.
      const bool boundary = p->source == PointSource::kBoundary;
      bool along_ray = o.viewpoint_m && (boundary || sigma > 0.01 || r < -0.01);
      if (along_ray) {
        Vec2 ray = xy - view;
        double den = inward.dot(ray);
        if (std::abs(den) > 1e-6) {
          double s_ray = inward.dot(w.start - view) / den;
          if (s_ray > 0) t = d.dot(view + s_ray * ray - w.start);
        }
      }
      if (t < -0.3 || t > len + 0.3) continue;
      if (best < 0 || std::abs(r) < std::abs(best_r)) {
        best = i;
        best_r = r;
        best_t = t;
      }
    }
    if (best < 0) continue;
    int slot = 2 * best + (p->label == LabelClass::kWindow ? 1 : 0);
    per_wall_kind[slot].push_back({best_t, p->position_m.z(), sigma, p->source == PointSource::kBoundary});
  }
  for (int slot = 0; slot < 2 * n; ++slot) {
    std::vector<OpeningPoint>& v = per_wall_kind[slot];
    if (v.empty()) continue;
    const int wi = slot / 2;
    const bool door = slot % 2 == 0;
    const double casing = door ? o.door_casing_m : o.window_casing_m;
    const PlanWall& w = plan.walls[wi];
    const double len = w.Length();
    const Vec2 d = (w.end - w.start) / len;
    std::sort(v.begin(), v.end(), [](const OpeningPoint& a, const OpeningPoint& b) { return a.t < b.t; });
    std::vector<std::vector<OpeningPoint>> groups;
    size_t begin = 0;
    for (size_t i = 1; i <= v.size(); ++i) {
      if (i < v.size() && v[i].t - v[i - 1].t <= o.opening_gap_m) continue;
      for (std::vector<OpeningPoint>& g : SplitAtPiers({v.begin() + begin, v.begin() + i}, o)) {
        groups.push_back(std::move(g));
      }
      begin = i;
    }
    for (const std::vector<OpeningPoint>& group : groups) {
      if (static_cast<int>(group.size()) < o.min_opening_points) continue;
      std::vector<double> ts, zs, boundary_ts;
      double sum_var = 0;
      for (const OpeningPoint& g : group) {
        ts.push_back(g.t);
        zs.push_back(g.z);
        sum_var += g.sigma * g.sigma;
        if (g.boundary) boundary_ts.push_back(g.t);
      }
      std::sort(ts.begin(), ts.end());
      std::sort(zs.begin(), zs.end());
      const auto [extent_a, extent_b] = BinnedExtent(ts, o.edge_level, o.opening_gap_m);
      // Edge uncertainty of the extent: the points' σ averaged over the few
      // that fix an edge, plus sampling spacing.
      const double n_edge = std::max(1.0, 0.02 * group.size());
      const double mean_var = sum_var / group.size();
      const double spacing = (extent_b - extent_a) / group.size();
      const double extent_var = mean_var / n_edge + spacing * spacing;
      // Label edges on the wall surface fix an edge better than the extent
      // of the opening's points (recessed glass, jambs, depth noise).
      EdgePair edges = BoundaryEdges(boundary_ts, extent_a, extent_b, extent_var, o);
      spdlog::debug("plan: wall {} {} group: extent [{:.3f}, {:.3f}], edges [{:.3f}{}, {:.3f}{}], {} boundary points",
                    wi, door ? "door" : "window", extent_a, extent_b, edges.a, edges.from_boundary_a ? " (label edge)" : "",
                    edges.b, edges.from_boundary_b ? " (label edge)" : "", boundary_ts.size());
      // One edge seen on the wall, the other not: an open leaf hides it —
      // the hinge side behind the leaf near its hinge, or the free side
      // behind the leaf's free end. A leaf is as wide as its clear opening,
      // so the unseen edge lies one leaf width from the seen one; the leaf
      // must meet the wall at one of the two.
      if (door && edges.from_boundary_a != edges.from_boundary_b) {
        std::vector<Vec2> near;
        for (const Vec2& q : leaf_pts[wi]) {
          const double t = d.dot(q - w.start);
          if (t > extent_a - o.leaf_max_distance_m && t < extent_b + o.leaf_max_distance_m) near.push_back(q);
        }
        // The hinge is at the seen edge, or on the unseen side: beyond where
        // the points stop (the leaf hides the jamb), or a little inside (the
        // leaf, seen past the jamb, lends the wall door points).
        constexpr double kHingeTolerance = 0.15, kInside = 0.3;
        const bool unseen_b = edges.from_boundary_a;
        const double clear_seen = unseen_b ? edges.a + casing : edges.b - casing;
        const double extent_unseen = unseen_b ? extent_b - casing : extent_a + casing;
        const double beyond = o.leaf_max_distance_m;
        const std::vector<std::pair<double, double>> windows = {
            {clear_seen - kHingeTolerance, clear_seen + kHingeTolerance},
            unseen_b ? std::pair{extent_unseen - kInside, extent_unseen + beyond}
                     : std::pair{extent_unseen - beyond, extent_unseen + kInside}};
        // All of the door's points first; then, if that gave no leaf that
        // fits the opening, only the front ones (a glass leaf shows what is
        // behind it).
        const std::optional<Vec2> view =
            o.viewpoint_m ? std::optional<Vec2>(o.viewpoint_m->head<2>()) : std::nullopt;
        for (const bool front_only : {false, true}) {
          const std::optional<Leaf> leaf = FindLeaf(near, w.start, d, windows, view, front_only, o);
          if (!leaf) continue;
          // Hinged at the seen edge: that point is known better than where
          // the fitted line meets the wall.
          const bool hinge_seen = std::abs(leaf->t_hinge - clear_seen) < kHingeTolerance;
          const double width = hinge_seen ? leaf->WidthFrom(w.start + clear_seen * d) : leaf->width;
          const double clear_unseen = unseen_b ? clear_seen + width : clear_seen - width;
          if (width <= o.min_opening_width_m ||
              (!hinge_seen && std::abs(leaf->t_hinge - clear_unseen) >= kHingeTolerance)) {
            continue;
          }
          const double var = (unseen_b ? edges.var_a : edges.var_b) + 0.01 * 0.01;
          if (unseen_b) {
            edges.b = clear_unseen + casing, edges.var_b = var;
          } else {
            edges.a = clear_unseen - casing, edges.var_a = var;
          }
          ++s.door_leaves;
          spdlog::debug("plan: wall {} door: width {:.3f} m from an open leaf ({} points{}, hinge at t = {:.3f}{})", wi,
                        width, leaf->inliers.size(), front_only ? ", front ones" : "", leaf->t_hinge,
                        hinge_seen ? ", the seen edge" : "");
          break;
        }
      }
      const double a = edges.a, b = edges.b;
      double t0 = std::clamp(a + casing, 0.0, len), t1 = std::clamp(b - casing, 0.0, len);
      if (t1 - t0 < o.min_opening_width_m) continue;
      auto [z0, z1] = BinnedExtent(zs, o.edge_level, o.opening_gap_m);
      PlanOpening op;
      op.kind = door ? OpeningKind::kDoor : OpeningKind::kWindow;
      op.wall = wi;
      op.start = w.start + t0 * d;
      op.end = w.start + t1 * d;
      op.width = t1 - t0;
      if (door) {
        op.sill = 0.0;
        op.height = z1 - casing;
      } else {
        op.sill = std::max(0.0, z0 + casing);
        op.height = z1 - casing - *op.sill;
      }
      // ±: each edge's variance plus the casing-width uncertainty.
      const double casing_var = o.casing_sigma_m * o.casing_sigma_m;
      op.width_sigma_m = std::sqrt(edges.var_a + edges.var_b + 2 * casing_var);
      double zspacing = (z1 - z0) / group.size();
      double zedge_var = mean_var / n_edge + zspacing * zspacing + o.casing_sigma_m * o.casing_sigma_m;
      op.height_sigma_m = std::sqrt((door ? 1 : 2) * zedge_var);
      op.sill_sigma_m = door ? 0.0 : std::sqrt(zedge_var);
      plan.openings.push_back(op);
    }
  }
  std::stable_sort(plan.openings.begin(), plan.openings.end(), [&](const PlanOpening& a, const PlanOpening& b) {
    if (a.wall != b.wall) return a.wall < b.wall;
    return (a.start - plan.walls[a.wall].start).norm() < (b.start - plan.walls[b.wall].start).norm();
  });
  s.openings = static_cast<int>(plan.openings.size());
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return result;
}

}  // namespace asbuilt
