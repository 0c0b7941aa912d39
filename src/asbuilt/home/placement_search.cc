#include "asbuilt/home/placement_search.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace asbuilt::placement {

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
  // The best few fill in, each room still unplaced counted at what a
  // one-sided link may add: a placement that left out a room whose door
  // another survey missed is not outranked by one that linked it wrongly.
  auto key = [&](const State& x) { return x.score + kRoomLeft * static_cast<double>(rooms_.size() - x.count); };
  std::sort(doors.begin(), doors.end(), [&](const State& x, const State& y) { return key(x) > key(y); });
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
  pair_cache_.clear();
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

Placer::PoseKey Placer::KeyOf(int room, const Pose& pose) {
  return {room, std::llround(pose.translation().x() * 1e4), std::llround(pose.translation().y() * 1e4),
          std::llround(YawOf(pose) * 1e6)};
}

const RoomGeom& Placer::PlacedGeom(int room, const Pose& pose) {
  const PoseKey key = KeyOf(room, pose);
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
      }
      if (!one_sided_) continue;
      // A door one of the two surveys missed. A room whose survey found no
      // door at all pays for being placed so.
      for (const OneSidedLink& l : OneSidedLinks(pa, gb, s.used[a], s.used[b], o_.wall_thickness_m)) {
        add({.from_state = index,
             .a_room = a,
             .a_door = l.a_door,
             .b_room = b,
             .b_door = l.b_door,
             .a_wall = l.a_wall,
             .b_wall = l.b_wall,
             .pose = l.pose},
            kDoorIntoWall - (l.b_door < 0 && gb.doors.empty() ? kNoDoorOfItsOwn : 0.0));
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
    const std::pair<PoseKey, PoseKey> key{KeyOf(room, pose), KeyOf(static_cast<int>(c), s.pose[c])};
    auto it = pair_cache_.find(key);
    if (it == pair_cache_.end()) it = pair_cache_.emplace(key, PairScore(g, *placed_now_[c], o_)).first;
    const std::optional<double> term = it->second;
    if (!term) return std::nullopt;
    score += *term;
  }
  return score;
}

void MarkMeetingDoors(const std::vector<const RoomGeom*>& placed, int room, const PlacementOptions& o, State& s) {
  const RoomGeom& x = *placed[room];
  for (std::size_t y = 0; y < placed.size(); ++y) {
    if (static_cast<int>(y) == room || placed[y] == nullptr || !BoxesNear(x, *placed[y], o.max_wall_thickness_m + 0.05))
      continue;
    for (std::size_t i = 0; i < x.doors.size(); ++i) {
      for (std::size_t j = 0; j < placed[y]->doors.size(); ++j) {
        if (s.used[room][i] || s.used[y][j] || !DoorsMeet(x.doors[i], placed[y]->doors[j], o)) continue;
        s.used[room][i] = s.used[y][j] = 1;
      }
    }
  }
}

State Placer::Apply(const State& from, const Candidate& c) {
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
  std::vector<const RoomGeom*> placed(rooms_.size(), nullptr);
  for (std::size_t r = 0; r < rooms_.size(); ++r) {
    if (s.placed[r]) placed[r] = &PlacedGeom(static_cast<int>(r), s.pose[r]);
  }
  MarkMeetingDoors(placed, c.b_room, o_, s);
  return s;
}

}  // namespace asbuilt::placement
