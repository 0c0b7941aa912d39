#include "asbuilt/plan/plan_ring.h"

#include "asbuilt/plan/plan_ring_visible.h"

#include <algorithm>
#include <limits>
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace asbuilt {
namespace {

constexpr double kRingInf = std::numeric_limits<double>::infinity();
// A vertex is looked for up to this far beyond a line's end along its line, m.
constexpr double kVertexReach = 8.0;
// A vertex up to this far inside a line's extent still counts as beyond it, m.
constexpr double kVertexSlack = 0.1;
// Vertices less precise than this (farther than about 6 m) do not decide corners, m.
constexpr double kMaxVertexSigma = 0.12;

// The capture centre when known, else the length-weighted centre of the lines.
Vec2 RingViewpoint(const std::vector<WallLine>& lines, const PlanOptions& o) {
  Vec2 view = Vec2::Zero();
  if (o.viewpoint_m) {
    view = o.viewpoint_m->head<2>();
  } else {
    double sw = 0;
    for (const WallLine& l : lines) {
      double len = l.t_max - l.t_min;
      view += len * 0.5 * (l.Start() + l.End());
      sw += len;
    }
    view /= sw;
  }
  return view;
}

// A line with the bearing of its middle and the angle it subtends, seen from
// the viewpoint, rad.
struct OrderedLine {
  WallLine line;
  double mid_angle;
  double span;
};

// Orients each line counter-clockwise around `view`, drops lines mostly
// hidden behind or in front of a much better supported one in the same
// viewing directions (clutter: visible wall surfaces do not overlap in angle
// seen from the capture point), and orders the rest by bearing.
std::vector<WallLine> OrderAroundViewpoint(std::vector<WallLine> lines, const Vec2& view, double strong) {
  std::vector<OrderedLine> ordered;
  for (WallLine& l : lines) {
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
  std::vector<bool> drop(ordered.size(), false);
  for (size_t a = 0; a < ordered.size(); ++a) {
    for (size_t b = 0; b < ordered.size(); ++b) {
      if (a == b || drop[b]) continue;
      double d = std::abs(WrapAngle(ordered[a].mid_angle - ordered[b].mid_angle));
      double overlap =
          std::min(ordered[a].span, ordered[b].span) / 2 + std::max(ordered[a].span, ordered[b].span) / 2 - d;
      overlap = std::min(overlap, std::min(ordered[a].span, ordered[b].span));
      if (overlap > 0.5 * ordered[a].span && ordered[a].line.votes * 3 < ordered[b].line.votes &&
          ordered[a].line.votes < strong) {
        drop[a] = true;
      }
    }
  }
  std::vector<OrderedLine> kept;
  for (size_t i = 0; i < ordered.size(); ++i) {
    if (!drop[i]) kept.push_back(std::move(ordered[i]));
  }
  std::sort(kept.begin(), kept.end(),
            [](const OrderedLine& a, const OrderedLine& b) { return a.mid_angle < b.mid_angle; });
  std::vector<WallLine> ring;
  for (OrderedLine& e : kept) ring.push_back(std::move(e.line));
  return ring;
}

// A line seen between two pieces of one wall and wholly behind that wall's
// line was seen through the wall's openings (ground contacts outside a
// window, a neighbouring room through a door): not this room's wall. The
// pieces then meet and merge later. (One piece alone is no evidence: the
// end wall of an L's far wing lies behind the line of the cut wall.)
void DropLinesSeenThroughAWall(std::vector<WallLine>& ring, const Vec2& view, double strong, const PlanOptions& o) {
  for (size_t i = 0; ring.size() > 3 && i < ring.size();) {
    const WallLine& before = ring[(i + ring.size() - 1) % ring.size()];
    const WallLine& after = ring[(i + 1) % ring.size()];
    const WallLine& l = ring[i];
    auto behind = [&](const Vec2& p) {
      // Farther from the viewpoint than the wall's line along the ray to p.
      const double den = before.Normal().dot(p - view);
      if (std::abs(den) < 1e-9) return false;
      const double s_line = before.Normal().dot(before.c - view) / den;
      return s_line > 0 && s_line < 1 - 2 * o.epsilon_m / std::max(1e-9, (p - view).norm());
    };
    if (CollinearLines(before, after, o) && !CollinearLines(before, l, o) && behind(l.Start()) && behind(l.End()) &&
        l.votes < strong) {
      spdlog::debug("plan: dropped a line seen through a wall's openings: ({:.3f}, {:.3f}) → ({:.3f}, {:.3f})",
                    l.Start().x(), l.Start().y(), l.End().x(), l.End().y());
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
      continue;
    }
    ++i;
  }
}

// A room vertex: a wall–wall corner column, seen in one or more frames.
struct RoomVertex {
  Vec2 p = Vec2::Zero();
  double sigma = 0;
  int points = 0;
};

// Vertex points of all frames, clustered greedily (most precise first) within
// max(15 cm, 3σ); each cluster at the 1/σ²-weighted mean of its points, with
// σ from their σ and their spread.
std::vector<RoomVertex> ClusterVertices(std::vector<VertexPoint> pts) {
  std::sort(pts.begin(), pts.end(), [](const VertexPoint& a, const VertexPoint& b) { return a.sigma < b.sigma; });
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
  std::vector<RoomVertex> out;
  for (const Acc& a : acc) {
    const Vec2 m = a.Mean();
    double spread = 0;
    for (const Vec2& p : a.members) spread += (p - m).squaredNorm();
    spread /= static_cast<double>(a.members.size());
    out.push_back({m, std::sqrt(1 / a.w + spread), static_cast<int>(a.members.size())});
  }
  return out;
}

// The room vertices precise enough to decide corners, and how they relate to
// lines.
struct RoomVertices {
  std::vector<RoomVertex> all;

  // A vertex belongs to a line when it lies in its band, max(10 cm, 3σ).
  static bool OnLine(const WallLine& l, const RoomVertex& v) {
    return std::abs(l.Distance(v.p)) <= std::max(0.1, 3 * v.sigma);
  }
  // The vertex on `l` it reaches first beyond its end, up to kVertexReach;
  // nullptr when none.
  const RoomVertex* After(const WallLine& l) const {
    const RoomVertex* best = nullptr;
    double best_t = kRingInf;
    for (const RoomVertex& v : all) {
      const double t = l.Dir().dot(v.p - l.c);
      if (OnLine(l, v) && t > l.t_max - kVertexSlack && t < l.t_max + kVertexReach && t < best_t) {
        best = &v, best_t = t;
      }
    }
    return best;
  }
  // The vertex on `l` it reaches first before its start; nullptr when none.
  const RoomVertex* Before(const WallLine& l) const {
    const RoomVertex* best = nullptr;
    double best_t = -kRingInf;
    for (const RoomVertex& v : all) {
      const double t = l.Dir().dot(v.p - l.c);
      if (OnLine(l, v) && t < l.t_min + kVertexSlack && t > l.t_min - kVertexReach && t > best_t) {
        best = &v, best_t = t;
      }
    }
    return best;
  }
};

RoomVertices FindRoomVertices(const std::vector<VertexPoint>& vertex_points) {
  RoomVertices vertices{ClusterVertices(vertex_points)};
  std::erase_if(vertices.all, [](const RoomVertex& v) { return v.sigma > kMaxVertexSigma; });
  if (!vertices.all.empty()) {
    spdlog::debug("plan: {} room vertices from {} vertex points", vertices.all.size(), vertex_points.size());
    for (const RoomVertex& v : vertices.all) {
      spdlog::debug("  vertex ({:.3f}, {:.3f}) ±{:.3f} m, {} points", v.p.x(), v.p.y(), v.sigma, v.points);
    }
  }
  return vertices;
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

// A vertex on the extensions of two lines two or three places apart in the
// ring is their corner; weak lines between them, wholly behind the two
// walls' extensions to it, were seen through those walls' openings (ground
// contacts outside a window) and are dropped.
void JoinAcrossVertices(std::vector<WallLine>& ring, const RoomVertices& vertices, const Vec2& view, double strong,
                        const PlanOptions& o) {
  for (size_t i = 0; ring.size() > 3 && i < ring.size(); ++i) {
    const RoomVertex* v = vertices.After(ring[i]);
    if (!v) continue;
    bool cut = false;
    for (size_t k = 2; k <= 3 && k + 1 < ring.size() && !cut; ++k) {
      const size_t j = (i + k) % ring.size();
      const WallLine& a = ring[i];
      const WallLine& c = ring[j];
      if (std::abs(AngleDiffModPi(a.theta, c.theta)) <= DegToRad(o.parallel_max_deg) || !RoomVertices::OnLine(c, *v) ||
          c.Dir().dot(v->p - c.c) > c.t_min + kVertexSlack) {
        continue;
      }
      bool hidden = true;
      for (size_t m = 1; m < k && hidden; ++m) {
        const WallLine& b = ring[(i + m) % ring.size()];
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
}

// Merges ring neighbours that continue each other (one wall seen in pieces),
// at the better supported one's direction and σ. Two pieces of one wall with
// up to kMaxWobbleLines short lines between them, every end of which lies
// within the two pieces' collinearity band of the merged line, are one wall
// too: a floor edge misread along one wall (furniture, a door's casing, a
// label that frays) wobbles about it in steps no deeper than its own noise.
void MergeRingNeighbours(const std::vector<WallPoint>& pts, std::vector<WallLine>& ring, const PlanOptions& o) {
  constexpr size_t kMaxWobbleLines = 6;
  auto try_merge = [&](size_t i, size_t k) {
    const size_t n = ring.size(), j = (i + k) % n;
    if (k > 1 && n - k < 3) return false;
    if (!CollinearLines(ring[i], ring[j], o)) return false;
    std::vector<int> all = ring[i].members;
    for (size_t m = 1; m <= k; ++m) {
      const std::vector<int>& more = ring[(i + m) % n].members;
      all.insert(all.end(), more.begin(), more.end());
    }
    const WallLine& big = ring[i].votes >= ring[j].votes ? ring[i] : ring[j];
    WallLine fit = FitWallLine(pts, std::move(all), big.theta, o.max_independent_points, o.max_gap_m);
    const double band = CollinearTolerance(ring[i], ring[j], o);
    for (size_t m = 1; m < k; ++m) {
      const WallLine& wobble = ring[(i + m) % n];
      if (std::abs(fit.Distance(wobble.Start())) >= band || std::abs(fit.Distance(wobble.End())) >= band) return false;
    }
    fit.var_theta = big.var_theta;
    ring[i] = std::move(fit);
    for (size_t m = 1; m <= k; ++m) {
      const size_t e = i + 1 < ring.size() ? i + 1 : 0;  // What follows i, wrapping.
      ring.erase(ring.begin() + e);
      if (e < i) --i;
    }
    return true;
  };
  for (bool merged = true; merged && ring.size() > 2;) {
    merged = false;
    for (size_t k = 1; k <= kMaxWobbleLines + 1 && !merged; ++k) {
      for (size_t i = 0; i < ring.size() && ring.size() > 2 && k < ring.size() && !merged; ++i)
        merged = try_merge(i, k);
    }
  }
}

// Makes `c` an inferred wall along its line, pointing along `toward`, from
// `from` to `to`, as high as `z_top`.
void FinishConnector(WallLine& c, const Vec2& from, const Vec2& to, const Vec2& toward, double z_top) {
  c.inferred = true;
  if (c.Dir().dot(toward) < 0) c.theta = WrapAngle(c.theta + kPi);
  c.t_min = c.Dir().dot(from - c.c);
  c.t_max = c.Dir().dot(to - c.c);
  c.z_top = z_top;
}

// One gap in the ring: from line a's end (or the vertex it goes on to, va)
// to line b's start (or the vertex vb), p → q.
struct RingGap {
  const WallLine& a;
  const WallLine& b;
  const RoomVertex* va;
  const RoomVertex* vb;
  Vec2 p, q;
  Vec2 gap;  // q − p, or b's direction when p = q.
  double z_top() const { return 0.5 * (a.z_top + b.z_top); }
};

// Both ends at vertices, the gap running across the dominant directions
// (more than 20° off the nearest): two walls are missing, not one. The wall
// turns at each vertex (the dominant direction across a at va, across b at
// vb, each the one nearer the gap), and the two connectors meet where those
// lines cross (a small room's two near plain walls that gave no points: one
// connector from corner to corner would cut the room in half). nullopt when
// that does not apply.
std::optional<std::pair<WallLine, WallLine>> TwoConnectors(const RingGap& g, const std::vector<Direction>& dirs,
                                                           const PlanOptions& o) {
  const double gap_theta = std::atan2(g.gap.y(), g.gap.x());
  auto off = [&](const Direction& d) { return std::abs(AngleDiffModPi(gap_theta, d.theta)); };
  auto turn = [&](const WallLine& l) -> const Direction* {  // Across l, nearest the gap.
    const Direction* best = nullptr;
    for (const Direction& d : dirs) {
      if (std::abs(AngleDiffModPi(l.theta, d.theta)) <= DegToRad(o.parallel_max_deg)) continue;
      if (!best || off(d) < off(*best)) best = &d;
    }
    return best;
  };
  const Direction* da = turn(g.a);
  const Direction* db = turn(g.b);
  if (!(da && db && std::min(off(*da), off(*db)) > DegToRad(20.0) &&
        std::abs(AngleDiffModPi(da->theta, db->theta)) > DegToRad(o.parallel_max_deg))) {
    return std::nullopt;
  }
  WallLine c1, c2;
  c1.c = g.p, c1.theta = da->theta, c1.var_theta = da->Var(), c1.var_rho = g.va->sigma * g.va->sigma;
  c2.c = g.q, c2.theta = db->theta, c2.var_theta = db->Var(), c2.var_rho = g.vb->sigma * g.vb->sigma;
  const std::optional<Vec2> corner = IntersectLines(c1, c2);
  if (!(corner && (*corner - g.p).dot(g.gap) > 0 && (g.q - *corner).dot(g.gap) > 0)) return std::nullopt;
  FinishConnector(c1, g.p, *corner, *corner - g.p, g.z_top());
  FinishConnector(c2, *corner, g.q, g.q - *corner, g.z_top());
  spdlog::debug(
      "plan: two connectors through vertices ({:.3f}, {:.3f}) → ({:.3f}, {:.3f}), turning at "
      "({:.3f}, {:.3f})",
      g.p.x(), g.p.y(), g.q.x(), g.q.y(), corner->x(), corner->y());
  return std::pair{std::move(c1), std::move(c2)};
}

// The one connector of a gap: through the gap's middle (or from the vertex
// at its end), in the nearest dominant direction to the gap when one is
// close (from a vertex the wall turns: the nearest among those across the
// vertex's own line), else along the gap. With neither end at a vertex, a
// vertex in the gap on neither line is the missing wall's own corner column,
// seen where the rest of it was hidden: the connector runs through it.
WallLine OneConnector(const RingGap& g, const RoomVertices& vertices, const std::vector<Direction>& dirs,
                      const PlanOptions& o) {
  const WallLine& a = g.a;
  const WallLine& b = g.b;
  const RoomVertex* va = g.va;
  const RoomVertex* vb = g.vb;
  const Vec2& p = g.p;
  const Vec2& q = g.q;
  WallLine c;
  c.c = va && !vb ? p : vb && !va ? q : 0.5 * (p + q);
  c.theta = std::atan2(g.gap.y(), g.gap.x());
  c.var_theta = DegToRad(5.0) * DegToRad(5.0);
  c.var_rho = 0.05 * 0.05;
  const WallLine* turned = va ? &a : vb ? &b : nullptr;
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
  if (!va && !vb) {
    const RoomVertex* inside = nullptr;
    for (const RoomVertex& v : vertices.all) {
      if (RoomVertices::OnLine(a, v) || RoomVertices::OnLine(b, v)) continue;
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
  FinishConnector(c, p, q, g.gap, g.z_top());  // From a towards b.
  if (va || vb) {
    c.var_rho = std::pow(va && vb ? std::min(va->sigma, vb->sigma) : (va ? va : vb)->sigma, 2);
    spdlog::debug("plan: connector through vertices ({}) → ({})",
                  va ? fmt::format("{:.3f}, {:.3f}", va->p.x(), va->p.y()) : "none",
                  vb ? fmt::format("{:.3f}, {:.3f}", vb->p.x(), vb->p.y()) : "none");
  }
  return c;
}

// Closes the ring between a = ring[i] and b = ring[i + 1]. `closed` ends
// with a's copy; `b_copy` is b's (already in `closed` when b is its first
// wall, else ring[i + 1] itself). Either end may be extended; connecting
// walls are appended to `closed`. Returns how many were inferred.
int CloseGap(const WallLine& a, const WallLine& b, WallLine& b_copy, std::vector<WallLine>& closed,
             const RoomVertices& vertices, const std::vector<Direction>& dirs, const PlanOptions& o) {
  const double ext = o.max_corner_extension_m;
  auto plausible = [&](const Vec2& x) {
    double ta = a.Dir().dot(x - a.c), tb = b.Dir().dot(x - b.c);
    return ta > a.t_min && ta < a.t_max + ext && tb < b.t_max && tb > b.t_min - ext;
  };
  bool meet = std::abs(AngleDiffModPi(a.theta, b.theta)) > DegToRad(o.parallel_max_deg);
  std::optional<Vec2> x = meet ? IntersectLines(a, b) : std::nullopt;
  if (x && plausible(*x)) return 0;
  // A vertex on both lines where they meet: their corner, however far
  // beyond their points.
  if (x) {
    const double ta = a.Dir().dot(*x - a.c), tb = b.Dir().dot(*x - b.c);
    const bool at_corner = std::any_of(vertices.all.begin(), vertices.all.end(), [&](const RoomVertex& v) {
      return RoomVertices::OnLine(a, v) && RoomVertices::OnLine(b, v) &&
             (v.p - *x).norm() <= std::max(0.2, 3 * v.sigma);
    });
    if (at_corner && ta > a.t_min && tb < b.t_max) {
      closed.back().t_max = std::max(a.t_max, ta);
      b_copy.t_min = std::min(b.t_min, tb);
      spdlog::debug("plan: a vertex places the corner at ({:.3f}, {:.3f})", x->x(), x->y());
      return 0;
    }
  }
  // Where a line's extension reaches a vertex, the line goes on to it and
  // the connector starts (or ends) there. A vertex that takes the
  // connector's end farther from the other line's end is some other corner
  // on the line's extension, not the one this gap closes.
  const RoomVertex* va = vertices.After(a);
  const RoomVertex* vb = vertices.Before(b);
  const double raw_gap = (b.Start() - a.End()).norm();
  if (va && (b.Start() - va->p).norm() > raw_gap + kVertexSlack) va = nullptr;
  if (vb && (vb->p - a.End()).norm() > raw_gap + kVertexSlack) vb = nullptr;
  RingGap g{a, b, va, vb, va ? va->p : a.End(), vb ? vb->p : b.Start(), Vec2::Zero()};
  g.gap = g.q - g.p;
  if (g.gap.norm() < 1e-6) g.gap = b.Dir();
  if (va && vb) {
    if (auto two = TwoConnectors(g, dirs, o)) {
      closed.back().t_max = std::max(a.t_max, a.Dir().dot(g.p - a.c));
      b_copy.t_min = std::min(b.t_min, b.Dir().dot(g.q - b.c));
      closed.push_back(std::move(two->first));
      closed.push_back(std::move(two->second));
      return 2;
    }
  }
  WallLine c = OneConnector(g, vertices, dirs, o);
  // A connector along a neighbour's own line is that wall seen only in
  // part (its points stop short of the corner, past furniture): the wall
  // goes on to where its line meets the other neighbour — when that is
  // where the other's points end — and no wall is inferred.
  if (x) {
    const double ta = a.Dir().dot(*x - a.c), tb = b.Dir().dot(*x - b.c);
    auto along = [&](const WallLine& l) { return std::abs(AngleDiffModPi(l.theta, c.theta)) <= DegToRad(3.0); };
    if (along(b) && ta > a.t_min && ta < a.t_max + ext && tb < b.t_min) {
      b_copy.t_min = tb;
      return 0;
    }
    if (along(a) && tb > b.t_min - ext && tb < b.t_max && ta > a.t_max) {
      closed.back().t_max = ta;  // a's copy.
      return 0;
    }
  }
  if (va) closed.back().t_max = std::max(a.t_max, a.Dir().dot(va->p - a.c));
  if (vb) b_copy.t_min = std::min(b.t_min, b.Dir().dot(vb->p - b.c));
  closed.push_back(std::move(c));
  return 1;
}

}  // namespace

Ring CloseRoom(const WallPoints& walls, std::vector<WallLine> lines, const std::vector<VertexPoint>& vertex_points,
               const DirectionFrame& frame, const PlanOptions& o) {
  const double strong = walls.strong_line_votes;
  if (o.one_viewpoint) lines = SelectVisibleLines(walls, std::move(lines), frame, o);
  Ring out;
  out.viewpoint = RingViewpoint(lines, o);
  const Vec2& view = out.viewpoint;
  std::vector<WallLine> ring = OrderAroundViewpoint(std::move(lines), view, strong);
  spdlog::debug("plan: viewpoint ({:.3f}, {:.3f})", view.x(), view.y());
  DropLinesSeenThroughAWall(ring, view, strong, o);
  const RoomVertices vertices = FindRoomVertices(vertex_points);
  JoinAcrossVertices(ring, vertices, view, strong, o);
  MergeRingNeighbours(walls.points, ring, o);
  std::vector<WallLine> closed;
  for (size_t i = 0; i < ring.size(); ++i) {
    closed.push_back(ring[i]);
    WallLine& b_copy = i + 1 == ring.size() ? closed.front() : ring[i + 1];  // b, or its copy already closed.
    out.inferred_walls += CloseGap(ring[i], ring[(i + 1) % ring.size()], b_copy, closed, vertices, frame.directions, o);
  }
  out.walls = std::move(closed);
  LogWallLines("closed ring", out.walls);
  return out;
}

std::vector<Vec2> RingCorners(const std::vector<WallLine>& ring) {
  const int n = static_cast<int>(ring.size());
  std::vector<Vec2> c(n);
  for (int i = 0; i < n; ++i) {
    const WallLine& a = ring[(i + n - 1) % n];
    const WallLine& b = ring[i];
    std::optional<Vec2> x;
    if (std::abs(AngleDiffModPi(a.theta, b.theta)) > DegToRad(1.0)) x = IntersectLines(a, b);
    c[i] = x ? *x : 0.5 * (a.End() + b.Start());
  }
  return c;
}

}  // namespace asbuilt
