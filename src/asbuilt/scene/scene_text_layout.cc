#include "asbuilt/scene/scene_text_layout.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "asbuilt/scene/scene_text_vocabulary.h"
#include "asbuilt/util/error.h"

namespace asbuilt::scene_text {

std::vector<Vec2> RoomPolygon(const Request& r, double w, double d, std::vector<std::string>& assumptions) {
  if (!r.l_shape) return {{0, 0}, {w, 0}, {w, d}, {0, d}};
  double cw = r.cut_width.value_or(std::round(w * 5.0) / 10.0);
  double cd = r.cut_depth.value_or(std::round(d * 5.0) / 10.0);
  if (!r.cut_width)
    assumptions.push_back(fmt::format("L-shape: {:.2f} × {:.2f} m cut out of the {} corner", cw, cd, r.cut_corner));
  if (cw <= 0 || cd <= 0 || cw >= w - 0.5 || cd >= d - 0.5) {
    throw InputError("text", "",
                     fmt::format("the {:.2f} × {:.2f} m cut-out does not fit in a {:.2f} × {:.2f} m "
                                 "room (each side must leave at least 0.5 m)",
                                 cw, cd, w, d));
  }
  const std::string& k = r.cut_corner;
  if (k == "north-west") return {{0, 0}, {w, 0}, {w, d}, {cw, d}, {cw, d - cd}, {0, d - cd}};
  if (k == "south-east") return {{0, 0}, {w - cw, 0}, {w - cw, cd}, {w, cd}, {w, d}, {0, d}};
  if (k == "south-west") return {{cw, 0}, {w, 0}, {w, d}, {0, d}, {0, cd}, {cw, cd}};
  if (k != "north-east") {
    assumptions.push_back(fmt::format("cut-out corner \"{}\" is not a corner: used north-east", k));
  }
  return {{0, 0}, {w, 0}, {w, d - cd}, {w - cw, d - cd}, {w - cw, d}, {0, d}};
}

namespace {

struct PendingOpening {
  Opening opening;
  Placement placement = Placement::kAuto;
  std::string compass;
  double from_end_m = 0;
  std::string text;
};

// Offsets along each wall: explicit placements first, the rest spread evenly
// (or, when that collides, into the largest free gaps).
void LayOutWall(const Room& room, int wall, std::vector<PendingOpening*>& ops, std::vector<std::string>& assumptions) {
  const double length = WallLength(room, wall);
  const std::string wall_name = fmt::format("{} wall ({:.2f} m)", WallCompassName(room, wall), length);
  const Vec2 dir = (WallEnd(room, wall) - WallStart(room, wall)).normalized();
  double total = 0;
  for (PendingOpening* p : ops) total += p->opening.width_m;
  if (total + 0.1 * (ops.size() + 1) > length + 1e-9) {
    throw InputError("text", "",
                     fmt::format("the {} cannot hold {} opening{} {:.2f} m wide in total", wall_name, ops.size(),
                                 ops.size() == 1 ? "" : "s", total));
  }
  std::vector<std::pair<double, double>> taken;  // [lo, hi] along the wall.
  std::vector<PendingOpening*> automatic;
  for (PendingOpening* p : ops) {
    Opening& o = p->opening;
    const double w = o.width_m;
    auto toward = [&](const std::string& compass, double margin) -> std::optional<double> {
      double t = dir.dot(CompassVector(compass).value_or(Vec2::Zero()));
      if (t > 0.3) return length - w - margin;  // The named end is the wall's end.
      if (t < -0.3) return margin;
      return std::nullopt;
    };
    std::optional<double> offset;
    switch (p->placement) {
      case Placement::kAuto:
        break;
      case Placement::kCentre:
        offset = 0.5 * (length - w);
        break;
      case Placement::kLeft:
        offset = length - w - 0.3;
        break;  // Facing the wall from inside, its end is on the left.
      case Placement::kRight:
        offset = 0.3;
        break;
      case Placement::kCorner:
        offset = p->compass.empty() ? std::optional<double>(0.1) : toward(p->compass, 0.1);
        break;
      case Placement::kEnd:
        offset = toward(p->compass, 0.3);
        break;
      case Placement::kFromEnd: {
        double t = dir.dot(CompassVector(p->compass).value_or(Vec2::Zero()));
        if (t > 0.3) offset = length - w - p->from_end_m;
        if (t < -0.3) offset = p->from_end_m;
        break;
      }
    }
    if (p->placement != Placement::kAuto && !offset) {
      assumptions.push_back(
          fmt::format("\"{}\": the {} end of the {} is not one of its ends; placed "
                      "automatically",
                      p->text, p->compass, wall_name));
    }
    if (!offset) {
      automatic.push_back(p);
      continue;
    }
    if (*offset < -1e-9 || *offset + w > length + 1e-9) {
      throw InputError("text", "",
                       fmt::format("\"{}\": a {:.2f} m {} at {:.2f} m along the {} does not fit", p->text, w,
                                   OpeningKindName(o.kind), *offset, wall_name));
    }
    // Several openings at one spot ("three windows near the north end"):
    // each next one moves away from the anchor until it is clear.
    auto clashes = [&](double at) {
      for (auto [lo, hi] : taken) {
        if (at < hi + 0.1 && at + w > lo - 0.1) return true;
      }
      return false;
    };
    double at = std::max(0.0, *offset);
    const double step = at + 0.5 * w > 0.5 * length ? -0.05 : 0.05;
    while (clashes(at) && at >= 0 && at + w <= length) at += step;
    if (at < -1e-9 || at + w > length + 1e-9) {
      throw InputError("text", "",
                       fmt::format("\"{}\": no room left for a {:.2f} m {} there on the {}", p->text, w,
                                   OpeningKindName(o.kind), wall_name));
    }
    o.offset_m = std::max(0.0, at);
    taken.push_back({o.offset_m, o.offset_m + w});
  }
  if (automatic.empty()) return;
  auto overlaps = [&](double lo, double hi) {
    for (auto [a, b] : taken) {
      if (lo < b + 0.05 && hi > a - 0.05) return true;
    }
    return lo < 0.1 - 1e-9 || hi > length - 0.1 + 1e-9;
  };
  // Even spread (EvenlySpacedOffsets), where it collides with nothing.
  const std::size_t k = automatic.size();
  std::vector<double> widths;
  for (const PendingOpening* p : automatic) widths.push_back(p->opening.width_m);
  const std::vector<double> even = EvenlySpacedOffsets(length, widths);
  bool even_ok = true;
  for (std::size_t i = 0; i < k; ++i) {
    double lo = even[i];
    double hi = lo + automatic[i]->opening.width_m;
    even_ok = even_ok && !overlaps(lo, hi);
    for (std::size_t j = 0; j < i; ++j) {
      double jlo = even[j], jhi = even[j] + automatic[j]->opening.width_m;
      even_ok = even_ok && !(lo < jhi + 0.05 && hi > jlo - 0.05);
    }
  }
  if (even_ok) {
    for (std::size_t i = 0; i < k; ++i) automatic[i]->opening.offset_m = even[i];
    return;
  }
  // Largest free gap, one at a time.
  for (PendingOpening* p : automatic) {
    std::vector<std::pair<double, double>> sorted = taken;
    std::sort(sorted.begin(), sorted.end());
    double best_lo = 0, best_len = -1, cursor = 0.1;
    for (auto [lo, hi] : sorted) {
      if (lo - 0.05 - cursor > best_len) {
        best_len = lo - 0.05 - cursor;
        best_lo = cursor;
      }
      cursor = std::max(cursor, hi + 0.05);
    }
    if (length - 0.1 - cursor > best_len) {
      best_len = length - 0.1 - cursor;
      best_lo = cursor;
    }
    const double w = p->opening.width_m;
    if (best_len < w) {
      throw InputError("text", "",
                       fmt::format("\"{}\": no room left for a {:.2f} m {} on the {}", p->text, w,
                                   OpeningKindName(p->opening.kind), wall_name));
    }
    p->opening.offset_m = best_lo + 0.5 * (best_len - w);
    taken.push_back({p->opening.offset_m, p->opening.offset_m + w});
  }
}

}  // namespace

std::vector<Opening> BuildOpenings(const Request& r, const Room& room, std::vector<std::string>& assumptions) {
  std::vector<PendingOpening> pending;
  for (const OpeningRequest& q : r.openings) {
    if (q.count <= 0) continue;
    Opening base;
    base.kind = q.kind;
    const bool door = q.kind == OpeningKind::kDoor;
    double default_width = door ? 0.9 : (q.french ? 1.4 : 1.2);
    base.width_m = q.width.value_or(default_width * q.width_scale);
    if (door) {
      base.height_m = q.height.value_or(std::min(2.1, room.height_m - 0.1));
      base.sill_m = q.sill.value_or(0.0);
      base.open_deg = q.open_deg.value_or(0.0);
      if (q.hinge) base.hinge = *q.hinge;
    } else {
      double sill = q.sill.value_or(q.french ? 0.0 : 0.9);
      double height = q.height.value_or(q.french ? std::min(2.1, room.height_m - 0.1) : 1.2);
      if (!q.height && sill + height > room.height_m - 0.15) height = room.height_m - 0.15 - sill;
      if (!q.sill && !q.french && height < 0.5) {
        sill = std::max(0.3, room.height_m - 0.15 - 1.2);
        height = room.height_m - 0.15 - sill;
      }
      base.sill_m = sill;
      base.height_m = height;
      if (q.glass) base.glass = *q.glass;
    }
    // Which walls.
    std::vector<int> walls;
    if (q.all_walls) {
      for (int w = 0; w < WallCount(room); ++w) walls.push_back(w);
    } else {
      for (const std::string& name : q.walls) {
        std::vector<int> facing = WallsFacing(room, name);
        if (q.each_wall) {
          walls.insert(walls.end(), facing.begin(), facing.end());
        } else {
          walls.push_back(WallFacing(room, name).value_or(0));
        }
      }
    }
    std::string placement_compass = q.placement_compass;
    if (walls.empty()) {
      // "a door in the north-east corner": the first compass word names the wall.
      std::string name = door ? "south" : "north";
      if (!placement_compass.empty() && (q.placement == Placement::kCorner)) {
        auto dash = placement_compass.find('-');
        if (dash != std::string::npos) {
          name = placement_compass.substr(0, dash);
        }
      }
      walls.push_back(WallFacing(room, name).value_or(0));
      assumptions.push_back(fmt::format("\"{}\": no wall given, used the {} wall", q.text, name));
    }
    if (!q.count_given && q.count > 1 && !q.each_wall) {
      assumptions.push_back(fmt::format("\"{}\": no count given, made {}", q.text, q.count));
    }
    int total = q.each_wall ? q.count * static_cast<int>(walls.size()) : q.count;
    if (!q.count_given && !q.each_wall && walls.size() > 1) total = static_cast<int>(walls.size());
    for (int i = 0; i < total; ++i) {
      PendingOpening p;
      p.opening = base;
      p.opening.wall = q.each_wall ? walls[i / q.count] : walls[i % walls.size()];
      p.placement = q.placement;
      p.compass = placement_compass;
      p.from_end_m = q.from_end_m;
      p.text = q.text;
      pending.push_back(p);
    }
  }
  std::map<int, std::vector<PendingOpening*>> by_wall;
  for (PendingOpening& p : pending) by_wall[p.opening.wall].push_back(&p);
  for (auto& [wall, ops] : by_wall) LayOutWall(room, wall, ops, assumptions);
  std::vector<Opening> out;
  for (const PendingOpening& p : pending) out.push_back(p.opening);
  return out;
}

Vec2 TurnSpot(const std::vector<Vec2>& polygon) {
  if (std::optional<Vec2> spot = SurveySpot(polygon)) return *spot;
  Vec2 c = PolygonCentroid(polygon);
  if (PointInPolygon(polygon, c)) return c;
  Vec2 lo = polygon[0], hi = polygon[0];
  for (const Vec2& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  Vec2 best = c;
  double best_d = 1e18;
  for (int i = 1; i < 40; ++i) {
    for (int j = 1; j < 40; ++j) {
      Vec2 p(lo.x() + (hi.x() - lo.x()) * i / 40.0, lo.y() + (hi.y() - lo.y()) * j / 40.0);
      if (PointInPolygon(polygon, p) && (p - c).norm() < best_d) {
        best_d = (p - c).norm();
        best = p;
      }
    }
  }
  return best;
}

}  // namespace asbuilt::scene_text
