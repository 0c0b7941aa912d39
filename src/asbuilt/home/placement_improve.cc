#include "asbuilt/home/placement_improve.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

namespace asbuilt::placement {
namespace {

int DoorIndex(const RoomGeom& g, int opening) {
  for (std::size_t i = 0; i < g.doors.size(); ++i) {
    if (g.doors[i].opening == opening) return static_cast<int>(i);
  }
  return -1;
}

// A link's own terms, as the search scored it.
double LinkTerms(const std::vector<RoomGeom>& geoms, const RoomLink& l) {
  if (l.a.opening < 0 || l.b.opening < 0) {
    const int plain = l.a.opening < 0 ? l.a.room : l.b.room;
    return kDoorIntoWall - (geoms[plain].doors.empty() ? kNoDoorOfItsOwn : 0.0);
  }
  const int i = DoorIndex(geoms[l.a.room], l.a.opening), j = DoorIndex(geoms[l.b.room], l.b.opening);
  if (i < 0 || j < 0) return 0.0;
  return -kWidthPerM * std::abs(geoms[l.a.room].doors[i].width - geoms[l.b.room].doors[j].width);
}

// A way to join the part beyond a cut link back: the link and where it puts
// its room of that part.
struct Swap {
  RoomLink link;
  int part_room = -1;  // The link's room in the part that moves.
  Pose pose = Pose::Identity();
};

// Every link between a placed room `a` of the part that stays and `b` of the
// part that moves, with b's pose by it.
std::vector<Swap> SwapsBetween(const std::vector<RoomGeom>& geoms, const std::vector<RoomGeom>& placed, const State& s,
                               const std::vector<std::vector<char>>& used, int a, int b, const PlacementOptions& o,
                               const PlacementConstraints& c) {
  auto forbidden = [&](const OpeningRef& x, const OpeningRef& y) {
    return std::any_of(c.different.begin(), c.different.end(), [&](const auto& p) {
      return (p.first == x && p.second == y) || (p.first == y && p.second == x);
    });
  };
  std::vector<Swap> out;
  const RoomGeom &ga = geoms[a], &gb = geoms[b], &pa = placed[a];
  for (int i = 0; i < static_cast<int>(ga.doors.size()); ++i) {
    if (used[a][i]) continue;
    const Hole& da = ga.doors[i];
    for (int j = 0; j < static_cast<int>(gb.doors.size()); ++j) {
      const Hole& db = gb.doors[j];
      if (used[b][j] || forbidden({a, da.opening}, {b, db.opening}) || !WidthsMatch(da.width, db.width, o)) continue;
      out.push_back({.link = {.a = {a, da.opening}, .b = {b, db.opening}},
                     .part_room = b,
                     .pose = s.pose[a] * LinkTransform(da, db, o.wall_thickness_m)});
    }
  }
  // A door one of the two surveys missed.
  for (const OneSidedLink& l : OneSidedLinks(pa, gb, used[a], used[b], o.wall_thickness_m)) {
    out.push_back({.link = {.a = {a, l.a_door >= 0 ? ga.doors[l.a_door].opening : -1},
                            .b = {b, l.b_door >= 0 ? gb.doors[l.b_door].opening : -1},
                            .wall_a = l.a_wall,
                            .wall_b = l.b_wall},
                   .part_room = b,
                   .pose = l.pose});
  }
  return out;
}

// The area of the box of the rooms' walls in the home's axes.
double BoxOf(const std::vector<const RoomGeom*>& rooms, const Eigen::Matrix2d& axes) {
  Vec2 lo = Vec2::Constant(1e300), hi = Vec2::Constant(-1e300);
  for (const RoomGeom* g : rooms) GrowBox(*g, axes, lo, hi);
  return BoxArea(lo, hi);
}

// Each room's link from the roots (the seed, the rooms a person fixed):
// link_of, and each link turned so that its b is the room it placed.
void Orient(const std::vector<int>& roots, State& s) {
  const std::size_t n = s.placed.size();
  std::vector<char> seen(n, 0);
  std::vector<int> queue = roots;
  for (int r : roots) seen[r] = 1;
  std::fill(s.link_of.begin(), s.link_of.end(), -1);
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const int r = queue[q];
    for (std::size_t k = 0; k < s.links.size(); ++k) {
      RoomLink& l = s.links[k];
      if (l.a.room != r && l.b.room != r) continue;
      if (seen[l.a.room == r ? l.b.room : l.a.room]) continue;  // The link that placed r, or a loop.
      if (l.b.room == r) {
        std::swap(l.a, l.b);
        std::swap(l.wall_a, l.wall_b);
      }
      seen[l.b.room] = 1;
      s.link_of[l.b.room] = static_cast<int>(k);
      queue.push_back(l.b.room);
    }
  }
}

// Rooms reached from the roots by the links other than `cut`: the part of
// the home that stays when `cut` is swapped.
std::vector<char> Stays(const State& s, const std::vector<int>& roots, int cut) {
  std::vector<char> stays(s.placed.size(), 0);
  std::vector<int> queue = roots;
  for (int r : roots) stays[r] = 1;
  for (std::size_t q = 0; q < queue.size(); ++q) {
    for (int k = 0; k < static_cast<int>(s.links.size()); ++k) {
      const RoomLink& l = s.links[k];
      if (k == cut || (l.a.room != queue[q] && l.b.room != queue[q])) continue;
      const int other = l.a.room == queue[q] ? l.b.room : l.a.room;
      if (!stays[other]) {
        stays[other] = 1;
        queue.push_back(other);
      }
    }
  }
  return stays;
}

// The doors in use without the link `cut` (-1: none): those of the other
// links, and those that meet a door of another room on the same side of the
// cut (`side`: per room; all alike when nothing is cut).
std::vector<std::vector<char>> UsedDoors(const std::vector<RoomGeom>& geoms, const std::vector<RoomGeom>& placed,
                                         const State& s, int cut, const std::vector<char>& side,
                                         const PlacementOptions& o) {
  std::vector<std::vector<char>> used;
  for (const RoomGeom& g : geoms) used.emplace_back(g.doors.size(), 0);
  for (int k = 0; k < static_cast<int>(s.links.size()); ++k) {
    if (k == cut) continue;
    for (const OpeningRef& end : {s.links[k].a, s.links[k].b}) {
      if (end.opening >= 0) used[end.room][DoorIndex(geoms[end.room], end.opening)] = 1;
    }
  }
  State marks = s;
  marks.used = std::move(used);
  for (int r = 0; r < static_cast<int>(geoms.size()); ++r) {
    if (!s.placed[r]) continue;
    std::vector<const RoomGeom*> same(geoms.size(), nullptr);
    for (int y = 0; y < static_cast<int>(geoms.size()); ++y) {
      if (s.placed[y] && side[y] == side[r]) same[y] = &placed[y];
    }
    MarkMeetingDoors(same, r, o, marks);
  }
  return marks.used;
}

}  // namespace

void ImproveBySwaps(const std::vector<RoomGeom>& geoms, int seed, const PlacementOptions& o,
                    const PlacementConstraints& c, State& s, double min_gain) {
  const int n = static_cast<int>(geoms.size());
  std::vector<int> roots = {seed};
  for (const auto& f : c.fixed) {
    if (f.first != seed) roots.push_back(f.first);
  }
  Eigen::Matrix2d axes = Eigen::Matrix2d::Identity();
  if (!geoms[seed].walls.empty()) {
    axes.col(0) = s.pose[seed].linear() * geoms[seed].walls.front().Dir();
    axes.col(1) = Perp(axes.col(0));
  }
  Orient(roots, s);
  std::vector<RoomGeom> placed(n);
  for (int r = 0; r < n; ++r) {
    if (s.placed[r]) placed[r] = Transformed(geoms[r], s.pose[r]);
  }
  for (int round = 0; round < 2 * n; ++round) {
    double best_gain = min_gain;
    std::optional<std::pair<int, Swap>> best;
    for (int cut = 0; cut < static_cast<int>(s.links.size()); ++cut) {
      const RoomLink& old = s.links[cut];
      if (old.by_user) continue;
      const std::vector<char> stays = Stays(s, roots, cut);
      std::vector<int> moves, keeps;
      for (int r = 0; r < n; ++r) {
        if (s.placed[r]) (stays[r] ? keeps : moves).push_back(r);
      }
      if (moves.empty()) continue;
      const std::vector<std::vector<char>> used = UsedDoors(geoms, placed, s, cut, stays, o);
      double before = LinkTerms(geoms, old);
      std::vector<const RoomGeom*> kept_geoms;
      for (int y : keeps) kept_geoms.push_back(&placed[y]);
      std::vector<const RoomGeom*> all = kept_geoms;
      for (int x : moves) {
        all.push_back(&placed[x]);
        for (int y : keeps) before += PairScore(placed[x], placed[y], o).value_or(-1000.0);
      }
      before -= kEmptyPerM2 * BoxOf(all, axes);
      for (int a : keeps) {
        for (int b : moves) {
          for (Swap& swap : SwapsBetween(geoms, placed, s, used, a, b, o, c)) {
            const Pose delta = swap.pose * s.pose[b].inverse();
            if (delta.translation().norm() < 0.02 && std::abs(YawOf(delta)) < 0.01) continue;
            double after = LinkTerms(geoms, swap.link);
            std::vector<RoomGeom> moved;
            moved.reserve(moves.size());
            bool refused = false;
            for (int x : moves) {
              moved.push_back(Transformed(geoms[x], delta * s.pose[x]));
              for (int y : keeps) {
                const std::optional<double> term = PairScore(moved.back(), placed[y], o);
                if (!term) refused = true;
                after += term.value_or(0.0);
                if (refused) break;
              }
              if (refused) break;
            }
            if (refused) continue;
            std::vector<const RoomGeom*> now = kept_geoms;
            for (const RoomGeom& g : moved) now.push_back(&g);
            after -= kEmptyPerM2 * BoxOf(now, axes);
            if (after - before > best_gain) {
              best_gain = after - before;
              best = std::pair{cut, swap};
            }
          }
        }
      }
    }
    if (!best) return;
    // Apply: the part beyond the cut moves as one, the links swap.
    const auto& [cut, swap] = *best;
    const RoomLink old = s.links[cut];
    const Pose delta = swap.pose * s.pose[swap.part_room].inverse();
    const std::vector<char> stays = Stays(s, roots, cut);
    for (int r = 0; r < n; ++r) {
      if (!s.placed[r] || stays[r]) continue;
      s.pose[r] = delta * s.pose[r];
      placed[r] = Transformed(geoms[r], s.pose[r]);
    }
    s.links[cut] = swap.link;
    s.links[cut].score = old.score + best_gain;
    s.score += best_gain;
    s.used = UsedDoors(geoms, placed, s, -1, std::vector<char>(n, 0), o);
    Orient(roots, s);
  }
}

}  // namespace asbuilt::placement
