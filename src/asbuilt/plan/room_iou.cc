#include "asbuilt/plan/room_iou.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

using Intervals = std::vector<std::pair<double, double>>;

// Sorted, disjoint intervals of the line y = const inside `plan`'s rooms.
Intervals Cover(const Plan& plan, double y) {
  Intervals all;
  for (const PlanRoom& room : plan.rooms) {
    const std::vector<Vec2>& p = room.polygon;
    if (p.size() < 3) continue;
    std::vector<double> xs;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec2& a = p[i];
      const Vec2& b = p[(i + 1) % p.size()];
      // Half-open in y so a vertex on the scanline counts once.
      if ((a.y() <= y) != (b.y() <= y)) xs.push_back(a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
    }
    std::sort(xs.begin(), xs.end());
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2) all.emplace_back(xs[i], xs[i + 1]);
  }
  std::sort(all.begin(), all.end());
  Intervals merged;
  for (const auto& iv : all) {
    if (!merged.empty() && iv.first <= merged.back().second) {
      merged.back().second = std::max(merged.back().second, iv.second);
    } else {
      merged.push_back(iv);
    }
  }
  return merged;
}

double Length(const Intervals& a) {
  double sum = 0;
  for (const auto& [x0, x1] : a) sum += x1 - x0;
  return sum;
}

double IntersectionLength(const Intervals& a, const Intervals& b) {
  double sum = 0;
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    sum += std::max(0.0, std::min(a[i].second, b[j].second) - std::max(a[i].first, b[j].first));
    (a[i].second < b[j].second) ? ++i : ++j;
  }
  return sum;
}

bool HasRoom(const Plan& plan) {
  return std::any_of(plan.rooms.begin(), plan.rooms.end(), [](const PlanRoom& r) { return r.polygon.size() >= 3; });
}

}  // namespace

void RoomIouOptions::Check() const {
  CheckArgument(row_step_m >= 1e-5 && row_step_m <= 1.0,
                fmt::format("RoomIouOptions.row_step_m = {}, must be in [1e-5, 1]", row_step_m));
}

std::string RoomOverlap::ToString() const {
  return fmt::format("IoU {:.3f} (∩ {:.2f} m², ∪ {:.2f} m²)", Iou(), intersection_m2, union_m2);
}

std::optional<RoomOverlap> RoomPolygonOverlap(const Plan& predicted, const Plan& truth, const RoomIouOptions& options) {
  options.Check();
  if (!HasRoom(predicted) || !HasRoom(truth)) return std::nullopt;
  double y0 = INFINITY, y1 = -INFINITY;
  for (const Plan* plan : {&predicted, &truth}) {
    for (const PlanRoom& r : plan->rooms) {
      for (const Vec2& v : r.polygon) y0 = std::min(y0, v.y()), y1 = std::max(y1, v.y());
    }
  }
  RoomOverlap out;
  // Midpoint rule: one scanline through the middle of each row.
  const double h = options.row_step_m;
  for (double y = y0 + 0.5 * h; y < y1; y += h) {
    const Intervals a = Cover(predicted, y), b = Cover(truth, y);
    const double la = Length(a), lb = Length(b), li = IntersectionLength(a, b);
    out.predicted_m2 += la * h;
    out.truth_m2 += lb * h;
    out.intersection_m2 += li * h;
    out.union_m2 += (la + lb - li) * h;
  }
  return out;
}

}  // namespace asbuilt
