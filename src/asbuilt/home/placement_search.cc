#include "asbuilt/home/placement_search.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace asbuilt::placement {
namespace {

// B's pose relative to A's when A's door i and B's door j are one door, the
// faces `thickness` apart: B's door turned to face A's, centre on centre.
Pose LinkTransform(const Hole& a, const Hole& b, double thickness) {
  const double yaw = std::atan2(-a.n.y(), -a.n.x()) - std::atan2(b.n.y(), b.n.x());
  Pose t = Pose::Identity();
  t.linear() = Eigen::Rotation2Dd(yaw).toRotationMatrix();
  t.translation() = a.c + thickness * a.n - t.linear() * b.c;
  return t;
}

// B's pose when the point `s` along B's face g (its own frame) lies across
// the partition from the point `u` along the placed face f: g turned to face f.
Pose FaceTransform(const Face& f, double u, const Face& g, double s, double thickness) {
  const double yaw = std::atan2(-f.n.y(), -f.n.x()) - std::atan2(g.n.y(), g.n.x());
  Pose t = Pose::Identity();
  t.linear() = Eigen::Rotation2Dd(yaw).toRotationMatrix();
  t.translation() = f.a + u * f.Dir() + thickness * f.n - t.linear() * (g.a + s * g.Dir());
  return t;
}

// Where along a plain face of length `lg` a door seen at `u` along a face of
// length `lf` (turned to face it) can open: the faces' ends lined up either
// way, or centred on the door.
std::vector<double> Slides(double u, double lf, double lg, double width) {
  std::vector<double> out;
  for (double s : {0.5 * lg, lf - u, lg - u}) {
    if (s < 0.5 * width + 0.05 || s > lg - 0.5 * width - 0.05) continue;
    if (std::none_of(out.begin(), out.end(), [&](double t) { return std::abs(t - s) < 0.02; })) out.push_back(s);
  }
  return out;
}

// The box of a placed room's walls in the home's axes (the first room's frame
// turned by `axes`).
void GrowBox(const RoomGeom& g, const Eigen::Matrix2d& axes, Vec2& lo, Vec2& hi) {
  for (const Face& f : g.walls) {
    for (const Vec2& p : {f.a, f.b}) {
      const Vec2 q = axes.transpose() * p;
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
  }
}
double BoxArea(const Vec2& lo, const Vec2& hi) { return lo.x() > hi.x() ? 0.0 : (hi - lo).prod(); }

}  // namespace

std::string State::Signature() const {
  std::string s;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    if (!placed[i]) continue;
    s += fmt::format("{}:{:.0f},{:.0f},{:.0f};", i, 100 * pose[i].translation().x(), 100 * pose[i].translation().y(),
                     std::remainder(YawOf(pose[i]) * 180 / std::numbers::pi, 360.0));
  }
  return s;
}

Placer::Placer(const std::vector<HomeRoomInput>& rooms, const PlacementOptions& options,
               const PlacementConstraints& constraints)
    : rooms_(rooms), o_(options), c_(constraints) {
  for (const HomeRoomInput& r : rooms) geoms_.push_back(GeomOf(r.plan));
}

std::vector<State> Placer::Search(int seed, const Pose& seed_pose) {
  one_sided_ = false;
  width_ = o_.beam_width;
  std::vector<State> doors = Beam({Start(seed, seed_pose)});
  if (!o_.one_sided_links) return doors;
  one_sided_ = true;
  std::sort(doors.begin(), doors.end(), [](const State& x, const State& y) { return x.score > y.score; });
  // The door links decided the home; one-sided links fill it in from its
  // best few placements, with a narrower beam (they are many more).
  width_ = std::max(1, o_.beam_width / 4);
  if (static_cast<int>(doors.size()) > width_) doors.resize(width_);
  std::vector<State> filled = Beam(doors);
  width_ = o_.beam_width;
  return filled;
}

State Placer::Start(int seed, const Pose& seed_pose) {
  State start;
  const std::size_t n = rooms_.size();
  start.placed.assign(n, 0);
  start.pose.assign(n, Pose::Identity());
  start.link_of.assign(n, -1);
  for (const RoomGeom& g : geoms_) start.used.emplace_back(g.doors.size(), 0);
  start.placed[seed] = 1;
  start.pose[seed] = seed_pose;
  start.count = 1;
  const RoomGeom& first = geoms_[seed];
  const Vec2 d = first.walls.empty() ? Vec2(1, 0) : (seed_pose.linear() * first.walls.front().Dir()).eval();
  axes_.col(0) = d;
  axes_.col(1) = Perp(d);
  placed_cache_.clear();
  GrowBox(PlacedGeom(seed, seed_pose), axes_, start.lo, start.hi);
  start.covered_m2 = first.area;
  for (const auto& [room, pose] : c_.fixed) {
    if (room == seed) continue;
    start.placed[room] = 1;
    start.pose[room] = PoseTransform(pose);
    ++start.count;
    GrowBox(PlacedGeom(room, start.pose[room]), axes_, start.lo, start.hi);
    start.covered_m2 += geoms_[room].area;
  }
  return start;
}

std::vector<State> Placer::Beam(std::vector<State> beam) {
  std::vector<State> done;
  while (!beam.empty()) {
    std::vector<Candidate> all;
    for (std::size_t s = 0; s < beam.size(); ++s) {
      std::vector<Candidate> mine = Expand(beam[s], static_cast<int>(s));
      if (mine.empty()) done.push_back(beam[s]);
      std::sort(mine.begin(), mine.end(), [](const Candidate& x, const Candidate& y) { return x.score > y.score; });
      if (static_cast<int>(mine.size()) > width_) mine.resize(width_);
      all.insert(all.end(), mine.begin(), mine.end());
    }
    std::sort(all.begin(), all.end(), [&](const Candidate& x, const Candidate& y) {
      return beam[x.from_state].score + x.score > beam[y.from_state].score + y.score;
    });
    std::vector<State> next;
    std::vector<std::string> seen;
    for (const Candidate& cand : all) {
      if (static_cast<int>(next.size()) >= width_) break;
      State s = Apply(beam[cand.from_state], cand);
      std::string sig = s.Signature();
      if (std::find(seen.begin(), seen.end(), sig) != seen.end()) continue;
      seen.push_back(std::move(sig));
      next.push_back(std::move(s));
    }
    beam = std::move(next);
  }
  std::stable_sort(done.begin(), done.end(), [](const State& x, const State& y) { return x.score > y.score; });
  return done;
}

bool Placer::Forbidden(const OpeningRef& x, const OpeningRef& y) const {
  for (const auto& [p, q] : c_.different) {
    if ((p == x && q == y) || (p == y && q == x)) return true;
  }
  return false;
}

bool Placer::AskedFor(const OpeningRef& x, const OpeningRef& y) const {
  for (const auto& [p, q] : c_.same) {
    if ((p == x && q == y) || (p == y && q == x)) return true;
  }
  return false;
}

const RoomGeom& Placer::PlacedGeom(int room, const Pose& pose) {
  const PoseKey key{room, std::llround(pose.translation().x() * 1e4), std::llround(pose.translation().y() * 1e4),
                    std::llround(YawOf(pose) * 1e6)};
  auto it = placed_cache_.find(key);
  if (it == placed_cache_.end()) it = placed_cache_.emplace(key, Transformed(geoms_[room], pose)).first;
  return it->second;
}

std::vector<Candidate> Placer::Expand(const State& s, int index) {
  std::vector<Candidate> out;
  const int n = static_cast<int>(rooms_.size());
  placed_now_.assign(n, nullptr);
  for (int r = 0; r < n; ++r) {
    if (s.placed[r]) placed_now_[r] = &PlacedGeom(r, s.pose[r]);
  }
  // A candidate's score: its terms against the placed rooms, the room, the
  // home's box; nullopt when refused.
  auto add = [&](Candidate c, double link_terms) {
    std::optional<double> score = Score(s, c.b_room, c.pose);
    if (!score) return;
    c.lo = s.lo;
    c.hi = s.hi;
    GrowBox(PlacedGeom(c.b_room, c.pose), axes_, c.lo, c.hi);
    const double empty_before = BoxArea(s.lo, s.hi) - s.covered_m2;
    const double empty_after = BoxArea(c.lo, c.hi) - s.covered_m2 - geoms_[c.b_room].area;
    c.score = *score + kPlacedRoom + link_terms - kEmptyPerM2 * std::max(0.0, empty_after - empty_before);
    out.push_back(c);
  };
  for (int a = 0; a < n; ++a) {
    if (!s.placed[a]) continue;
    const RoomGeom& ga = geoms_[a];
    const RoomGeom& pa = *placed_now_[a];
    for (int b = 0; b < n; ++b) {
      if (s.placed[b]) continue;
      const RoomGeom& gb = geoms_[b];
      for (int i = 0; i < static_cast<int>(ga.doors.size()); ++i) {
        if (s.used[a][i]) continue;
        const Hole& da = ga.doors[i];
        for (int j = 0; j < static_cast<int>(gb.doors.size()); ++j) {
          const Hole& db = gb.doors[j];
          const OpeningRef ra{a, da.opening}, rb{b, db.opening};
          if (s.used[b][j] || Forbidden(ra, rb)) continue;
          const bool asked = AskedFor(ra, rb);
          if (!asked && !WidthsMatch(da.width, db.width, o_)) continue;
          add({.from_state = index,
               .a_room = a,
               .a_door = i,
               .b_room = b,
               .b_door = j,
               .pose = s.pose[a] * LinkTransform(da, db, o_.wall_thickness_m),
               .by_user = asked},
              -kWidthPerM * std::abs(da.width - db.width) + (asked ? kUserLink : 0.0));
        }
        if (!one_sided_) continue;
        // A's door onto a plain wall of B (B's survey missed the door).
        const Hole& placed_door = pa.doors[i];
        const Face& f = pa.walls[placed_door.wall];
        const double u = ProjectOnFace(f, placed_door.c, 0).along;
        for (int k : gb.plain_walls) {
          const Face& g = gb.walls[k];
          if (g.Length() < da.width + 0.1) continue;
          for (double sl : Slides(u, f.Length(), g.Length(), da.width)) {
            add({.from_state = index,
                 .a_room = a,
                 .a_door = i,
                 .b_room = b,
                 .b_door = -1,
                 .b_wall = k,
                 .pose = FaceTransform(f, u, g, sl, o_.wall_thickness_m)},
                kDoorIntoWall - kOneSided);
          }
        }
      }
      if (!one_sided_) continue;
      // B's door onto a plain wall of A (A's survey missed the door).
      for (int j = 0; j < static_cast<int>(gb.doors.size()); ++j) {
        if (s.used[b][j]) continue;
        const Hole& db = gb.doors[j];
        const Face& g = gb.walls[db.wall];
        const double sc = ProjectOnFace(g, db.c, 0).along;
        for (int k : ga.plain_walls) {
          const Face& f = pa.walls[k];
          if (f.Length() < db.width + 0.1) continue;
          for (double uu : Slides(sc, g.Length(), f.Length(), db.width)) {
            add({.from_state = index,
                 .a_room = a,
                 .a_door = -1,
                 .b_room = b,
                 .b_door = j,
                 .a_wall = k,
                 .pose = FaceTransform(f, uu, g, sc, o_.wall_thickness_m)},
                kDoorIntoWall - kOneSided);
          }
        }
      }
    }
  }
  return out;
}

std::optional<double> Placer::Score(const State& s, int room, const Pose& pose) {
  const RoomGeom& g = PlacedGeom(room, pose);
  double score = 0.0;
  if (room < static_cast<int>(c_.previous.size()) && c_.previous[room]) {
    const Pose before = PoseTransform(*c_.previous[room]);
    const bool kept = (before.translation() - pose.translation()).norm() < 0.05 &&
                      std::abs(std::remainder(YawOf(before) - YawOf(pose), 2 * std::numbers::pi)) < 0.02;
    if (kept) score += c_.kept_room;
  }
  for (std::size_t c = 0; c < rooms_.size(); ++c) {
    if (!s.placed[c]) continue;
    const std::optional<double> term = PairScore(g, *placed_now_[c], o_);
    if (!term) return std::nullopt;
    score += *term;
  }
  return score;
}

State Placer::Apply(const State& from, const Candidate& c) const {
  State s = from;
  s.placed[c.b_room] = 1;
  s.pose[c.b_room] = c.pose;
  if (c.a_door >= 0) s.used[c.a_room][c.a_door] = 1;
  if (c.b_door >= 0) s.used[c.b_room][c.b_door] = 1;
  s.link_of[c.b_room] = static_cast<int>(s.links.size());
  auto opening = [&](int room, int door) { return door >= 0 ? geoms_[room].doors[door].opening : -1; };
  s.links.push_back({.a = {c.a_room, opening(c.a_room, c.a_door)},
                     .b = {c.b_room, opening(c.b_room, c.b_door)},
                     .wall_a = c.a_wall,
                     .wall_b = c.b_wall,
                     .score = c.score,
                     .by_user = c.by_user});
  s.score += c.score;
  s.lo = c.lo;
  s.hi = c.hi;
  s.covered_m2 += geoms_[c.b_room].area;
  ++s.count;
  return s;
}

}  // namespace asbuilt::placement
