#include "asbuilt/plan/sample.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// True when the open segment p→q properly crosses segment a→b.
bool Crosses(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b) {
  Vec2 r = q - p, s = b - a;
  double den = Cross(r, s);
  if (std::abs(den) < 1e-12) return false;
  double t = Cross(a - p, s) / den;
  double u = Cross(a - p, r) / den;
  return t > 1e-6 && t < 1 - 1e-6 && u > 1e-6 && u < 1 - 1e-6;
}

}  // namespace

void SampleOptions::Check() const {
  auto positive = [](double v, const char* name) {
    CheckArgument(v > 0 && std::isfinite(v), fmt::format("SampleOptions.{} = {}, must be > 0", name, v));
  };
  auto non_negative = [](double v, const char* name) {
    CheckArgument(v >= 0 && std::isfinite(v), fmt::format("SampleOptions.{} = {}, must be >= 0", name, v));
  };
  positive(wall_points_per_m2, "wall_points_per_m2");
  non_negative(opening_points_per_m2, "opening_points_per_m2");
  non_negative(sigma_base_m, "sigma_base_m");
  non_negative(sigma_per_m2, "sigma_per_m2");
  non_negative(lateral_fraction, "lateral_fraction");
  CheckArgument(outlier_fraction >= 0 && outlier_fraction < 1,
                fmt::format("SampleOptions.outlier_fraction = {}, must be in [0, 1)", outlier_fraction));
  non_negative(door_casing_m, "door_casing_m");
  non_negative(window_casing_m, "window_casing_m");
  positive(default_height_m, "default_height_m");
}

Vec3 SampleViewpoint(const Plan& plan, const SampleOptions& options) {
  if (options.viewpoint_m) return *options.viewpoint_m;
  Vec2 c = Vec2::Zero();
  if (!plan.rooms.empty() && plan.rooms[0].polygon.size() >= 3) {
    // Area centroid of the polygon.
    const auto& poly = plan.rooms[0].polygon;
    double a = 0;
    for (size_t i = 0; i < poly.size(); ++i) {
      const Vec2& p = poly[i];
      const Vec2& q = poly[(i + 1) % poly.size()];
      double cr = Cross(p, q);
      a += cr;
      c += cr * (p + q);
    }
    c /= 3.0 * a;
  } else {
    for (const PlanWall& w : plan.walls) c += 0.5 * (w.start + w.end);
    if (!plan.walls.empty()) c /= static_cast<double>(plan.walls.size());
  }
  return Vec3(c.x(), c.y(), 1.45);
}

std::vector<ClassPoint> SamplePointsFromPlan(const Plan& plan, const SampleOptions& options, std::uint64_t seed) {
  options.Check();
  CheckArgument(!plan.walls.empty(), "SamplePointsFromPlan: the plan has no walls");
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Vec3 eye = SampleViewpoint(plan, options);
  const Vec2 eye2 = eye.head<2>();

  std::vector<ClassPoint> points;
  auto add_noisy = [&](LabelClass label, const Vec3& p, int own_wall) {
    // Occlusion: the 2-D ray from the viewpoint must not cross another wall
    // (its own wall is open there: glass and leaves sit in the opening).
    Vec2 p2 = p.head<2>();
    Vec2 towards = (p2 - eye2);
    Vec2 shortened = eye2 + towards * (1.0 - 0.02 / std::max(0.05, towards.norm()));
    for (int i = 0; i < static_cast<int>(plan.walls.size()); ++i) {
      if (i != own_wall && Crosses(eye2, shortened, plan.walls[i].start, plan.walls[i].end)) return;
    }
    Vec3 ray = p - eye;
    double d = ray.norm();
    if (d < 1e-6) return;
    ray /= d;
    Vec3 a = ray.cross(Vec3::UnitZ());
    if (a.norm() < 1e-6) a = Vec3::UnitX();
    a.normalize();
    Vec3 b = ray.cross(a);
    double sigma = options.sigma_base_m + options.sigma_per_m2 * d * d;
    Vec3 noisy = p + sigma * gauss(rng) * ray + options.lateral_fraction * sigma * (gauss(rng) * a + gauss(rng) * b);
    points.push_back({label, noisy, sigma, options.source, -1});
  };

  for (int wi = 0; wi < static_cast<int>(plan.walls.size()); ++wi) {
    const PlanWall& w = plan.walls[wi];
    const double length = w.Length();
    const double height = w.height.value_or(options.default_height_m);
    const Vec2 dir = (w.end - w.start) / length;
    const Vec2 inward(-dir.y(), dir.x());  // Interior is to the left of start → end.
    // Label areas of this wall's openings, in (t, z) wall coordinates.
    struct Area {
      LabelClass label;
      double t0, t1, z0, z1;  // Labelled extent (clear opening + casing).
      double c0, c1, s0, s1;  // Clear opening.
      double recess_m;        // Glass / leaf behind the face.
    };
    std::vector<Area> areas;
    for (const PlanOpening& o : plan.openings) {
      if (o.wall != wi) continue;
      bool door = o.kind == OpeningKind::kDoor;
      double casing = door ? options.door_casing_m : options.window_casing_m;
      double c0 = dir.dot(o.start - w.start), c1 = dir.dot(o.end - w.start);
      if (c0 > c1) std::swap(c0, c1);
      double sill = o.sill.value_or(door ? 0.0 : 0.9);
      double h = o.height.value_or(door ? 2.1 : 1.2);
      areas.push_back({door ? LabelClass::kDoor : LabelClass::kWindow, c0 - casing, c1 + casing,
                       std::max(0.0, sill - (door ? 0.0 : casing)), std::min(height, sill + h + casing), c0, c1, sill,
                       sill + h, door ? 0.03 : 0.5 * w.thickness.value_or(0.2)});
    }
    auto sample_at = [&](double t, double z) {
      LabelClass label = LabelClass::kWall;
      double recess = 0.0;
      for (const Area& ar : areas) {
        if (t >= ar.t0 && t <= ar.t1 && z >= ar.z0 && z <= ar.z1) {
          label = ar.label;
          bool clear = t > ar.c0 && t < ar.c1 && z > ar.s0 && z < ar.s1;
          recess = clear ? ar.recess_m : 0.0;
        }
      }
      Vec2 xy = w.start + t * dir - recess * inward;
      add_noisy(label, Vec3(xy.x(), xy.y(), z), wi);
    };
    int n = static_cast<int>(std::round(options.wall_points_per_m2 * length * height));
    for (int i = 0; i < n; ++i) sample_at(uni(rng) * length, uni(rng) * height);
    for (const Area& ar : areas) {
      int m = static_cast<int>(std::round(options.opening_points_per_m2 * (ar.t1 - ar.t0) * (ar.z1 - ar.z0)));
      for (int i = 0; i < m; ++i) {
        sample_at(ar.t0 + uni(rng) * (ar.t1 - ar.t0), ar.z0 + uni(rng) * (ar.z1 - ar.z0));
      }
    }
  }

  // Outliers: uniform in the plan's bounding box grown by 0.5 m, labels in
  // proportion 80 % wall, 10 % door, 10 % window.
  if (options.outlier_fraction > 0 && !points.empty()) {
    Vec2 lo = plan.walls[0].start, hi = lo;
    double height = 0;
    for (const PlanWall& w : plan.walls) {
      lo = lo.cwiseMin(w.start).cwiseMin(w.end);
      hi = hi.cwiseMax(w.start).cwiseMax(w.end);
      height = std::max(height, w.height.value_or(options.default_height_m));
    }
    lo -= Vec2(0.5, 0.5);
    hi += Vec2(0.5, 0.5);
    int n = static_cast<int>(std::round(points.size() * options.outlier_fraction / (1 - options.outlier_fraction)));
    for (int i = 0; i < n; ++i) {
      double r = uni(rng);
      LabelClass label = r < 0.8 ? LabelClass::kWall : (r < 0.9 ? LabelClass::kDoor : LabelClass::kWindow);
      Vec3 p(lo.x() + uni(rng) * (hi.x() - lo.x()), lo.y() + uni(rng) * (hi.y() - lo.y()), uni(rng) * height);
      double sigma = options.sigma_base_m + options.sigma_per_m2 * (p - eye).squaredNorm();
      points.push_back({label, p, sigma, options.source, -1});
    }
    // Interleave so that no consumer can rely on the order.
    std::shuffle(points.begin(), points.end(), rng);
  }
  return points;
}

}  // namespace asbuilt
