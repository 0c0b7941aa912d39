#include "asbuilt/plan/plan_lines.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace asbuilt {
namespace {

// Sequential RANSAC stops after this many hypotheses in a row gave no wall:
// each failure removes a clutter patch (points by a corner, furniture), and a
// far wall's few precise contacts may come only after several.
constexpr int kMaxRansacFailures = 12;

// The best line hypothesis of one RANSAC round: its normal n and offset ρ
// (points p with |n·p − ρ| inside their band are inliers) and its votes.
struct LineHypothesis {
  double votes = 0;
  Vec2 n = Vec2::UnitY();
  double rho = 0;
};

// Scores the line through a and b on `subset` (votes of the points in their
// band); keeps it in `best` when it holds more.
void ScoreHypothesis(const std::vector<WallPoint>& pts, const std::vector<int>& subset, const Vec2& a, const Vec2& b,
                     LineHypothesis& best) {
  Vec2 d = b - a;
  if (d.norm() < 0.1) return;
  Vec2 n = Vec2(-d.y(), d.x()).normalized();
  double rho = n.dot(a);
  double count = 0;
  for (int k : subset) count += std::abs(n.dot(pts[k].p) - rho) < pts[k].thr ? pts[k].vote : 0.0;
  if (count > best.votes) best = {count, n, rho};
}

// Scores ransac_iterations hypotheses on a random subset of `remaining`
// (ransac_subset_points of them), each through two points drawn by their
// votes: a few hundred precise contacts among thousands of noisy dense
// points still get paired. Returns the best and the subset's size.
std::pair<LineHypothesis, int> BestHypothesis(const std::vector<WallPoint>& pts, const std::vector<int>& remaining,
                                              const PlanOptions& o, std::mt19937_64& rng) {
  std::vector<int> subset = remaining;
  int m = std::min<int>(subset.size(), o.ransac_subset_points);
  for (int i = 0; i < m; ++i) {
    std::uniform_int_distribution<int> pick(i, static_cast<int>(subset.size()) - 1);
    std::swap(subset[i], subset[pick(rng)]);
  }
  subset.resize(m);
  std::vector<double> subset_votes;
  subset_votes.reserve(m);
  for (int k : subset) subset_votes.push_back(pts[k].vote);
  std::discrete_distribution<int> pick(subset_votes.begin(), subset_votes.end());
  LineHypothesis best;
  for (int it = 0; it < o.ransac_iterations; ++it) {
    const Vec2& a = pts[subset[pick(rng)]].p;
    const Vec2& b = pts[subset[pick(rng)]].p;
    ScoreHypothesis(pts, subset, a, b, best);
  }
  return {best, m};
}

// SplitMix64's finaliser: a well-mixed 64-bit hash.
std::uint64_t Mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// A point's sampling key (PlanOptions::one_viewpoint): the seed and its
// position rounded to kKeyCellM, hashed. It names the point whatever its
// index, so the draws do not move when other points come, go or change
// order, and a sub-millimetre change moves only the few points next to a
// cell's edge.
constexpr double kKeyCellM = 0.01;
std::uint64_t PointKey(const WallPoint& p, std::uint64_t seed) {
  auto cell = [](double v) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v / kKeyCellM))); };
  return Mix(Mix(Mix(seed ^ cell(p.p.x())) ^ cell(p.p.y())) ^ cell(p.z));
}

// Points with equal keys (one cell) ordered by position: no index decides.
bool KeyLess(const std::vector<WallPoint>& pts, const std::vector<std::uint64_t>& keys, int a, int b) {
  if (keys[a] != keys[b]) return keys[a] < keys[b];
  if (pts[a].p.x() != pts[b].p.x()) return pts[a].p.x() < pts[b].p.x();
  if (pts[a].p.y() != pts[b].p.y()) return pts[a].p.y() < pts[b].p.y();
  return pts[a].z < pts[b].z;
}

// BestHypothesis with draws tied to the points, not to a random stream:
// the subset is the ransac_subset_points smallest keys of `remaining`, and
// hypothesis i's two points win exponential races (each point's time
// −ln U / vote, U from its key and i: drawn by vote). A point that joins or
// leaves `remaining` changes only the draws it wins, so a change between
// rounds (one point more in a line's band) no longer reshuffles every later
// round's hypotheses, as a shared random stream does.
std::pair<LineHypothesis, int> BestKeyedHypothesis(const std::vector<WallPoint>& pts,
                                                   const std::vector<std::uint64_t>& keys,
                                                   const std::vector<int>& remaining, const PlanOptions& o) {
  std::vector<int> subset = remaining;
  const int m = std::min<int>(subset.size(), o.ransac_subset_points);
  auto less = [&](int a, int b) { return KeyLess(pts, keys, a, b); };
  std::nth_element(subset.begin(), subset.begin() + (m > 0 ? m - 1 : 0), subset.end(), less);
  subset.resize(m);
  std::sort(subset.begin(), subset.end(), less);
  const int draws = 2 * o.ransac_iterations;
  std::vector<double> first(draws, std::numeric_limits<double>::infinity());
  std::vector<int> winner(draws, -1);
  std::vector<std::uint64_t> salt(draws);
  for (int d = 0; d < draws; ++d) salt[d] = Mix(static_cast<std::uint64_t>(d));
  for (int k : subset) {
    if (pts[k].vote <= 0) continue;
    const std::uint64_t key = keys[k];
    const double inv_vote = 1.0 / pts[k].vote;
    for (int d = 0; d < draws; ++d) {
      const double u = (static_cast<double>(Mix(key ^ salt[d]) >> 11) + 0.5) * 0x1.0p-53;
      // −ln u ≥ 1 − u: most points lose a race without the logarithm (the
      // margin keeps a last-ulp difference from skipping a winner).
      if ((1.0 - u) * inv_vote > first[d] * (1.0 + 1e-12)) continue;
      const double t = -std::log(u) / pts[k].vote;
      if (t < first[d]) first[d] = t, winner[d] = k;
    }
  }
  LineHypothesis best;
  for (int it = 0; it < o.ransac_iterations; ++it) {
    if (winner[2 * it] < 0 || winner[2 * it + 1] < 0) continue;
    ScoreHypothesis(pts, subset, pts[winner[2 * it]].p, pts[winner[2 * it + 1]].p, best);
  }
  return {best, m};
}

// The points of `remaining` in the band of the hypothesis, refined twice by
// least squares while they carry min_wall_points votes.
std::vector<int> RefinedInliers(const std::vector<WallPoint>& pts, const std::vector<int>& remaining,
                                const LineHypothesis& h, const PlanOptions& o) {
  std::vector<int> inliers;
  auto collect = [&](const Vec2& n, double rho) {
    inliers.clear();
    for (int k : remaining) {
      if (std::abs(n.dot(pts[k].p) - rho) < pts[k].thr) inliers.push_back(k);
    }
  };
  collect(h.n, h.rho);
  for (int refine = 0; refine < 2 && Votes(pts, inliers) >= o.min_wall_points; ++refine) {
    WallLine fit = FitWallLine(pts, inliers, std::nullopt, o.max_independent_points, o.max_gap_m);
    collect(fit.Normal(), fit.Normal().dot(fit.c));
  }
  return inliers;
}

// What sequential RANSAC keeps between rounds.
struct RansacState {
  std::vector<WallLine> lines;
  std::vector<bool> taken;  // Per point: a member of an accepted line.
  double best_density = 0;  // Votes per metre of the densest wall so far.
};

// Splits a hypothesis' inliers into dense runs along their fitted line and
// accepts each run that is a wall (enough votes, long enough, dense enough,
// a large enough share of `total_votes`, or strong). Sorts `inliers` along
// the line. Returns whether any run was accepted.
bool AcceptRuns(const std::vector<WallPoint>& pts, std::vector<int>& inliers, double total_votes, double strong,
                const PlanOptions& o, RansacState& state) {
  WallLine fit = FitWallLine(pts, inliers, std::nullopt, o.max_independent_points, o.max_gap_m);
  Vec2 dir = fit.Dir();
  std::sort(inliers.begin(), inliers.end(),
            [&](int a, int b) { return dir.dot(pts[a].p - fit.c) < dir.dot(pts[b].p - fit.c); });
  std::vector<double> ts;
  for (int k : inliers) ts.push_back(dir.dot(pts[k].p - fit.c));
  bool accepted = false;
  for (auto [b, e] : DenseRuns(ts, o.max_gap_m)) {
    std::vector<int> run(inliers.begin() + b, inliers.begin() + e);
    const double run_votes = Votes(pts, run);
    if (run_votes < o.min_wall_points) continue;
    WallLine piece = FitWallLine(pts, run, std::nullopt, o.max_independent_points, o.max_gap_m);
    if (piece.t_max - piece.t_min < o.min_wall_length_m) continue;
    // Outliers that happen to line up are far sparser than any wall.
    // (Density is judged only for weakly supported lines: a near wall's
    // dense points outnumber a far wall's contacts by 100 per metre.)
    double density = run_votes / (piece.t_max - piece.t_min);
    if (density < o.min_relative_density * state.best_density && run_votes < strong) {
      continue;
    }
    if (run_votes < o.min_wall_fraction * total_votes && run_votes < strong) continue;
    state.best_density = std::max(state.best_density, density);
    for (int k : run) state.taken[k] = true;
    state.lines.push_back(std::move(piece));
    accepted = true;
  }
  return accepted;
}

// Sequential RANSAC over the wall points: lines with their members. Two
// passes: the floor/ceiling contacts alone first (precise, few, and on walls
// only — a far wall's few hundred must not wait for luck among a near wall's
// hundred thousand dense points), then every point not taken. Without
// contacts the plain algorithm: counts, no exemptions, 4 failures.
std::vector<WallLine> SequentialRansac(const WallPoints& walls, const PlanOptions& o, std::mt19937_64& rng) {
  std::vector<std::uint64_t> keys;
  if (o.one_viewpoint) {
    keys.reserve(walls.points.size());
    for (const WallPoint& p : walls.points) keys.push_back(PointKey(p, o.seed));
  }
  const std::vector<WallPoint>& pts = walls.points;
  const double total_votes = walls.TotalVotes();
  const double strong = walls.strong_line_votes;
  const int max_failures = walls.weigh_votes ? kMaxRansacFailures : 4;
  RansacState state;
  state.taken.assign(pts.size(), false);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> remaining;
    for (int k = 0; k < static_cast<int>(pts.size()); ++k) {
      if (!state.taken[k] && (pass == 1 || pts[k].contact)) remaining.push_back(k);
    }
    int failures = 0;
    while (static_cast<int>(remaining.size()) >= o.min_wall_points && state.lines.size() < 64 &&
           failures < max_failures) {
      const auto [best, m] =
          o.one_viewpoint ? BestKeyedHypothesis(pts, keys, remaining, o) : BestHypothesis(pts, remaining, o, rng);
      double expected = best.votes * remaining.size() / m;
      if (expected < o.min_wall_points) break;
      std::vector<int> inliers = RefinedInliers(pts, remaining, best, o);
      if (Votes(pts, inliers) < o.min_wall_points) {
        ++failures;
      } else {
        // Points outside every run are strays (outliers in the band) and
        // leave the pool too.
        failures = AcceptRuns(pts, inliers, total_votes, strong, o, state) ? 0 : failures + 1;
      }
      // Drop the hypothesis' points so the next round looks elsewhere.
      std::vector<bool> drop(pts.size(), false);
      for (int k : inliers) drop[k] = true;
      std::erase_if(remaining, [&](int k) { return drop[k]; });
    }
  }
  return std::move(state.lines);
}

// Each point to the line it fits best (within the band and 0.3 m of the
// line's extent), then refit, twice; removes the bias of points near corners
// that the first line to be found took from its neighbour.
void CompetitiveRefit(const std::vector<WallPoint>& pts, std::vector<WallLine>& lines, const PlanOptions& o) {
  for (int round = 0; round < 2; ++round) {
    std::vector<std::vector<int>> members(lines.size());
    for (int k = 0; k < static_cast<int>(pts.size()); ++k) {
      int best = -1;
      double best_r = 0;
      for (int l = 0; l < static_cast<int>(lines.size()); ++l) {
        const WallLine& line = lines[l];
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
    std::vector<WallLine> refit;
    for (size_t l = 0; l < lines.size(); ++l) {
      if (Votes(pts, members[l]) < o.min_wall_points) continue;
      WallLine fit = FitWallLine(pts, std::move(members[l]), std::nullopt, o.max_independent_points, o.max_gap_m);
      if (fit.t_max - fit.t_min < o.min_wall_length_m) continue;
      refit.push_back(std::move(fit));
    }
    lines = std::move(refit);
  }
}

// Drops lines sparser (votes per metre) than min_relative_density of the
// densest, or with less than min_wall_fraction of all votes, unless strong.
void DropSparseLines(const WallPoints& walls, std::vector<WallLine>& lines, const PlanOptions& o) {
  const double strong = walls.strong_line_votes;
  double best = 0;
  const double total_votes = walls.TotalVotes();
  for (const WallLine& l : lines) best = std::max(best, l.votes / std::max(0.1, l.t_max - l.t_min));
  std::erase_if(lines, [&](const WallLine& l) {
    return (l.votes / std::max(0.1, l.t_max - l.t_min) < o.min_relative_density * best && l.votes < strong) ||
           (l.votes < o.min_wall_fraction * total_votes && l.votes < strong);
  });
}

}  // namespace

FittedLines FindWallLines(const WallPoints& walls, const PlanOptions& o) {
  FittedLines out;
  std::mt19937_64 rng(o.seed);
  out.lines = SequentialRansac(walls, o, rng);
  out.ransac_lines = static_cast<int>(out.lines.size());
  LogWallLines("RANSAC", out.lines);
  CompetitiveRefit(walls.points, out.lines, o);
  MergeCollinearLines(walls.points, out.lines, o);
  DropSparseLines(walls, out.lines, o);
  LogWallLines("refit + merge", out.lines);
  return out;
}

void MergeCollinearLines(const std::vector<WallPoint>& pts, std::vector<WallLine>& lines, const PlanOptions& o) {
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
        if (!duplicate && (!CollinearLines(lines[a], lines[b], o) || gap > o.max_gap_m)) continue;
        std::vector<int> all = lines[a].members;
        all.insert(all.end(), lines[b].members.begin(), lines[b].members.end());
        bool snapped = lines[a].var_theta > 0 && lines[a].votes >= lines[b].votes;
        double keep_var = lines[a].var_theta;
        WallLine fit = FitWallLine(pts, std::move(all), std::nullopt, o.max_independent_points, o.max_gap_m);
        if (snapped) {
          fit = FitWallLine(pts, fit.members, lines[a].theta, o.max_independent_points, o.max_gap_m);
          fit.var_theta = keep_var;
        }
        lines[a] = std::move(fit);
        lines.erase(lines.begin() + b);
        merged = true;
      }
    }
  }
}

}  // namespace asbuilt
