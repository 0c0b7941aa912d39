#include "asbuilt/home/placement.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "asbuilt/home/placement_geometry.h"
#include "asbuilt/home/placement_improve.h"
#include "asbuilt/home/placement_refine.h"
#include "asbuilt/home/placement_search.h"
#include "asbuilt/util/error.h"

// PlaceRooms in stages: each room's geometry (placement_geometry.h), the
// beam search from the first room and from the two with most doors
// (placement_search.h), then each distinct placement refined into a
// HomePlacement (placement_refine.h).

namespace asbuilt {
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
  if (improve < 0 || improve > 100) fail("improve must be in [0, 100]");
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
  // A person who moves the room the home grew from moves that room, not the
  // home: grown from it, every room would follow it by the same links. The
  // home then grows from a room they did not move, where it was.
  if (fixed[seed] && !constraints.previous.empty()) {
    for (std::size_t r = 0; r < rooms.size(); ++r) {
      if (fixed[r] || !constraints.previous[r] || placer.geoms()[r].doors.empty()) continue;
      seed = static_cast<int>(r);
      seed_pose = PoseTransform(*constraints.previous[r]);
      break;
    }
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
  // The best few placements improved by swapping links, then ranked again.
  std::sort(done.begin(), done.end(), [](const State& x, const State& y) { return x.score > y.score; });
  for (int i = 0; i < options.improve && i < static_cast<int>(done.size()); ++i) {
    placement::ImproveBySwaps(placer.geoms(), seed, options, constraints, done[i]);
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
