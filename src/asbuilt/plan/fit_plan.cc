#include "asbuilt/plan/fit_plan.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

#include "asbuilt/geometry/polygon.h"
#include "asbuilt/plan/plan_stages.h"
#include "asbuilt/plan/plan_uncertainty.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// The position σ of a corner a person placed, m: it enters the ± of the
// walls through it.
constexpr double kFixedCornerSigmaM = 0.01;

// Stages 1–4 on points that this holder owns (the stages point into them).
struct StagesHolder {
  std::vector<ClassPoint> points;
  RingStages stages;
  std::vector<double> bearings;  // Per wall point, around the ring's viewpoint, rad.
};

std::unique_ptr<StagesHolder> RunStages(std::vector<ClassPoint> points, const PlanOptions& o,
                                        const std::string& source) {
  auto h = std::make_unique<StagesHolder>();
  h->points = std::move(points);
  h->stages = FitRingStages(h->points, o, source);
  const Vec2 v = h->stages.ring.viewpoint;
  for (const WallPoint& p : h->stages.planar.walls.points) {
    h->bearings.push_back(std::atan2(p.p.y() - v.y(), p.p.x() - v.x()));
  }
  return h;
}

// The points with every ceiling contact moved along its ray (from the
// camera of its frame) to height `ceiling_m`.
std::vector<ClassPoint> WithCeilingAt(const PlanInput& input, double ceiling_m) {
  std::vector<ClassPoint> out = input.points;
  for (ClassPoint& p : out) {
    if (p.source != PointSource::kContact || p.position_m.z() < kCeilingContactMinZ) continue;
    const auto frame =
        std::find_if(input.frames.begin(), input.frames.end(), [&](const PlanFrame& f) { return f.index == p.frame; });
    if (frame == input.frames.end()) continue;
    const Vec3 cam = frame->camera_m;
    const double above = p.position_m.z() - cam.z();
    if (above < 0.05) continue;
    CheckArgument(ceiling_m > cam.z() + 0.05,
                  fmt::format("PlanConstraints.ceiling_height_m = {:.3f}, must be above the camera ({:.3f} m)",
                              ceiling_m, cam.z()));
    const double scale = (ceiling_m - cam.z()) / above;
    const Vec2 xy = cam.head<2>() + scale * (p.position_m.head<2>() - cam.head<2>());
    p.position_m = Vec3(xy.x(), xy.y(), ceiling_m);
    p.sigma_m *= scale;
  }
  return out;
}

// Is angle x within the shorter arc from a to b (both ends included)?
bool InArc(double x, double a, double b) {
  const double span = WrapAngle(b - a), d = WrapAngle(x - a);
  return span >= 0 ? (d >= 0 && d <= span) : (d <= 0 && d >= span);
}

// The wall points seen between the bearings of corners a and b.
std::vector<int> SectorPoints(const StagesHolder& h, const Vec2& a, const Vec2& b) {
  const Vec2 v = h.stages.ring.viewpoint;
  const double ba = std::atan2(a.y() - v.y(), a.x() - v.x()), bb = std::atan2(b.y() - v.y(), b.x() - v.x());
  std::vector<int> idx;
  for (std::size_t k = 0; k < h.bearings.size(); ++k) {
    if (InArc(h.bearings[k], ba, bb)) idx.push_back(static_cast<int>(k));
  }
  return idx;
}

// Indices of idx within their inlier band of the line through p at θ.
std::vector<int> Inliers(const WallPoints& wp, const std::vector<int>& idx, const Vec2& p, double theta) {
  const Vec2 n = NormalOf(theta);
  std::vector<int> out;
  for (int k : idx) {
    if (std::abs(n.dot(wp.points[k].p - p)) <= wp.points[k].thr) out.push_back(k);
  }
  return out;
}

// θ of the weighted least-squares line through `anchor` (rotated about it)
// and its variance, as TlsDirection; nullopt with fewer than 2 points.
std::optional<std::pair<double, double>> DirectionThrough(const WallPoints& wp, const std::vector<int>& idx,
                                                          const Vec2& anchor, int max_independent) {
  if (idx.size() < 2) return std::nullopt;
  Eigen::Matrix2d m = Eigen::Matrix2d::Zero();
  for (int k : idx) {
    const Vec2 d = wp.points[k].p - anchor;
    m += wp.points[k].w * d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(m);
  const Vec2 dir = es.eigenvectors().col(1);
  const double chi2 = std::max(es.eigenvalues()(0), 0.0), swt2 = std::max(es.eigenvalues()(1), 1e-12);
  const int count = static_cast<int>(idx.size());
  const double reduced = count > 1 ? chi2 / (count - 1) : 1.0;
  const double correlation = std::max(1.0, static_cast<double>(count) / max_independent);
  return std::pair{std::atan2(dir.y(), dir.x()), reduced / swt2 * correlation};
}

// θ snapped to the nearest dominant direction when within the snap limit.
double Snapped(double theta, const DirectionFrame& frame, const PlanOptions& o) {
  const double limit = DegToRad(frame.manhattan ? o.manhattan_snap_max_deg : o.snap_max_deg);
  double best = theta, best_diff = limit;
  for (const Direction& d : frame.directions) {
    const double diff = std::abs(AngleDiffModPi(theta, d.theta));
    if (diff <= best_diff) {
      best_diff = diff;
      best = theta - AngleDiffModPi(theta, d.theta);
    }
  }
  return best;
}

// A line through `anchor` at θ with `members`, its extent from a to b.
WallLine AnchoredLine(const WallPoints& wp, const Vec2& anchor, double theta, double var_theta,
                      std::vector<int> members, const Vec2& a, const Vec2& b, double default_z_top) {
  WallLine l;
  l.c = anchor;
  l.theta = theta;
  if (l.Dir().dot(b - a) < 0) l.theta = WrapAngle(theta + kPi);
  l.var_theta = var_theta;
  l.var_rho = kFixedCornerSigmaM * kFixedCornerSigmaM;
  l.t_min = l.Dir().dot(a - anchor);
  l.t_max = l.Dir().dot(b - anchor);
  std::vector<double> zs;
  for (int k : members) {
    const double r = l.Distance(wp.points[k].p);
    l.chi2 += wp.points[k].w * r * r;
    l.sum_w += wp.points[k].w;
    l.votes += wp.points[k].vote;
    zs.push_back(wp.points[k].z);
  }
  std::sort(zs.begin(), zs.end());
  l.z_top = zs.empty() ? default_z_top : SortedQuantile(zs, 0.995);
  l.members = std::move(members);
  l.inferred = l.members.empty();
  return l;
}

// The wall from corner a to corner b through `anchor` (a or b), re-fitted
// from the sector's points: the candidate direction with most inlier votes,
// then least squares through the anchor, snapped, twice.
WallLine FitThroughAnchor(const StagesHolder& h, const std::vector<int>& sector, const Vec2& anchor, const Vec2& a,
                          const Vec2& b, const PlanOptions& o, double default_z_top) {
  const WallPoints& wp = h.stages.planar.walls;
  std::vector<double> candidates;
  for (const Direction& d : h.stages.frame.directions) candidates.push_back(d.theta);
  for (const WallLine& l : h.stages.ring.walls) candidates.push_back(l.theta);
  if ((b - a).norm() > 1e-6) candidates.push_back(std::atan2(b.y() - a.y(), b.x() - a.x()));
  double theta = candidates.back(), best = -1;
  for (double c : candidates) {
    const double votes = Votes(wp.points, Inliers(wp, sector, anchor, c));
    if (votes > best + 1e-9) {
      best = votes;
      theta = c;
    }
  }
  double var_theta = 0;
  std::vector<int> members = Inliers(wp, sector, anchor, theta);
  if (Votes(wp.points, members) < o.min_wall_points) {
    // Too little evidence: the wall runs to the other corner.
    theta = std::atan2(b.y() - a.y(), b.x() - a.x());
    return AnchoredLine(wp, anchor, theta, 0, {}, a, b, default_z_top);
  }
  for (int iteration = 0; iteration < 2; ++iteration) {
    const auto fit = DirectionThrough(wp, members, anchor, o.max_independent_points);
    if (!fit) break;
    theta = Snapped(fit->first, h.stages.frame, o);
    var_theta = theta == fit->first ? fit->second : 0.0;
    members = Inliers(wp, sector, anchor, theta);
  }
  return AnchoredLine(wp, anchor, theta, var_theta, std::move(members), a, b, default_z_top);
}

// The wall from free corner a to free corner b: the survey's line when a
// and b are its corners, else the survey line with most inlier votes in the
// sector, its offset refitted there.
WallLine FitBetweenFree(const StagesHolder& h, const std::vector<int>& sector, const std::vector<Vec2>& base_corners,
                        const Vec2& a, const Vec2& b, const PlanOptions& o, double default_z_top) {
  const WallPoints& wp = h.stages.planar.walls;
  const std::vector<WallLine>& base = h.stages.ring.walls;
  const int n = static_cast<int>(base.size());
  for (int k = 0; k < n; ++k) {
    if ((base_corners[k] - a).norm() < 1e-9 && (base_corners[(k + 1) % n] - b).norm() < 1e-9) return base[k];
  }
  double best = 0;
  std::optional<WallLine> chosen;
  for (const WallLine& l : base) {
    if (l.inferred) continue;
    std::vector<int> inl = Inliers(wp, sector, l.c, l.theta);
    const double votes = Votes(wp.points, inl);
    if (votes >= o.min_wall_points && votes > best) {
      best = votes;
      chosen = FitWallLine(wp.points, std::move(inl), l.theta, o.max_independent_points, o.max_gap_m);
    }
  }
  if (!chosen) {
    return AnchoredLine(wp, a, std::atan2(b.y() - a.y(), b.x() - a.x()), 0, {}, a, b, default_z_top);
  }
  WallLine l = *chosen;
  if (l.Dir().dot(b - a) < 0) {
    l.theta = WrapAngle(l.theta + kPi);
    std::swap(l.t_min, l.t_max);
    l.t_min = -l.t_min;
    l.t_max = -l.t_max;
  }
  return l;
}

// The ring through the given corners, and the corners the plan's walls run
// between (fixed ones as given, free ones where their walls cross).
std::pair<Ring, std::vector<Vec2>> ConstrainedRing(const StagesHolder& h, const std::vector<PlanCorner>& corners,
                                                   const PlanOptions& o) {
  const int n = static_cast<int>(corners.size());
  const std::vector<Vec2> base_corners = RingCorners(h.stages.ring.walls);
  double z_top = 0;
  for (const WallLine& l : h.stages.ring.walls) z_top = std::max(z_top, l.z_top);
  Ring ring{.viewpoint = h.stages.ring.viewpoint};
  for (int i = 0; i < n; ++i) {
    const PlanCorner& a = corners[i];
    const PlanCorner& b = corners[(i + 1) % n];
    const std::vector<int> sector = SectorPoints(h, a.xy_m, b.xy_m);
    WallLine line;
    if (a.fixed && b.fixed) {
      const double theta = std::atan2(b.xy_m.y() - a.xy_m.y(), b.xy_m.x() - a.xy_m.x());
      line = AnchoredLine(h.stages.planar.walls, a.xy_m, theta, 0,
                          Inliers(h.stages.planar.walls, sector, a.xy_m, theta), a.xy_m, b.xy_m, z_top);
    } else if (a.fixed || b.fixed) {
      line = FitThroughAnchor(h, sector, a.fixed ? a.xy_m : b.xy_m, a.xy_m, b.xy_m, o, z_top);
    } else {
      line = FitBetweenFree(h, sector, base_corners, a.xy_m, b.xy_m, o, z_top);
    }
    if (line.members.empty()) ++ring.inferred_walls;
    ring.walls.push_back(std::move(line));
  }
  std::vector<Vec2> xy(n);
  for (int i = 0; i < n; ++i) {
    const PlanCorner& c = corners[i];
    if (c.fixed) {
      xy[i] = c.xy_m;
      continue;
    }
    const WallLine& before = ring.walls[(i + n - 1) % n];
    const WallLine& after = ring.walls[i];
    std::optional<Vec2> x;
    if (std::abs(AngleDiffModPi(before.theta, after.theta)) > DegToRad(1.0)) x = IntersectLines(before, after);
    if (x && (*x - c.xy_m).norm() <= o.max_corner_extension_m) {
      xy[i] = *x;
    } else {
      // Parallel walls, or crossing far away: the hint, on each wall's line, halfway.
      const Vec2 on_before = c.xy_m - before.Distance(c.xy_m) * before.Normal();
      const Vec2 on_after = c.xy_m - after.Distance(c.xy_m) * after.Normal();
      xy[i] = 0.5 * (on_before + on_after);
    }
  }
  // A room that crosses itself more than its corners as given: the free
  // corners that moved most go back to their hints until it does not.
  std::vector<Vec2> hints;
  for (const PlanCorner& c : corners) hints.push_back(c.xy_m);
  const int allowed = PolygonCrossings(hints);
  if (PolygonCrossings(xy) > allowed) {
    std::vector<int> order;
    for (int i = 0; i < n; ++i) {
      if (!corners[i].fixed) order.push_back(i);
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return (xy[a] - hints[a]).norm() > (xy[b] - hints[b]).norm(); });
    for (int i : order) {
      xy[i] = hints[i];
      if (PolygonCrossings(xy) <= allowed) break;
    }
  }
  return {std::move(ring), std::move(xy)};
}

// Each opening on its nearest wall, ends projected onto it, ordered by
// wall, then along it.
std::vector<PlanOpening> PlaceOpenings(const std::vector<PlanUserOpening>& given, const std::vector<PlanWall>& walls) {
  std::vector<PlanOpening> out;
  if (walls.empty()) return out;
  for (const PlanUserOpening& g : given) {
    const Vec2 mid = 0.5 * (g.start_m + g.end_m);
    int best = 0;
    double best_d = INFINITY;
    for (std::size_t w = 0; w < walls.size(); ++w) {
      const Vec2 a = walls[w].start, d = walls[w].end - a;
      const double t = std::clamp(d.dot(mid - a) / std::max(d.squaredNorm(), 1e-12), 0.0, 1.0);
      const double dist = (a + t * d - mid).norm();
      if (dist < best_d) {
        best_d = dist;
        best = static_cast<int>(w);
      }
    }
    const PlanWall& w = walls[best];
    const double length = w.Length();
    const Vec2 dir = (w.end - w.start) / std::max(length, 1e-12);
    double t0 = std::clamp(dir.dot(g.start_m - w.start), 0.0, length);
    double t1 = std::clamp(dir.dot(g.end_m - w.start), 0.0, length);
    if (t0 > t1) std::swap(t0, t1);
    PlanOpening o{.kind = g.kind, .wall = best, .start = w.start + t0 * dir, .end = w.start + t1 * dir};
    o.width = t1 - t0;
    o.height = g.top_m - g.bottom_m;
    o.sill = g.bottom_m;
    out.push_back(o);
  }
  std::sort(out.begin(), out.end(), [&](const PlanOpening& a, const PlanOpening& b) {
    if (a.wall != b.wall) return a.wall < b.wall;
    return (a.start - walls[a.wall].start).norm() < (b.start - walls[b.wall].start).norm();
  });
  return out;
}

}  // namespace

PlanOptions ResolvePlanOptions(const PlanInput& input, const PlanOptions& options) {
  PlanOptions o = options;
  std::optional<Vec3> viewpoint;
  if (!input.frames.empty()) {
    Vec3 sum = Vec3::Zero();
    for (const PlanFrame& f : input.frames) sum += f.position_m;
    viewpoint = sum / static_cast<double>(input.frames.size());
  }
  if (!o.viewpoint_m) o.viewpoint_m = viewpoint;
  const bool scale_auto = !o.contact_scale_sigma;
  o = o.ForLabels(input.exact_labels);
  // A camera height off by δ scales every contact's distance by 1 + δ/h
  // (floor and ceiling alike: the ceiling's height comes from the same pairs).
  if (scale_auto && viewpoint && viewpoint->z() > 0.1 && std::isfinite(input.camera_height_sigma_m)) {
    o.contact_scale_sigma = std::hypot(*o.contact_scale_sigma, input.camera_height_sigma_m / viewpoint->z());
  }
  // The ceiling estimate's σ as a share of its height above the rig: a
  // ceiling contact's distance is proportional to H − h (docs/plan.md, "±").
  const double h_ceiling = input.ceiling_height_m, sigma = input.ceiling_height_sigma_m;
  if (viewpoint && std::isfinite(h_ceiling) && std::isfinite(sigma) && h_ceiling - viewpoint->z() > 0.1 &&
      !o.ceiling_scale_sigma) {
    o.ceiling_scale_sigma = sigma / (h_ceiling - viewpoint->z());
  }
  // One camera turning in place: every point was seen from the viewpoint.
  if (!o.one_viewpoint && input.one_camera && viewpoint) {
    bool one_spot = true;
    for (const PlanFrame& f : input.frames) {
      one_spot = one_spot && (f.position_m.head<2>() - viewpoint->head<2>()).norm() < 0.05;
    }
    o.one_viewpoint = one_spot;
  }
  return o;
}

void PlanConstraints::Check() const {
  CheckArgument(corners.empty() || corners.size() >= 3,
                fmt::format("PlanConstraints.corners: {} corner(s), a room needs at least 3", corners.size()));
  const int n = static_cast<int>(corners.size());
  for (int i = 0; i < n; ++i) {
    CheckArgument(corners[i].xy_m.allFinite(), fmt::format("PlanConstraints.corners[{}] is not finite", i));
  }
  if (ceiling_height_m) {
    CheckArgument(std::isfinite(*ceiling_height_m) && *ceiling_height_m > 0,
                  fmt::format("PlanConstraints.ceiling_height_m = {}, must be > 0", *ceiling_height_m));
  }
  if (openings) {
    for (std::size_t i = 0; i < openings->size(); ++i) {
      const PlanUserOpening& g = (*openings)[i];
      CheckArgument(g.start_m.allFinite() && g.end_m.allFinite() && std::isfinite(g.bottom_m) && std::isfinite(g.top_m),
                    fmt::format("PlanConstraints.openings[{}] is not finite", i));
      CheckArgument(g.top_m > g.bottom_m && g.bottom_m >= -0.05,
                    fmt::format("PlanConstraints.openings[{}]: head {:.3f} m must be above sill {:.3f} m >= 0", i,
                                g.top_m, g.bottom_m));
    }
  }
}

struct PlanFitter::State {
  PlanInput input;
  PlanOptions options;
  std::unique_ptr<StagesHolder> measured;  // Null when the points hold fewer than two walls,
  std::exception_ptr no_walls;             // and then why.
  // The stages at the last ceiling height asked for (a review changes it seldom).
  mutable std::optional<double> ceiling_m;
  mutable std::unique_ptr<StagesHolder> at_ceiling;
};

PlanFitter::PlanFitter(PlanInput input, const PlanOptions& options) : state_(std::make_unique<State>()) {
  state_->options = ResolvePlanOptions(input, options);
  state_->options.Check();
  state_->input = std::move(input);
  try {
    state_->measured = RunStages(state_->input.points, state_->options, state_->input.source);
  } catch (const Error&) {
    state_->no_walls = std::current_exception();  // Fit() without corners rethrows it; with corners it needs no points.
  }
}

PlanFitter::~PlanFitter() = default;
PlanFitter::PlanFitter(PlanFitter&&) noexcept = default;
PlanFitter& PlanFitter::operator=(PlanFitter&&) noexcept = default;

const PlanInput& PlanFitter::input() const { return state_->input; }
const PlanOptions& PlanFitter::options() const { return state_->options; }
Vec2 PlanFitter::viewpoint() const {
  if (state_->measured) return state_->measured->stages.ring.viewpoint;
  return state_->options.viewpoint_m ? Vec2(state_->options.viewpoint_m->head<2>()) : Vec2::Zero();
}

namespace {

// The plan of a person's corners alone (the points held no walls): straight
// walls between them, `height_m` high when known.
PlanResult PlanOfCorners(const std::vector<PlanCorner>& corners, std::optional<double> height_m) {
  PlanResult result;
  PlanRoom room;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    PlanWall w{.start = corners[i].xy_m, .end = corners[(i + 1) % corners.size()].xy_m, .height = height_m};
    result.plan.walls.push_back(w);
    room.polygon.push_back(corners[i].xy_m);
  }
  room.area_m2 = std::abs(PolygonArea(room.polygon));
  result.plan.rooms.push_back(room);
  result.summary.walls = static_cast<int>(result.plan.walls.size());
  result.summary.wall_inferred.assign(result.plan.walls.size(), false);
  return result;
}

}  // namespace

PlanResult PlanFitter::Fit(const PlanConstraints& constraints) const {
  constraints.Check();
  const auto start_time = std::chrono::steady_clock::now();
  const State& s = *state_;
  if (!s.measured) {
    if (constraints.corners.empty()) std::rethrow_exception(s.no_walls);
    PlanResult result = PlanOfCorners(constraints.corners, constraints.ceiling_height_m);
    if (constraints.openings) result.plan.openings = PlaceOpenings(*constraints.openings, result.plan.walls);
    result.summary.openings = static_cast<int>(result.plan.openings.size());
    return result;
  }
  const StagesHolder* h = s.measured.get();
  const bool new_ceiling =
      constraints.ceiling_height_m && !(std::abs(*constraints.ceiling_height_m - s.input.ceiling_height_m) < 1e-6);
  if (new_ceiling) {
    if (!s.ceiling_m || std::abs(*s.ceiling_m - *constraints.ceiling_height_m) > 1e-9) {
      s.at_ceiling.reset();
      s.ceiling_m.reset();
      s.at_ceiling = RunStages(WithCeilingAt(s.input, *constraints.ceiling_height_m), s.options, s.input.source);
      s.ceiling_m = *constraints.ceiling_height_m;
    }
    h = s.at_ceiling.get();
  }
  PlanResult result;
  const bool given_openings = constraints.openings.has_value();
  if (constraints.corners.empty()) {
    result = PlanFromRingStages(h->stages, h->stages.ring, s.options, nullptr, given_openings);
  } else {
    auto [ring, corners] = ConstrainedRing(*h, constraints.corners, s.options);
    result = PlanFromRingStages(h->stages, ring, s.options, &corners, given_openings);
  }
  if (given_openings) {
    result.plan.openings = PlaceOpenings(*constraints.openings, result.plan.walls);
    result.summary.openings = static_cast<int>(result.plan.openings.size());
    result.summary.door_leaves = 0;
  }
  if (constraints.ceiling_height_m) {
    for (PlanWall& w : result.plan.walls) w.height = *constraints.ceiling_height_m;
  }
  result.summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return result;
}

PlanResult FitPlan(const PlanInput& input, const PlanOptions& options, const PlanConstraints& constraints) {
  const auto start_time = std::chrono::steady_clock::now();
  PlanResult result = PlanFitter(input, options).Fit(constraints);
  result.summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return result;
}

}  // namespace asbuilt
