#include "asbuilt/home/home_plan.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "asbuilt/geometry/polygon.h"
#include "asbuilt/plan/room_iou.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

using Pose = Eigen::Isometry2d;

// A room's outline: its plan's polygon, or its walls' ends in order when the
// survey closed none (so the room keeps its name and place on the drawing).
std::vector<Vec2> OutlineOf(const Plan& plan) {
  for (const PlanRoom& r : plan.rooms) {
    if (r.polygon.size() >= 3) return r.polygon;
  }
  std::vector<Vec2> ends;
  for (const PlanWall& w : plan.walls) ends.push_back(w.start);
  return ends.size() >= 3 ? ends : std::vector<Vec2>{};
}

// The normal of a wall's face out of its room (away from the outline's
// inside; to the right of a counter-clockwise ring without an outline).
Vec2 OutwardNormal(const PlanWall& w, const std::vector<Vec2>& outline) {
  const Vec2 d = (w.end - w.start).normalized();
  const Vec2 right(d.y(), -d.x());
  if (outline.size() < 3) return right;
  return PointInPolygon(outline, 0.5 * (w.start + w.end) + 0.05 * right) ? Vec2(-right) : right;
}

struct Box {
  Vec2 lo = Vec2::Constant(1e300), hi = Vec2::Constant(-1e300);
  void Grow(const Vec2& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool Empty() const { return lo.x() > hi.x(); }
};

Box BoxOf(const Plan& plan, const Pose& t) {
  Box b;
  for (const PlanWall& w : plan.walls) {
    b.Grow(t * w.start);
    b.Grow(t * w.end);
  }
  for (const Vec2& p : OutlineOf(plan)) b.Grow(t * p);
  return b;
}

}  // namespace

std::vector<Pose> DrawnRoomPoses(const std::vector<HomeRoomInput>& rooms, const HomePlacement& placement,
                                 const HomePlanOptions& o) {
  std::vector<Pose> pose(rooms.size(), Pose::Identity());
  Box placed;
  for (std::size_t r = 0; r < rooms.size(); ++r) {
    if (!placement.rooms[r].placed) continue;
    pose[r] = placement.rooms[r].floor_from_room;
    const Box b = BoxOf(rooms[r].plan, pose[r]);
    if (!b.Empty()) {
      placed.Grow(b.lo);
      placed.Grow(b.hi);
    }
  }
  double x = placed.Empty() ? 0.0 : placed.hi.x() + o.beside_gap_m;
  const double y = placed.Empty() ? 0.0 : placed.lo.y();
  for (std::size_t r = 0; r < rooms.size(); ++r) {
    if (placement.rooms[r].placed) continue;
    const Box b = BoxOf(rooms[r].plan, Pose::Identity());
    if (b.Empty()) continue;
    pose[r].translation() = Vec2(x, y) - b.lo;
    x += b.hi.x() - b.lo.x() + o.beside_gap_m;
  }
  return pose;
}

namespace {

int VerdictRank(const std::string& v) { return v == "unreliable" ? 2 : v == "check" ? 1 : 0; }

// The home's verdict: its worst room's, and "check" while a room is unplaced.
std::optional<PlanVerdictNote> HomeVerdict(const std::vector<HomeRoomInput>& rooms, const HomePlacement& placement) {
  PlanVerdictNote note{.verdict = "good", .confidence = 1.0};
  bool any = false;
  for (std::size_t r = 0; r < rooms.size(); ++r) {
    if (!placement.rooms[r].placed) {
      if (VerdictRank(note.verdict) < 1) note.verdict = "check";
      note.reasons.push_back(fmt::format("{}: {}", rooms[r].name, placement.rooms[r].placed_by));
    }
    const auto& v = rooms[r].plan.verdict;
    if (!v) continue;
    any = true;
    note.confidence = std::min(note.confidence, v->confidence);
    if (VerdictRank(v->verdict) > VerdictRank(note.verdict)) note.verdict = v->verdict;
    if (VerdictRank(v->verdict) > 0) {
      note.reasons.push_back(
          fmt::format("{}: {}{}", rooms[r].name, v->verdict, v->reasons.empty() ? "" : " — " + v->reasons.front()));
    }
  }
  if (!any && note.reasons.empty()) return std::nullopt;
  return note;
}

// Merges the two faces of each partition: the shorter face is dropped when
// the longer covers it, the longer takes the distance as its thickness, and
// what the dropped face held moves onto the kept one.
void MergePartitions(Plan& plan, const std::vector<int>& room_of_wall, const std::vector<Vec2>& normal_out,
                     const HomePlanOptions& o) {
  const double anti = std::cos(3.0 * std::numbers::pi / 180.0);
  std::vector<int> merged_into(plan.walls.size(), -1);
  for (std::size_t i = 0; i < plan.walls.size(); ++i) {
    for (std::size_t j = 0; j < plan.walls.size(); ++j) {
      if (i == j || room_of_wall[i] == room_of_wall[j] || merged_into[i] >= 0 || merged_into[j] >= 0) continue;
      const PlanWall &keep = plan.walls[i], &drop = plan.walls[j];
      if (drop.Length() > keep.Length()) continue;
      const Vec2 d = (keep.end - keep.start).normalized();
      const Vec2 dd = (drop.end - drop.start).normalized();
      if (d.dot(dd) > -anti) continue;
      const Vec2& n = normal_out[i];
      const double da = (drop.start - keep.start).dot(n), db = (drop.end - keep.start).dot(n);
      if (std::min(da, db) < -0.03 || std::max(da, db) > o.max_wall_thickness_m) continue;
      const double s0 = (drop.start - keep.start).dot(d), s1 = (drop.end - keep.start).dot(d);
      const double lo = std::max(0.0, std::min(s0, s1)), hi = std::min(keep.Length(), std::max(s0, s1));
      if (hi - lo < o.min_partition_overlap * drop.Length()) continue;
      merged_into[j] = static_cast<int>(i);
      plan.walls[i].thickness = std::max(0.0, 0.5 * (da + db));
    }
  }
  std::vector<int> new_index(plan.walls.size(), -1);
  std::vector<PlanWall> walls;
  for (std::size_t w = 0; w < plan.walls.size(); ++w) {
    if (merged_into[w] >= 0) continue;
    new_index[w] = static_cast<int>(walls.size());
    walls.push_back(plan.walls[w]);
  }
  for (PlanOpening& op : plan.openings) {
    if (const int into = merged_into[op.wall]; into >= 0) {
      const PlanWall& k = plan.walls[into];
      const Vec2 d = (k.end - k.start).normalized();
      const Vec2 a = k.start + (op.start - k.start).dot(d) * d, b = k.start + (op.end - k.start).dot(d) * d;
      const bool flip = (b - a).dot(d) < 0;
      op.start = flip ? b : a;
      op.end = flip ? a : b;
      op.wall = into;
    }
    op.wall = new_index[op.wall];
  }
  plan.walls = std::move(walls);
}

}  // namespace

void HomePlanOptions::Check() const {
  if (!(beside_gap_m >= 0 && beside_gap_m <= 100))
    throw InvalidArgument("HomePlanOptions: beside_gap_m must be in [0, 100]");
  if (!(max_wall_thickness_m > 0 && max_wall_thickness_m <= 1)) {
    throw InvalidArgument("HomePlanOptions: max_wall_thickness_m must be in (0, 1]");
  }
  if (!(min_partition_overlap > 0 && min_partition_overlap <= 1)) {
    throw InvalidArgument("HomePlanOptions: min_partition_overlap must be in (0, 1]");
  }
}

Plan HomePlan(const std::vector<HomeRoomInput>& rooms, const HomePlacement& placement, const HomePlanOptions& options) {
  options.Check();
  if (placement.rooms.size() != rooms.size()) throw InvalidArgument("HomePlan: one placement per room expected");
  const std::vector<Pose> pose = DrawnRoomPoses(rooms, placement, options);
  Plan home;
  home.verdict = HomeVerdict(rooms, placement);
  std::vector<int> room_of_wall, room_entry(rooms.size(), -1);
  std::vector<Vec2> normal_out;
  // Per room, where its openings start in home.openings; linked doors are
  // found by (room, opening) through it.
  std::vector<int> first_opening(rooms.size(), 0);
  std::vector<char> dropped;
  for (std::size_t r = 0; r < rooms.size(); ++r) {
    const Plan& p = rooms[r].plan;
    const Pose& t = pose[r];
    const int wall0 = static_cast<int>(home.walls.size());
    first_opening[r] = static_cast<int>(home.openings.size());
    const std::vector<Vec2> outline = OutlineOf(p);
    for (PlanWall w : p.walls) {
      normal_out.push_back(t.linear() * OutwardNormal(w, outline));
      w.start = t * w.start;
      w.end = t * w.end;
      home.walls.push_back(w);
      room_of_wall.push_back(static_cast<int>(r));
    }
    for (PlanOpening o : p.openings) {
      o.start = t * o.start;
      o.end = t * o.end;
      o.wall += wall0;
      home.openings.push_back(o);
      dropped.push_back(0);
    }
    if (outline.empty()) continue;
    PlanRoom room;
    for (const Vec2& q : outline) room.polygon.push_back(t * q);
    if (PolygonArea(room.polygon) < 0) std::reverse(room.polygon.begin(), room.polygon.end());
    room.area_m2 = p.rooms.empty() ? std::abs(PolygonArea(room.polygon)) : p.rooms.front().area_m2;
    if (!p.rooms.empty()) room.area_sigma_m2 = p.rooms.front().area_sigma_m2;
    room.name = rooms[r].name;
    if (placement.rooms[r].placed) room.pose = TransformPose(placement.rooms[r].floor_from_room);
    room.placed_by = placement.rooms[r].placed_by;
    room_entry[r] = static_cast<int>(home.rooms.size());
    home.rooms.push_back(std::move(room));
  }
  for (const RoomLink& l : placement.links) {
    // The door kept: a's, or the only side that saw it.
    const OpeningRef& kept_side = l.a.opening >= 0 ? l.a : l.b;
    const int kept_index = first_opening[kept_side.room] + kept_side.opening;
    if (l.a.opening >= 0 && l.b.opening >= 0) dropped[first_opening[l.b.room] + l.b.opening] = 1;
    if (room_entry[l.a.room] >= 0 && room_entry[l.b.room] >= 0) {
      home.openings[kept_index].rooms = std::pair{room_entry[l.a.room], room_entry[l.b.room]};
    }
  }
  std::vector<PlanOpening> kept;
  for (std::size_t i = 0; i < home.openings.size(); ++i) {
    if (!dropped[i]) kept.push_back(home.openings[i]);
  }
  home.openings = std::move(kept);
  MergePartitions(home, room_of_wall, normal_out, options);
  return home;
}

std::string HomeScore::ToString() const {
  return fmt::format("{}/{} rooms within the tolerances ({} placed), floor IoU {:.3f}", within, rooms, placed,
                     floor_iou);
}

HomeScore ScoreHome(const std::vector<HomeRoomInput>& rooms, const HomePlacement& placement,
                    const std::vector<Eigen::Isometry2d>& truth_floor_from_room,
                    const std::vector<std::vector<Vec2>>& truth_outline, const HomeScoreOptions& o) {
  const std::size_t n = rooms.size();
  if (placement.rooms.size() != n || truth_floor_from_room.size() != n || truth_outline.size() != n) {
    throw InvalidArgument("ScoreHome: one placement, truth pose and truth outline per room expected");
  }
  HomeScore score;
  score.rooms = static_cast<int>(n);
  std::vector<Vec2> centre(n, Vec2::Zero());
  for (std::size_t r = 0; r < n; ++r) {
    const std::vector<Vec2> outline = OutlineOf(rooms[r].plan);
    for (const Vec2& p : outline) centre[r] += p;
    if (!outline.empty()) centre[r] /= static_cast<double>(outline.size());
    score.placed += placement.rooms[r].placed;
  }
  auto errors = [&](const Pose& align, std::size_t r) {
    const Pose home = align * placement.rooms[r].floor_from_room;
    const double dp = (home * centre[r] - truth_floor_from_room[r] * centre[r]).norm();
    const double dy = std::abs(std::remainder(YawOf(home) - YawOf(truth_floor_from_room[r]), 2 * std::numbers::pi));
    return std::pair{dp, dy * 180 / std::numbers::pi};
  };
  auto inliers = [&](const Pose& align) {
    std::vector<std::size_t> in;
    for (std::size_t r = 0; r < n; ++r) {
      if (!placement.rooms[r].placed) continue;
      const auto [dp, dy] = errors(align, r);
      if (dp <= o.position_tolerance_m && dy <= o.yaw_tolerance_deg) in.push_back(r);
    }
    return in;
  };
  // Candidate alignments: each placed room on its truth; the most rooms
  // within tolerance wins, then refined over them (2D Procrustes of centres,
  // yaw as the mean of their yaw differences).
  Pose best = Pose::Identity();
  std::size_t best_count = 0;
  for (std::size_t r = 0; r < n; ++r) {
    if (!placement.rooms[r].placed) continue;
    Pose align = truth_floor_from_room[r] * placement.rooms[r].floor_from_room.inverse();
    std::vector<std::size_t> in = inliers(align);
    if (in.size() >= 2) {
      double dyaw = 0;
      for (std::size_t k : in) {
        dyaw += std::remainder(YawOf(truth_floor_from_room[k]) - YawOf(placement.rooms[k].floor_from_room),
                               2 * std::numbers::pi);
      }
      dyaw /= static_cast<double>(in.size());
      Vec2 mh = Vec2::Zero(), mt = Vec2::Zero();
      for (std::size_t k : in) {
        mh += placement.rooms[k].floor_from_room * centre[k];
        mt += truth_floor_from_room[k] * centre[k];
      }
      mh /= static_cast<double>(in.size());
      mt /= static_cast<double>(in.size());
      Pose refined = Pose::Identity();
      refined.linear() = Eigen::Rotation2Dd(dyaw).toRotationMatrix();
      refined.translation() = mt - refined.linear() * mh;
      if (inliers(refined).size() >= in.size()) {
        align = refined;
        in = inliers(refined);
      }
    }
    if (in.size() > best_count) {
      best_count = in.size();
      best = align;
    }
  }
  score.truth_from_home = best;
  score.within = static_cast<int>(best_count);
  Plan predicted, truth;
  for (std::size_t r = 0; r < n; ++r) {
    if (placement.rooms[r].placed) {
      const auto [dp, dy] = errors(best, r);
      score.centroid_error_m.push_back(dp);
      score.yaw_error_deg.push_back(dy);
      PlanRoom room;
      for (const Vec2& p : OutlineOf(rooms[r].plan))
        room.polygon.push_back(best * placement.rooms[r].floor_from_room * p);
      if (room.polygon.size() >= 3) predicted.rooms.push_back(std::move(room));
    } else {
      score.centroid_error_m.push_back(NAN);
      score.yaw_error_deg.push_back(NAN);
    }
    if (truth_outline[r].size() >= 3) truth.rooms.push_back(PlanRoom{.polygon = truth_outline[r]});
  }
  if (auto overlap = RoomPolygonOverlap(predicted, truth, RoomIouOptions{.row_step_m = 0.005})) {
    score.floor_iou = overlap->Iou();
  }
  return score;
}

}  // namespace asbuilt
