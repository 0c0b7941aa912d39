#include "asbuilt/home/placement_refine.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include <Eigen/Dense>
#include <fmt/format.h>

namespace asbuilt::placement {
namespace {

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
          if (!DoorsMeet(da, db, o)) continue;
          links.push_back({.a = {a, da.opening}, .b = {b, db.opening}, .loop = true});
        }
      }
    }
  }
}

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

// Least squares over every link: each room's pose (the seed's fixed) and one
// partition thickness for the home, held near the option's value by a weak
// prior so a home without loops keeps it.
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

}  // namespace

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

}  // namespace asbuilt::placement
