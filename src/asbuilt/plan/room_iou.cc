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

// Sorted, disjoint intervals of the line y = const inside `plan`'s rooms,
// into `merged`; `all` and `xs` are scratch (reused across scanlines).
void CoverInto(const Plan& plan, double y, Intervals& all, std::vector<double>& xs, Intervals& merged) {
  all.clear();
  for (const PlanRoom& room : plan.rooms) {
    const std::vector<Vec2>& p = room.polygon;
    if (p.size() < 3) continue;
    xs.clear();
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
  merged.clear();
  for (const auto& iv : all) {
    if (!merged.empty() && iv.first <= merged.back().second) {
      merged.back().second = std::max(merged.back().second, iv.second);
    } else {
      merged.push_back(iv);
    }
  }
}

// Scratch for scanning two plans row by row.
struct ScanBuffers {
  Intervals all, a, b;
  std::vector<double> xs;
};

// The y-range of `plan`'s room polygons.
std::pair<double, double> YRange(const Plan& plan) {
  double y0 = INFINITY, y1 = -INFINITY;
  for (const PlanRoom& r : plan.rooms) {
    for (const Vec2& v : r.polygon) y0 = std::min(y0, v.y()), y1 = std::max(y1, v.y());
  }
  return {y0, y1};
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
  const auto [pa, pb] = YRange(predicted);
  const auto [ta, tb] = YRange(truth);
  const double y0 = std::min(pa, ta), y1 = std::max(pb, tb);
  RoomOverlap out;
  ScanBuffers buf;
  // Midpoint rule: one scanline through the middle of each row.
  const double h = options.row_step_m;
  for (double y = y0 + 0.5 * h; y < y1; y += h) {
    CoverInto(predicted, y, buf.all, buf.xs, buf.a);
    CoverInto(truth, y, buf.all, buf.xs, buf.b);
    const double la = Length(buf.a), lb = Length(buf.b), li = IntersectionLength(buf.a, buf.b);
    out.predicted_m2 += la * h;
    out.truth_m2 += lb * h;
    out.intersection_m2 += li * h;
    out.union_m2 += (la + lb - li) * h;
  }
  return out;
}

std::optional<double> RoomIntersectionArea(const Plan& a, const Plan& b, const RoomIouOptions& options) {
  options.Check();
  if (!HasRoom(a) || !HasRoom(b)) return std::nullopt;
  const auto [a0, a1] = YRange(a);
  const auto [b0, b1] = YRange(b);
  const double h = options.row_step_m, y0 = std::min(a0, b0);
  // RoomPolygonOverlap's rows, those where both plans have a room only.
  const double from = std::max(a0, b0), to = std::min(a1, b1);
  double y = y0 + 0.5 * h;
  if (from > y) y += std::floor((from - y) / h) * h;
  ScanBuffers buf;
  double area = 0.0;
  for (; y < to; y += h) {
    if (y < from) continue;
    CoverInto(a, y, buf.all, buf.xs, buf.a);
    CoverInto(b, y, buf.all, buf.xs, buf.b);
    area += IntersectionLength(buf.a, buf.b) * h;
  }
  return area;
}

}  // namespace asbuilt
