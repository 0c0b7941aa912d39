#include "asbuilt/home/placement.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <unordered_map>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "asbuilt/home/placement_geometry.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace placement {
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

struct State {
  std::vector<char> placed;
  std::vector<Pose> pose;
  std::vector<int> link_of;             // Per room: index into links, -1.
  std::vector<std::vector<char>> used;  // Per room, per door (index into RoomGeom::doors).
  std::vector<RoomLink> links;
  double score = 0.0;
  int count = 0;
  Vec2 lo = Vec2::Constant(1e300), hi = Vec2::Constant(-1e300);  // Bounding box in the home's axes.
  double covered_m2 = 0.0;                                       // Floor of the rooms placed.

  // Which rooms are where, to tell placements apart (centimetres, degrees).
  std::string Signature() const {
    std::string s;
    for (std::size_t i = 0; i < placed.size(); ++i) {
      if (!placed[i]) continue;
      s += fmt::format("{}:{:.0f},{:.0f},{:.0f};", i, 100 * pose[i].translation().x(), 100 * pose[i].translation().y(),
                       std::remainder(YawOf(pose[i]) * 180 / std::numbers::pi, 360.0));
    }
    return s;
  }
};

struct Candidate {
  int from_state = 0;
  int a_room = 0, a_door = -1, b_room = 0, b_door = -1;  // Indices into RoomGeom::doors; −1: one-sided.
  int a_wall = -1, b_wall = -1;                          // A one-sided link's plain wall.
  Pose pose = Pose::Identity();
  double score = 0.0;
  bool by_user = false;
  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();  // The home's box with the room.
};

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

class Placer {
 public:
  Placer(const std::vector<HomeRoomInput>& rooms, const PlacementOptions& options,
         const PlacementConstraints& constraints)
      : rooms_(rooms), o_(options), c_(constraints) {
    for (const HomeRoomInput& r : rooms) geoms_.push_back(GeomOf(r.plan));
  }

  // Beam search from `seed`; every complete or stuck placement, best first.
  // Door-to-door links first; then, from the best of those placements, the
  // rooms left over by one-sided links too (a door one survey missed). A
  // room one-sided links could place wrongly never displaces a door link.
  std::vector<State> Search(int seed, const Pose& seed_pose) {
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

  State Start(int seed, const Pose& seed_pose) {
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

  // Grows every state one room at a time, keeping the best beam_width;
  // every state that cannot grow, best first.
  std::vector<State> Beam(std::vector<State> beam) {
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

  const std::vector<RoomGeom>& geoms() const { return geoms_; }

 private:
  bool Forbidden(const OpeningRef& x, const OpeningRef& y) const {
    for (const auto& [p, q] : c_.different) {
      if ((p == x && q == y) || (p == y && q == x)) return true;
    }
    return false;
  }
  bool AskedFor(const OpeningRef& x, const OpeningRef& y) const {
    for (const auto& [p, q] : c_.same) {
      if ((p == x && q == y) || (p == y && q == x)) return true;
    }
    return false;
  }

  // A room's geometry at a pose, computed once per room and pose (to 0.1 mm
  // and 1e-6 rad).
  const RoomGeom& PlacedGeom(int room, const Pose& pose) {
    const PoseKey key{room, std::llround(pose.translation().x() * 1e4), std::llround(pose.translation().y() * 1e4),
                      std::llround(YawOf(pose) * 1e6)};
    auto it = placed_cache_.find(key);
    if (it == placed_cache_.end()) it = placed_cache_.emplace(key, Transformed(geoms_[room], pose)).first;
    return it->second;
  }

  std::vector<Candidate> Expand(const State& s, int index) {
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

  std::optional<double> Score(const State& s, int room, const Pose& pose) {
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

  State Apply(const State& from, const Candidate& c) const {
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

  const std::vector<HomeRoomInput>& rooms_;
  const PlacementOptions& o_;
  const PlacementConstraints& c_;
  std::vector<RoomGeom> geoms_;
  struct PoseKey {
    int room;
    long long x, y, yaw;
    bool operator==(const PoseKey&) const = default;
  };
  struct PoseKeyHash {
    std::size_t operator()(const PoseKey& k) const {
      std::size_t h = std::hash<long long>()(k.x);
      for (long long v : {k.y, k.yaw, static_cast<long long>(k.room)}) h = h * 1000003u ^ std::hash<long long>()(v);
      return h;
    }
  };
  std::unordered_map<PoseKey, RoomGeom, PoseKeyHash> placed_cache_;
  std::vector<const RoomGeom*> placed_now_;  // The expanded state's placed rooms (nullptr: not placed).
  Eigen::Matrix2d axes_ = Eigen::Matrix2d::Identity();
  bool one_sided_ = false;
  int width_ = 0;  // The beam's width now.
};

const Hole* DoorOf(const RoomGeom& g, int opening) {
  for (const Hole& h : g.doors) {
    if (h.opening == opening) return &h;
  }
  return nullptr;
}

// Each placed room's geometry at its pose (empty for the others), once.
std::vector<RoomGeom> PlacedRooms(const std::vector<RoomGeom>& geoms, const State& s) {
  std::vector<RoomGeom> placed(geoms.size());
  for (std::size_t r = 0; r < geoms.size(); ++r) {
    if (s.placed[r]) placed[r] = Transformed(geoms[r], s.pose[r]);
  }
  return placed;
}

// Doors of two placed rooms that meet across a partition but placed nothing:
// the loops of the home.
void FindLoops(const std::vector<RoomGeom>& geoms, const State& s, const PlacementOptions& o,
               const PlacementConstraints& c, std::vector<RoomLink>& links) {
  const int n = static_cast<int>(geoms.size());
  const std::vector<RoomGeom> placed = PlacedRooms(geoms, s);
  auto forbidden = [&](const OpeningRef& x, const OpeningRef& y) {
    return std::any_of(c.different.begin(), c.different.end(), [&](const auto& p) {
      return (p.first == x && p.second == y) || (p.first == y && p.second == x);
    });
  };
  auto linked = [&](const OpeningRef& r) {
    for (const RoomLink& l : links) {
      if (l.a == r || l.b == r) return true;
    }
    return false;
  };
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if (!s.placed[a] || !s.placed[b]) continue;
      const RoomGeom &ga = placed[a], &gb = placed[b];
      for (const Hole& da : ga.doors) {
        for (const Hole& db : gb.doors) {
          if (linked({a, da.opening}) || linked({b, db.opening}) || forbidden({a, da.opening}, {b, db.opening}))
            continue;
          if (da.n.dot(db.n) > -kAntiParallel || !WidthsMatch(da.width, db.width, o)) continue;
          const double across = (db.c - da.c).dot(da.n);
          const double along = std::abs((db.c - da.c).dot(Perp(da.n)));
          if (across < -0.05 || across > o.max_wall_thickness_m || along > 0.35) continue;
          links.push_back({.a = {a, da.opening}, .b = {b, db.opening}, .loop = true});
        }
      }
    }
  }
}

// Least squares over every link: each room's pose (the seed's fixed) and one
// partition thickness for the home, held near the option's value by a weak
// prior so a home without loops keeps it.
// Two walls of two placed rooms the refinement keeps together: the two
// faces of one partition (`facing`: `thickness` apart) or one wall of the
// home running past a partition (on one line). They measure the partition
// where the doors alone cannot (a home without loops).
struct FaceTie {
  int a, wall_a, b, wall_b;
  bool facing;
};

std::vector<FaceTie> FindFaceTies(const std::vector<RoomGeom>& geoms, const State& s, const PlacementOptions& o) {
  std::vector<FaceTie> ties;
  const int n = static_cast<int>(geoms.size());
  const std::vector<RoomGeom> placed = PlacedRooms(geoms, s);
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      if (!s.placed[a] || !s.placed[b]) continue;
      const RoomGeom &ga = placed[a], &gb = placed[b];
      if (!BoxesNear(ga, gb, o.max_wall_thickness_m + 0.05)) continue;
      for (int i = 0; i < static_cast<int>(ga.walls.size()); ++i) {
        for (int j = 0; j < static_cast<int>(gb.walls.size()); ++j) {
          const Face &f = ga.walls[i], &g = gb.walls[j];
          const double da = (g.a - f.a).dot(f.n), db = (g.b - f.a).dot(f.n);
          const double s0 = ProjectOnFace(f, g.a, 0).along, s1 = ProjectOnFace(f, g.b, 0).along;
          if (f.n.dot(g.n) < -kFacesAntiParallel) {
            const double overlap = std::min(f.Length(), std::max(s0, s1)) - std::max(0.0, std::min(s0, s1));
            if (std::min(da, db) >= -0.03 && std::max(da, db) <= o.max_wall_thickness_m && overlap > 0.3) {
              ties.push_back({a, i, b, j, true});
            }
          } else if (f.n.dot(g.n) > kFacesAntiParallel && std::abs(da) < 0.05 && std::abs(db) < 0.05) {
            const double gap = std::max(std::min(s0, s1) - f.Length(), -std::max(s0, s1));
            if (gap >= -0.05 && gap <= o.max_wall_thickness_m) ties.push_back({a, i, b, j, false});
          }
        }
      }
    }
  }
  return ties;
}

// Returns each link's and then each tie's distance left (metres).
std::vector<double> Refine(const std::vector<RoomGeom>& geoms, const std::vector<char>& held, const PlacementOptions& o,
                           const std::vector<FaceTie>& ties, State& s, double& thickness) {
  std::vector<int> var(s.placed.size(), -1);
  int n_var = 0;
  for (std::size_t r = 0; r < s.placed.size(); ++r) {
    if (s.placed[r] && !held[r]) var[r] = n_var++;
  }
  const int n_params = 3 * n_var + 1;
  Eigen::VectorXd x(n_params);
  for (std::size_t r = 0; r < s.placed.size(); ++r) {
    if (var[r] < 0) continue;
    x.segment<3>(3 * var[r]) << s.pose[r].translation(), YawOf(s.pose[r]);
  }
  x(n_params - 1) = o.wall_thickness_m;
  auto pose_of = [&](const Eigen::VectorXd& p, int room) {
    if (var[room] < 0) return s.pose[room];
    Pose t = Pose::Identity();
    t.linear() = Eigen::Rotation2Dd(p(3 * var[room] + 2)).toRotationMatrix();
    t.translation() = p.segment<2>(3 * var[room]);
    return t;
  };
  auto residuals = [&](const Eigen::VectorXd& p) {
    Eigen::VectorXd r(3 * s.links.size() + ties.size() + 1);
    for (std::size_t k = 0; k < ties.size(); ++k) {
      const FaceTie& tie = ties[k];
      const Pose ta = pose_of(p, tie.a), tb = pose_of(p, tie.b);
      const Face &f = geoms[tie.a].walls[tie.wall_a], &g = geoms[tie.b].walls[tie.wall_b];
      const Vec2 n = ta.linear() * f.n, mid = tb * (0.5 * (g.a + g.b));
      r(3 * s.links.size() + k) = (mid - ta * f.a).dot(n) - (tie.facing ? p(n_params - 1) : 0.0);
    }
    for (std::size_t k = 0; k < s.links.size(); ++k) {
      const RoomLink& l = s.links[k];
      const Hole* ha = DoorOf(geoms[l.a.room], l.a.opening);
      const Hole* hb = DoorOf(geoms[l.b.room], l.b.opening);
      const Pose ta = pose_of(p, l.a.room), tb = pose_of(p, l.b.room);
      const double thickness = p(n_params - 1);
      if (ha != nullptr && hb != nullptr) {
        const Vec2 na = ta.linear() * ha->n, nb = tb.linear() * hb->n;
        r.segment<2>(3 * k) = tb * hb->c - (ta * ha->c + thickness * na);
        r(3 * k + 2) = std::remainder(std::atan2(nb.y(), nb.x()) - std::atan2(-na.y(), -na.x()), 2 * std::numbers::pi);
        continue;
      }
      // One-sided: the door's point across the partition on the other
      // room's face line, the faces anti-parallel; free along the wall.
      const bool door_in_a = ha != nullptr;
      const Hole& door = door_in_a ? *ha : *hb;
      const Pose& td = door_in_a ? ta : tb;
      const Pose& tw = door_in_a ? tb : ta;
      const Face& face = geoms[door_in_a ? l.b.room : l.a.room].walls[door_in_a ? l.wall_b : l.wall_a];
      const Vec2 nd = td.linear() * door.n, nf = tw.linear() * face.n;
      r(3 * k) = (td * door.c + thickness * nd - tw * face.a).dot(nf);
      r(3 * k + 1) = 0.0;
      r(3 * k + 2) = std::remainder(std::atan2(nf.y(), nf.x()) - std::atan2(-nd.y(), -nd.x()), 2 * std::numbers::pi);
    }
    r(r.size() - 1) = kThicknessPrior * (p(n_params - 1) - o.wall_thickness_m);
    return r;
  };
  for (int iter = 0; iter < 10; ++iter) {
    const Eigen::VectorXd r0 = residuals(x);
    Eigen::MatrixXd j(r0.size(), n_params);
    for (int k = 0; k < n_params; ++k) {
      Eigen::VectorXd xp = x;
      xp(k) += 1e-6;
      j.col(k) = (residuals(xp) - r0) / 1e-6;
    }
    Eigen::MatrixXd h = j.transpose() * j;
    h.diagonal().array() += 1e-9;
    const Eigen::VectorXd step = h.ldlt().solve(-j.transpose() * r0);
    x += step;
    if (step.norm() < 1e-9) break;
  }
  x(n_params - 1) = std::clamp(x(n_params - 1), kThinnestWall, o.max_wall_thickness_m);
  const Eigen::VectorXd left = residuals(x);
  std::vector<double> per_link;
  for (std::size_t k = 0; k < s.links.size(); ++k) per_link.push_back(left.segment<2>(3 * k).norm());
  for (std::size_t k = 0; k < ties.size(); ++k) per_link.push_back(std::abs(left(3 * s.links.size() + k)));
  for (std::size_t r = 0; r < s.placed.size(); ++r) {
    if (var[r] >= 0) s.pose[r] = pose_of(x, static_cast<int>(r));
  }
  thickness = x(n_params - 1);
  return per_link;
}

std::string OpeningName(const std::vector<HomeRoomInput>& rooms, const OpeningRef& r) {
  return fmt::format("{}#{}", rooms[r.room].name, r.opening);
}

// `refine`: false for the alternatives (offered to pick from; their poses
// as the search left them, the partition at its prior).
HomePlacement Finish(const std::vector<HomeRoomInput>& rooms, const std::vector<RoomGeom>& geoms, int seed,
                     const PlacementOptions& o, const PlacementConstraints& c, State s, bool refine) {
  std::vector<char> held(rooms.size(), 0);
  held[seed] = 1;
  for (const auto& f : c.fixed) held[f.first] = 1;
  HomePlacement h;
  h.score = s.score;
  h.links = s.links;
  FindLoops(geoms, s, o, c, h.links);
  // Refined over every link; a loop that cannot close within 5 cm was two
  // doors that only looked like one: dropped, and refined again.
  // Partition faces and continuing walls too; any of these that cannot close
  // likewise.
  std::vector<FaceTie> ties = refine ? FindFaceTies(geoms, s, o) : std::vector<FaceTie>{};
  h.wall_thickness_m = o.wall_thickness_m;
  while (refine) {
    State trial = s;
    trial.links = h.links;
    const std::vector<double> left = Refine(geoms, held, o, ties, trial, h.wall_thickness_m);
    // Every loop and tie left over 5 cm goes at once (a refinement per drop
    // was most of the time on rooms of many short walls).
    std::vector<RoomLink> links;
    std::vector<FaceTie> kept;
    for (std::size_t k = 0; k < left.size(); ++k) {
      const bool loose = left[k] > 0.05;
      if (k < h.links.size()) {
        if (!(loose && h.links[k].loop)) links.push_back(h.links[k]);
      } else if (!loose) {
        kept.push_back(ties[k - h.links.size()]);
      }
    }
    if (links.size() == h.links.size() && kept.size() == ties.size()) {
      s = std::move(trial);
      break;
    }
    h.links = std::move(links);
    ties = std::move(kept);
  }
  for (const RoomLink& l : h.links) h.loops += l.loop;
  h.rooms.resize(rooms.size());
  for (std::size_t r = 0; r < rooms.size(); ++r) {
    RoomPlacement& p = h.rooms[r];
    p.placed = s.placed[r];
    p.floor_from_room = s.pose[r];
    p.link = s.link_of[r];
    if (held[r] && static_cast<int>(r) != seed) {
      p.placed_by = "moved by hand";
    } else if (static_cast<int>(r) == seed) {
      p.placed_by =
          held[r] && std::any_of(c.fixed.begin(), c.fixed.end(), [&](const auto& f) { return f.first == seed; })
              ? "moved by hand"
              : "first room";
    } else if (p.link >= 0 || (p.placed && std::any_of(h.links.begin(), h.links.end(), [&](const RoomLink& l) {
                                 return l.a.room == static_cast<int>(r) || l.b.room == static_cast<int>(r);
                               }))) {
      // Its own link, or (the root of a search grown from it) its first link.
      if (p.link < 0) {
        for (std::size_t k = 0; k < h.links.size() && p.link < 0; ++k) {
          if (h.links[k].a.room == static_cast<int>(r) || h.links[k].b.room == static_cast<int>(r))
            p.link = static_cast<int>(k);
        }
      }
      const RoomLink& l = h.links[p.link];
      if (l.a.opening >= 0 && l.b.opening >= 0) {
        p.placed_by = fmt::format("door {} = {}{}", OpeningName(rooms, l.a), OpeningName(rooms, l.b),
                                  l.by_user ? " (by hand)" : "");
      } else {
        const bool door_in_a = l.a.opening >= 0;
        const OpeningRef& door = door_in_a ? l.a : l.b;
        const int room = door_in_a ? l.b.room : l.a.room, wall = door_in_a ? l.wall_b : l.wall_a;
        p.placed_by = fmt::format("door {} onto {}'s wall {} (no door found there)", OpeningName(rooms, door),
                                  rooms[room].name, wall);
      }
    }
  }
  // Rooms no link reaches: by their hint, in the frame the placed rooms'
  // hints agree on (the first placed room with a hint says where it is).
  std::optional<Pose> home_from_hints;
  for (std::size_t r = 0; r < rooms.size() && !home_from_hints; ++r) {
    if (h.rooms[r].placed && rooms[r].hint) {
      home_from_hints = h.rooms[r].floor_from_room * PoseTransform(*rooms[r].hint).inverse();
    }
  }
  for (std::size_t r = 0; r < rooms.size(); ++r) {
    RoomPlacement& p = h.rooms[r];
    if (p.placed) continue;
    if (rooms[r].hint && home_from_hints) {
      p.placed = true;
      p.floor_from_room = *home_from_hints * PoseTransform(*rooms[r].hint);
      p.placed_by = "hint";
    } else {
      p.placed_by = geoms[r].doors.empty() ? "not placed: no door seen"
                                           : "not placed: none of its doors fits a door of the placed rooms";
    }
  }
  return h;
}

}  // namespace
}  // namespace placement

namespace {

using placement::Finish;
using placement::GeomOf;
using placement::OpeningsAgainstWalls;
using placement::PairScore;
using placement::Placer;
using placement::Pose;
using placement::RoomGeom;
using placement::SharedFaces;
using placement::State;
using placement::Transformed;

}  // namespace

void PlacementOptions::Check() const {
  auto fail = [](const std::string& what) { throw InvalidArgument("PlacementOptions: " + what); };
  if (!(max_wall_thickness_m > 0 && max_wall_thickness_m <= 1.0)) fail("max_wall_thickness_m must be in (0, 1]");
  if (!(wall_thickness_m >= 0 && wall_thickness_m <= max_wall_thickness_m)) {
    fail("wall_thickness_m must be in [0, max_wall_thickness_m]");
  }
  if (!(max_width_difference_m >= 0 && max_width_difference_m <= 1)) fail("max_width_difference_m must be in [0, 1]");
  if (!(width_tolerance >= 0 && width_tolerance <= 1)) fail("width_tolerance must be in [0, 1]");
  if (!(max_overlap >= 0 && max_overlap <= 1)) fail("max_overlap must be in [0, 1]");
  if (beam_width < 1 || beam_width > 1000) fail("beam_width must be in [1, 1000]");
  if (alternatives < 0 || alternatives > 100) fail("alternatives must be in [0, 100]");
}

int HomePlacement::Placed() const {
  return static_cast<int>(std::count_if(rooms.begin(), rooms.end(), [](const RoomPlacement& r) { return r.placed; }));
}

std::string HomePlacement::ToString(const std::vector<HomeRoomInput>& inputs) const {
  std::string s = fmt::format("{} of {} rooms placed, {} loops, partition {:.3f} m, score {:.1f}", Placed(),
                              rooms.size(), loops, wall_thickness_m, score);
  for (std::size_t r = 0; r < rooms.size() && r < inputs.size(); ++r) {
    const Pose& t = rooms[r].floor_from_room;
    s += fmt::format("\n  {}: ({:.3f}, {:.3f}) m, {:.1f}°, {}", inputs[r].name, t.translation().x(),
                     t.translation().y(), YawOf(t) * 180 / std::numbers::pi, rooms[r].placed_by);
  }
  return s;
}

double YawOf(const Eigen::Isometry2d& t) { return std::atan2(t.linear()(1, 0), t.linear()(0, 0)); }

Eigen::Isometry2d PoseTransform(const PlanPose& pose) {
  Eigen::Isometry2d t = Eigen::Isometry2d::Identity();
  t.linear() = Eigen::Rotation2Dd(pose.yaw_deg * std::numbers::pi / 180).toRotationMatrix();
  t.translation() = pose.position_m;
  return t;
}

PlanPose TransformPose(const Eigen::Isometry2d& t) { return {t.translation(), YawOf(t) * 180 / std::numbers::pi}; }

double FitScore(const std::vector<HomeRoomInput>& rooms, const std::vector<Eigen::Isometry2d>& poses,
                const std::vector<char>& placed, const PlacementOptions& options, std::vector<std::string>* detail) {
  std::vector<RoomGeom> g;
  for (std::size_t r = 0; r < rooms.size(); ++r) g.push_back(Transformed(GeomOf(rooms[r].plan), poses[r]));
  double total = 0.0;
  for (std::size_t a = 0; a < rooms.size(); ++a) {
    for (std::size_t b = a + 1; b < rooms.size(); ++b) {
      if (!placed[a] || !placed[b]) continue;
      const std::optional<double> s = PairScore(g[a], g[b], options);
      const double v = s.value_or(-1000.0);
      total += v;
      if (detail && v != 0.0) {
        detail->push_back(fmt::format("{} / {}: {} (faces {:.2f} m, openings {:.1f} + {:.1f})", rooms[a].name,
                                      rooms[b].name, s ? fmt::format("{:.2f}", v) : std::string("overlap"),
                                      SharedFaces(g[a], g[b], options), OpeningsAgainstWalls(g[a], g[b], options),
                                      OpeningsAgainstWalls(g[b], g[a], options)));
      }
    }
  }
  return total;
}

PlacementResult PlaceRooms(const std::vector<HomeRoomInput>& rooms, const PlacementOptions& options,
                           const PlacementConstraints& constraints) {
  options.Check();
  if (rooms.empty()) throw InvalidArgument("PlaceRooms: a home needs at least one room");
  const auto start = std::chrono::steady_clock::now();
  auto check_ref = [&](const OpeningRef& r) {
    if (r.room < 0 || r.room >= static_cast<int>(rooms.size()) || r.opening < 0 ||
        r.opening >= static_cast<int>(rooms[r.room].plan.openings.size())) {
      throw InvalidArgument(fmt::format("PlaceRooms: no opening {} in room {}", r.opening, r.room));
    }
  };
  for (const auto* list : {&constraints.same, &constraints.different}) {
    for (const auto& [p, q] : *list) {
      check_ref(p);
      check_ref(q);
      if (p.room == q.room) throw InvalidArgument("PlaceRooms: two openings of one room cannot be one door");
    }
  }
  if (!constraints.previous.empty() && constraints.previous.size() != rooms.size()) {
    throw InvalidArgument(
        fmt::format("PlaceRooms: {} previous poses for {} rooms", constraints.previous.size(), rooms.size()));
  }
  std::vector<char> fixed(rooms.size(), 0);
  for (const auto& [room, pose] : constraints.fixed) {
    if (room < 0 || room >= static_cast<int>(rooms.size())) {
      throw InvalidArgument(fmt::format("PlaceRooms: no room {} to hold", room));
    }
    if (fixed[room]++) throw InvalidArgument(fmt::format("PlaceRooms: room {} held twice", room));
  }
  Placer placer(rooms, options, constraints);
  // The home frame is the first room's (or its hint's) that a door could
  // join to another room.
  int seed = 0;
  for (std::size_t r = 0; r < rooms.size(); ++r) {
    if (!placer.geoms()[r].doors.empty()) {
      seed = static_cast<int>(r);
      break;
    }
  }
  Pose seed_pose = rooms[seed].hint ? PoseTransform(*rooms[seed].hint) : Pose::Identity();
  for (const auto& [room, pose] : constraints.fixed) {
    if (room == seed) seed_pose = PoseTransform(pose);
  }
  std::vector<State> done = placer.Search(seed, seed_pose);
  // The home grown from other rooms too (the two with the most doors): an
  // early wrong link from one side is often plain from another. Their
  // placements are put in the first room's frame and compete by score.
  if (constraints.fixed.empty()) {
    std::vector<int> order;
    for (int r = 0; r < static_cast<int>(rooms.size()); ++r) {
      if (r != seed && placer.geoms()[r].doors.size() >= 2) order.push_back(r);
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return placer.geoms()[a].doors.size() > placer.geoms()[b].doors.size(); });
    if (order.size() > 2) order.resize(2);
    for (int other : order) {
      for (State s : placer.Search(other, Pose::Identity())) {
        if (!s.placed[seed]) continue;
        const Pose to_home = seed_pose * s.pose[seed].inverse();
        for (std::size_t r = 0; r < s.pose.size(); ++r) {
          if (s.placed[r]) s.pose[r] = to_home * s.pose[r];
        }
        done.push_back(std::move(s));
      }
    }
  }
  PlacementResult result;
  std::sort(done.begin(), done.end(), [](const State& x, const State& y) { return x.score > y.score; });
  std::vector<std::string> seen;
  for (const State& s : done) {
    std::string sig = s.Signature();
    if (std::find(seen.begin(), seen.end(), sig) != seen.end()) continue;
    seen.push_back(std::move(sig));
    HomePlacement h = Finish(rooms, placer.geoms(), seed, options, constraints, s, /*refine=*/seen.size() == 1);
    if (seen.size() == 1) {
      result.best = std::move(h);
    } else {
      result.alternatives.push_back(std::move(h));
      if (static_cast<int>(result.alternatives.size()) >= options.alternatives) break;
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace asbuilt
