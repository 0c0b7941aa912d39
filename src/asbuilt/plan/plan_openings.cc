#include "asbuilt/plan/plan_openings.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <unordered_map>

#include <Eigen/Eigenvalues>
#include <spdlog/spdlog.h>

#include "asbuilt/plan/plan_wall_line.h"

namespace asbuilt {
namespace {

// Extent of an opening's label along one axis from sorted positions: 2 cm
// bins, grown from the densest bin while bins hold at least `rel_level` of a
// well-filled bin (the 75th percentile; at least 2 points), across gaps of at
// most `max_gap`. Partly occluded stretches (furniture in front of a window)
// still count, sparse strays do not. Edges are the outermost points of the
// outermost bins.
std::pair<double, double> BinnedExtent(const std::vector<double>& ts, double rel_level, double max_gap) {
  const BinnedPositions binned = BinPositions(ts, 0.02);
  const double bin = binned.bin_m, t0 = binned.t0;
  const std::vector<int>& counts = binned.counts;
  const int nbins = static_cast<int>(counts.size());
  const double level = std::max(2.0, rel_level * binned.WellFilled());
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
  int n_a = 0, n_b = 0;  // Label-edge points on each side.
};

// Edges of one opening from its label-edge (boundary) positions, sorted,
// given the extent [a, b] of all its points: boundary positions in the lower
// half of [a, b] belong to edge a, those in the upper half to edge b. An edge
// with at least `min_boundary_points` becomes the median of its positions,
// with a variance from their spread (MAD); the other edge keeps the extent's.
EdgePair BoundaryEdges(const std::vector<double>& ts, double a, double b, double extent_var, const PlanOptions& o) {
  EdgePair out{a, b, extent_var, extent_var, false, false};
  const double mid = 0.5 * (a + b);
  const std::vector<double> lo(ts.begin(), std::lower_bound(ts.begin(), ts.end(), mid));
  const std::vector<double> hi(std::lower_bound(ts.begin(), ts.end(), mid), ts.end());
  out.n_a = static_cast<int>(lo.size());
  out.n_b = static_cast<int>(hi.size());
  auto median_var = [](const std::vector<double>& v) {
    const double m = SortedQuantile(v, 0.5);
    std::vector<double> dev;
    for (double x : v) dev.push_back(std::abs(x - m));
    std::sort(dev.begin(), dev.end());
    const double sigma = 1.4826 * SortedQuantile(dev, 0.5);
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
  bool boundary;        // A label edge on the wall surface (PointSource::kBoundary).
  bool behind = false;  // Seen behind the face (glass, a reveal) and sent along its ray onto it.
};

// A handful of label edges inside an opening (an open leaf's outline, a
// segmenter's stray edge) opposite a well-seen edge are not its edge: where
// one side has under 1/8 of the other side's label-edge points and more
// than max_own_beyond_label_edge of the opening's own points lie beyond its
// edge (past the casing and 3 cm), that side takes the extent instead (and
// a door's open leaf may then give its width).
void DropContradictedLabelEdges(const std::vector<OpeningPoint>& group, double casing, double extent_a, double extent_b,
                                double extent_var, const PlanOptions& o, EdgePair& edges) {
  constexpr double kSlack = 0.03, kStray = 0.125;
  int own = 0, beyond_a = 0, beyond_b = 0;
  for (const OpeningPoint& g : group) {
    if (g.boundary) continue;
    ++own;
    beyond_a += g.t < edges.a - casing - kSlack;
    beyond_b += g.t > edges.b + casing + kSlack;
  }
  if (own == 0) return;
  if (edges.from_boundary_a && beyond_a > o.max_own_beyond_label_edge * own && edges.n_a < kStray * edges.n_b) {
    edges.a = extent_a;
    edges.var_a = extent_var;
    edges.from_boundary_a = false;
  }
  if (edges.from_boundary_b && beyond_b > o.max_own_beyond_label_edge * own && edges.n_b < kStray * edges.n_a) {
    edges.b = extent_b;
    edges.var_b = extent_var;
    edges.from_boundary_b = false;
  }
}

// Two openings on one wall closer than `opening_gap_m` (windows either side
// of a 20 cm pier) fall into one group. The pier shows as a gap in the
// openings' own points with label edges on the wall at both of its ends;
// an occluder in front of one opening leaves a gap too, but no wall edges
// at it. Splits `group` (sorted by t) at such gaps.
std::vector<std::vector<OpeningPoint>> SplitAtPiers(const std::vector<OpeningPoint>& group, const PlanOptions& o) {
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
    return SortedQuantile(r, 0.98);
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
      front[b] = SortedQuantile(r, 0.1);
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
  leaf.width = SortedQuantile(from_hinge, 0.98);
  for (int i : best) leaf.inliers.push_back(pts[i]);
  const double span = leaf.width - SortedQuantile(from_hinge, 0.01);
  spdlog::debug("plan: open leaf: {} of {} points, hinge at t = {:.3f}, width {:.3f} m, {:.3f} m of it seen",
                best.size(), pts.size(), leaf.t_hinge, leaf.width, span);
  // The free end must be seen, and most of the leaf with it.
  if (span < 0.5 * leaf.width) return std::nullopt;
  return leaf;
}

// Door points standing in front of each wall (beyond opening_front_m, up to
// leaf_max_distance_m, and within that of its ends): where open leaves are
// looked for (FindLeaf).
std::vector<std::vector<Vec2>> LeafPointsPerWall(const std::vector<const ClassPoint*>& points,
                                                 const std::vector<PlanWall>& walls, const PlanOptions& o) {
  const int n = static_cast<int>(walls.size());
  std::vector<std::vector<Vec2>> leaf_pts(n);
  for (const ClassPoint* p : points) {
    if (p->label != LabelClass::kDoor) continue;
    const Vec2 xy = p->position_m.head<2>();
    for (int i = 0; i < n; ++i) {
      const PlanWall& w = walls[i];
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
  return leaf_pts;
}

// Each opening point projected onto the wall it belongs to, in slot
// 2·wall (doors) or 2·wall + 1 (windows).
std::vector<std::vector<OpeningPoint>> ProjectOntoWalls(const std::vector<const ClassPoint*>& points,
                                                        const std::vector<PlanWall>& walls, const Vec2& view,
                                                        const PlanOptions& o) {
  const int n = static_cast<int>(walls.size());
  std::vector<std::vector<OpeningPoint>> per_wall_kind(2 * n);
  for (const ClassPoint* p : points) {
    Vec2 xy = p->position_m.head<2>();
    double sigma = p->sigma_m > 0 ? p->sigma_m : o.nominal_sigma_m;
    int best = -1;
    double best_r = 0, best_t = 0;
    for (int i = 0; i < n; ++i) {
      const PlanWall& w = walls[i];
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
      // A label-edge point lies at the wall's own depth, so its offset from
      // the face is depth noise alone: it may stand as far in front as its σ
      // allows (a far wall's edges scatter 5–30 cm; dropped, they left a
      // door's width to where its points stop).
      const bool boundary = p->source == PointSource::kBoundary;
      const double front = boundary
                               ? std::max(o.opening_front_m, std::min(o.inlier_sigmas * sigma, o.max_inlier_distance_m))
                               : o.opening_front_m;
      if (r > front || r < -o.opening_band_m) continue;
      double t = d.dot(xy - w.start);
      // Noisy points (error mostly along the viewing ray) are projected
      // along the ray, which cancels that error. Precise points on or in front
      // of the face (casings, sill boards) keep the perpendicular projection,
      // which is exact for them, while precise points behind the face (glass,
      // jamb linings, a recessed leaf) go along the ray to where the opening
      // cuts the face.
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
    per_wall_kind[slot].push_back({best_t, p->position_m.z(), sigma, p->source == PointSource::kBoundary,
                                   o.viewpoint_m.has_value() && best_r < -0.01});
  }
  return per_wall_kind;
}

// One wall's points of one kind, sorted along it (in place), grouped at gaps
// longer than opening_gap_m and split at piers (SplitAtPiers).
std::vector<std::vector<OpeningPoint>> GroupAlongWall(std::vector<OpeningPoint>& v, const PlanOptions& o) {
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
  return groups;
}

// One edge of a door seen on the wall, the other not: an open leaf hides it —
// the hinge side behind the leaf near its hinge, or the free side behind the
// leaf's free end. A leaf is as wide as its clear opening, so the unseen edge
// lies one leaf width from the seen one; the leaf must meet the wall at one
// of the two. All of the door's points are tried first; then, if that gave
// no leaf that fits the opening, only the front ones (a glass leaf shows what
// is behind it). Moves the unseen edge of `edges` and returns true when a
// leaf gives the width.
bool DoorWidthFromLeaf(EdgePair& edges, double extent_a, double extent_b, double casing, const PlanWall& w,
                       const Vec2& d, const std::vector<Vec2>& wall_leaf_pts, int wi, const PlanOptions& o) {
  std::vector<Vec2> near;
  for (const Vec2& q : wall_leaf_pts) {
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
  const std::optional<Vec2> view = o.viewpoint_m ? std::optional<Vec2>(o.viewpoint_m->head<2>()) : std::nullopt;
  for (const bool front_only : {false, true}) {
    const std::optional<Leaf> leaf = FindLeaf(near, w.start, d, windows, view, front_only, o);
    if (!leaf) continue;
    // Hinged at the seen edge: that point is known better than where
    // the fitted line meets the wall.
    const bool hinge_seen = std::abs(leaf->t_hinge - clear_seen) < kHingeTolerance;
    const double width = hinge_seen ? leaf->WidthFrom(w.start + clear_seen * d) : leaf->width;
    const double clear_unseen = unseen_b ? clear_seen + width : clear_seen - width;
    if (width <= o.min_opening_width_m || (!hinge_seen && std::abs(leaf->t_hinge - clear_unseen) >= kHingeTolerance)) {
      continue;
    }
    const double var = (unseen_b ? edges.var_a : edges.var_b) + o.leaf_edge_sigma_m * o.leaf_edge_sigma_m;
    if (unseen_b) {
      edges.b = clear_unseen + casing, edges.var_b = var;
    } else {
      edges.a = clear_unseen - casing, edges.var_a = var;
    }
    spdlog::debug("plan: wall {} door: width {:.3f} m from an open leaf ({} points{}, hinge at t = {:.3f}{})", wi,
                  width, leaf->inliers.size(), front_only ? ", front ones" : "", leaf->t_hinge,
                  hinge_seen ? ", the seen edge" : "");
    return true;
  }
  return false;
}

// A label edge whose casing's outer side faces away from the viewpoint is
// seen at the casing's front corner, casing_depth_m in front of the face;
// sent along its ray onto the face it lands (edge − t_v)·p/(h − p) farther
// out (t_v: the viewpoint's foot along the wall, h: its distance from the
// face, p: casing_depth_m), the more the more obliquely the wall is seen.
// Moves such label edges of `edges` back onto the casing's outer side and
// adds the casing depth's uncertainty (casing_sigma_m · |edge − t_v|/h) to
// their variance. Needs PlanOptions::viewpoint_m; casing_depth_m 0: off.
void CorrectFarLabelEdges(EdgePair& edges, const PlanWall& w, const Vec2& d, const PlanOptions& o) {
  if (!o.viewpoint_m || o.casing_depth_m <= 0) return;
  const Vec2 v = o.viewpoint_m->head<2>() - w.start;
  const double t_v = d.dot(v), h = Vec2(-d.y(), d.x()).dot(v), p = o.casing_depth_m;
  if (h <= p + 0.1) return;
  const auto correct = [&](double& edge, double& var) {
    var += std::pow(o.casing_sigma_m * (edge - t_v) / h, 2);
    edge = t_v + (edge - t_v) * (h - p) / h;
  };
  // Edge a has the opening on its +t side: its outer side faces −t, away
  // from a viewpoint beyond it; edge b the other way round.
  if (edges.from_boundary_a && t_v > edges.a) correct(edges.a, edges.var_a);
  if (edges.from_boundary_b && t_v < edges.b) correct(edges.b, edges.var_b);
}

// Where an opening's edge came from, for the log: a label edge, an open
// leaf (the edge opposite a label edge, when the leaf gave the width) or the
// extent of the opening's points.
const char* EdgeOrigin(bool label_edge, bool from_leaf) {
  return label_edge ? "label edge" : from_leaf ? "leaf" : "extent";
}

// The opening a group of points on wall `wi` seen from `viewpoint` (plan, m)
// gives, with ±; nullopt when it
// has too few points or its clear opening is too narrow or too low. Counts a width
// taken from an open leaf in `door_leaves`.
std::optional<PlanOpening> MeasureOpening(const std::vector<OpeningPoint>& group, int wi, const PlanWall& w, bool door,
                                          const std::vector<Vec2>& wall_leaf_pts, const Vec2& viewpoint,
                                          const PlanOptions& o, int& door_leaves) {
  // Label edges alone, without the opening's own points between them, are
  // no opening: an open leaf's outline against the wall behind it gives
  // such edges (a door's leaf swung back along the next wall).
  const auto own = std::count_if(group.begin(), group.end(), [](const OpeningPoint& g) { return !g.boundary; });
  if (own < o.min_opening_points) return std::nullopt;
  const double casing = door ? o.door_casing_m : o.window_casing_m;
  const double len = w.Length();
  const Vec2 d = (w.end - w.start) / len;
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
  DropContradictedLabelEdges(group, casing, extent_a, extent_b, extent_var, o, edges);
  CorrectFarLabelEdges(edges, w, d, o);
  spdlog::debug("plan: wall {} {} group: extent [{:.3f}, {:.3f}], edges [{:.3f}{}, {:.3f}{}], {} boundary points", wi,
                door ? "door" : "window", extent_a, extent_b, edges.a, edges.from_boundary_a ? " (label edge)" : "",
                edges.b, edges.from_boundary_b ? " (label edge)" : "", boundary_ts.size());
  const bool from_leaf = door && edges.from_boundary_a != edges.from_boundary_b &&
                         DoorWidthFromLeaf(edges, extent_a, extent_b, casing, w, d, wall_leaf_pts, wi, o);
  door_leaves += from_leaf;
  // An edge that is neither a label edge nor placed from a leaf is where the
  // opening's points stop: occluders, a recessed frame and label blobs move
  // it far more than the points' own noise (extent_edge_sigma_m).
  const double extent_edge_var = o.extent_edge_sigma_m * o.extent_edge_sigma_m;
  if (!edges.from_boundary_a && !(from_leaf && edges.from_boundary_b)) edges.var_a += extent_edge_var;
  if (!edges.from_boundary_b && !(from_leaf && edges.from_boundary_a)) edges.var_b += extent_edge_var;
  // A label edge is known to its points' spread and to how far the labels
  // themselves may be off, an angle (label_edge_sigma_mrad) that moves the
  // edge along the wall by range²/h times it: far and oblique edges the most.
  const double label_edge_rad = 1e-3 * *o.ForLabels(false).label_edge_sigma_mrad;
  const Vec2 v = viewpoint - w.start;
  const double t_v = d.dot(v), h = std::max(0.1, std::abs(Vec2(-d.y(), d.x()).dot(v)));
  const auto label_edge_var = [&](double edge) {
    return std::pow(label_edge_rad * ((edge - t_v) * (edge - t_v) + h * h) / h, 2);
  };
  if (edges.from_boundary_a) edges.var_a += label_edge_var(edges.a);
  if (edges.from_boundary_b) edges.var_b += label_edge_var(edges.b);
  const double a = edges.a, b = edges.b;
  // An edge where the opening's points stop is the casing's outer side when
  // they stop on the face; where they are seen through the opening, behind
  // the face, it is the clear opening's edge itself.
  const auto through = [&](double edge, double toward) {
    int behind = 0, all = 0;
    for (const OpeningPoint& g : group) {
      if (g.boundary || std::abs(g.t - edge) > 0.02 || (g.t - edge) * (toward - edge) < 0) continue;
      ++all;
      behind += g.behind;
    }
    return all > 0 && behind >= 0.8 * all;
  };
  const bool a_from_extent = !edges.from_boundary_a && !(from_leaf && edges.from_boundary_b);
  const bool b_from_extent = !edges.from_boundary_b && !(from_leaf && edges.from_boundary_a);
  const double casing_a = a_from_extent && through(a, b) ? 0.0 : casing;
  const double casing_b = b_from_extent && through(b, a) ? 0.0 : casing;
  double t0 = std::clamp(a + casing_a, 0.0, len), t1 = std::clamp(b - casing_b, 0.0, len);
  if (t1 - t0 < o.min_opening_width_m) return std::nullopt;
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
  // A strip thinner than its casings has no clear opening (and plan.json
  // refuses a height ≤ 0); door labels that all stay near the floor are a
  // misread floor or rug, not a door (their highest point: a point file's
  // rows may be further apart than the binned extent bridges).
  if (*op.height <= 0.0 || (door && zs.back() <= o.min_door_height_m)) return std::nullopt;
  // ±: each edge's variance plus the casing-width uncertainty.
  const double casing_var = o.casing_sigma_m * o.casing_sigma_m;
  op.width_sigma_m = std::sqrt(edges.var_a + edges.var_b + 2 * casing_var);
  spdlog::debug("plan: wall {} {} width {:.3f} ± {:.3f} m, edges from {} and {}", wi, door ? "door" : "window",
                op.width, *op.width_sigma_m, EdgeOrigin(edges.from_boundary_a, from_leaf),
                EdgeOrigin(edges.from_boundary_b, from_leaf));
  double zspacing = (z1 - z0) / group.size();
  double zedge_var = mean_var / n_edge + zspacing * zspacing + o.casing_sigma_m * o.casing_sigma_m;
  op.height_sigma_m = std::sqrt((door ? 1 : 2) * zedge_var);
  op.sill_sigma_m = door ? 0.0 : std::sqrt(zedge_var);
  return op;
}

// A door and a window cannot fill the same stretch of one wall (a window
// over a door, a transom, stands above the door's head): where they
// overlap along the wall by more than half the narrower and in height, the
// one with fewer points was misread (a window's frame labelled door, door
// labels on the floor below a window) and is dropped.
void DropOverlappingOpenings(const std::vector<PlanWall>& walls, const std::vector<std::size_t>& support,
                             std::vector<PlanOpening>& openings) {
  constexpr double kMinOverlap = 0.5;
  auto span = [&](const PlanOpening& op) {
    const Vec2 d = (walls[op.wall].end - walls[op.wall].start).normalized();
    const double a = (op.start - walls[op.wall].start).dot(d), b = (op.end - walls[op.wall].start).dot(d);
    return std::pair{std::min(a, b), std::max(a, b)};
  };
  std::vector<bool> drop(openings.size(), false);
  for (std::size_t i = 0; i < openings.size(); ++i) {
    for (std::size_t j = i + 1; j < openings.size(); ++j) {
      const PlanOpening &a = openings[i], &b = openings[j];
      if (a.wall != b.wall || a.kind == b.kind || drop[i] || drop[j]) continue;
      const auto [a0, a1] = span(a);
      const auto [b0, b1] = span(b);
      const double along = std::min(a1, b1) - std::max(a0, b0);
      if (along <= kMinOverlap * std::min(a1 - a0, b1 - b0)) continue;
      const double a_bottom = a.sill.value_or(0.0), b_bottom = b.sill.value_or(0.0);
      const double a_top = a_bottom + a.height.value_or(0.0), b_top = b_bottom + b.height.value_or(0.0);
      if (std::min(a_top, b_top) <= std::max(a_bottom, b_bottom)) continue;  // One above the other.
      drop[support[i] >= support[j] ? j : i] = true;
    }
  }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < openings.size(); ++i) {
    if (drop[i]) {
      spdlog::debug("plan: wall {} {} {:.2f} m wide dropped: it overlaps a better-supported opening", openings[i].wall,
                    openings[i].kind == OpeningKind::kDoor ? "door" : "window", openings[i].width);
      continue;
    }
    openings[kept++] = openings[i];
  }
  openings.resize(kept);
}

// A segmenter may paint a band of door down a plain wall from the ceiling,
// with the wall seen and labelled wall below it. A doorway shows no wall
// low on its face (0.1–1 m up: its leaf, or the room beyond, or the floor
// through it), so a door whose clear span shows mostly wall there is no
// door. Bins of 10 cm across the span: a bin is wall where at least 3 wall
// points at the face (within opening_band_m behind it, 0.1 m in front) and
// more than twice its door points stand there; a floor contact of the wall
// (the wall's base seen in that column: a panorama's wall points) counts 3.
bool WallBelowDoor(const PlanOpening& op, const PlanWall& w, const WallPoints& wall_points,
                   const std::vector<OpeningPoint>& door_points, const PlanOptions& o) {
  constexpr double kBin = 0.1, kLow = 0.1, kHigh = 1.0, kFront = 0.1;
  constexpr int kMinWallPoints = 3;
  const double len = w.Length();
  if (o.door_wall_below_share >= 1.0 || len < 1e-9) return false;
  const Vec2 d = (w.end - w.start) / len, inward(-d.y(), d.x());
  const double a = std::min(d.dot(op.start - w.start), d.dot(op.end - w.start));
  const double b = std::max(d.dot(op.start - w.start), d.dot(op.end - w.start));
  const int bins = static_cast<int>(std::floor((b - a) / kBin));
  if (bins < 1) return false;
  std::vector<int> wall(bins, 0), door(bins, 0);
  auto bin_of = [&](double t) { return static_cast<int>(std::floor((t - a) / kBin)); };
  for (const WallPoint& p : wall_points.points) {
    const bool floor_contact = p.contact && p.z < kLow;
    if (!floor_contact && (p.z < kLow || p.z > kHigh)) continue;
    const double r = inward.dot(p.p - w.start);
    if (r > kFront || r < -o.opening_band_m) continue;
    const int i = bin_of(d.dot(p.p - w.start));
    if (i >= 0 && i < bins) wall[i] += floor_contact ? kMinWallPoints : 1;
  }
  for (const OpeningPoint& p : door_points) {
    const int i = bin_of(p.t);
    if (p.z >= kLow && p.z <= kHigh && i >= 0 && i < bins) ++door[i];
  }
  int wall_bins = 0;
  for (int i = 0; i < bins; ++i) wall_bins += wall[i] >= kMinWallPoints && wall[i] > 2 * door[i];
  return wall_bins > o.door_wall_below_share * bins;
}

}  // namespace

FoundOpenings FindOpenings(const std::vector<const ClassPoint*>& points, const std::vector<PlanWall>& walls,
                           const Vec2& viewpoint, const PlanOptions& o, const WallPoints* wall_points) {
  FoundOpenings out;
  const std::vector<std::vector<Vec2>> leaf_pts = LeafPointsPerWall(points, walls, o);
  std::vector<std::vector<OpeningPoint>> per_wall_kind = ProjectOntoWalls(points, walls, viewpoint, o);
  std::vector<std::size_t> support;  // Per opening found, its points.
  for (size_t slot = 0; slot < per_wall_kind.size(); ++slot) {
    if (per_wall_kind[slot].empty()) continue;
    const int wi = static_cast<int>(slot / 2);
    const bool door = slot % 2 == 0;
    for (const std::vector<OpeningPoint>& group : GroupAlongWall(per_wall_kind[slot], o)) {
      if (auto op = MeasureOpening(group, wi, walls[wi], door, leaf_pts[wi], viewpoint, o, out.door_leaves)) {
        if (door && wall_points && WallBelowDoor(*op, walls[wi], *wall_points, per_wall_kind[slot], o)) {
          spdlog::debug("plan: wall {} door {:.2f} m wide dropped: wall seen low across it", wi, op->width);
          continue;
        }
        out.openings.push_back(*op);
        support.push_back(group.size());
      }
    }
  }
  DropOverlappingOpenings(walls, support, out.openings);
  std::stable_sort(out.openings.begin(), out.openings.end(), [&](const PlanOpening& a, const PlanOpening& b) {
    if (a.wall != b.wall) return a.wall < b.wall;
    return (a.start - walls[a.wall].start).norm() < (b.start - walls[b.wall].start).norm();
  });
  return out;
}

}  // namespace asbuilt
