#include "asbuilt/geometry/polygon.h"

#include <algorithm>
#include <cmath>

namespace asbuilt {
namespace {

bool SegmentsCross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = Cross(b - a, c - a), d2 = Cross(b - a, d - a);
  const double d3 = Cross(d - c, a - c), d4 = Cross(d - c, b - c);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

}  // namespace

bool PointInPolygon(const std::vector<Vec2>& polygon, const Vec2& point) {
  if (polygon.size() < 3) return false;
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    if ((a.y() > point.y()) != (b.y() > point.y()) &&
        point.x() < a.x() + (point.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y())) {
      inside = !inside;
    }
  }
  return inside;
}

double PolygonArea(const std::vector<Vec2>& polygon) {
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % polygon.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

int PolygonCrossings(const std::vector<Vec2>& p) {
  const int n = static_cast<int>(p.size());
  int count = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      count += SegmentsCross(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]);
    }
  }
  return count;
}

std::vector<Eigen::Vector3i> TriangulatePolygon(const std::vector<Vec2>& polygon) {
  std::vector<Eigen::Vector3i> out;
  const int n = static_cast<int>(polygon.size());
  if (n < 3) return out;
  std::vector<int> idx(n);
  for (int i = 0; i < n; ++i) idx[i] = i;
  auto inside_tri = [&](const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
    return Cross(b - a, p - a) >= 0 && Cross(c - b, p - b) >= 0 && Cross(a - c, p - c) >= 0;
  };
  int guard = 0;
  while (idx.size() > 3 && guard++ < 10 * n * n) {
    bool clipped = false;
    const int m = static_cast<int>(idx.size());
    for (int i = 0; i < m; ++i) {
      int ia = idx[(i + m - 1) % m], ib = idx[i], ic = idx[(i + 1) % m];
      const Vec2 &a = polygon[ia], &b = polygon[ib], &c = polygon[ic];
      if (Cross(b - a, c - b) <= 1e-12) continue;  // Reflex or degenerate.
      bool ear = true;
      for (int k : idx) {
        if (k == ia || k == ib || k == ic) continue;
        if (inside_tri(polygon[k], a, b, c)) {
          ear = false;
          break;
        }
      }
      if (!ear) continue;
      out.emplace_back(ia, ib, ic);
      idx.erase(idx.begin() + i);
      clipped = true;
      break;
    }
    if (!clipped) break;  // Not simple; fall back to a fan below.
  }
  if (idx.size() == 3) {
    out.emplace_back(idx[0], idx[1], idx[2]);
  } else {
    for (std::size_t i = 1; i + 1 < idx.size(); ++i) out.emplace_back(idx[0], idx[i], idx[i + 1]);
  }
  return out;
}

std::vector<Vec2> OffsetPolygonOutwards(const std::vector<Vec2>& polygon, double distance_m) {
  const int n = static_cast<int>(polygon.size());
  std::vector<Vec2> out(n);
  for (int i = 0; i < n; ++i) {
    Vec2 a = polygon[(i + n - 1) % n], b = polygon[i], c = polygon[(i + 1) % n];
    Vec2 d0 = (b - a).normalized(), d1 = (c - b).normalized();
    Vec2 n0(d0.y(), -d0.x()), n1(d1.y(), -d1.x());  // Outward normals (right side).
    Vec2 bis = n0 + n1;
    double len = bis.norm();
    if (len < 1e-9) {
      out[i] = b + distance_m * n0;
      continue;
    }
    bis /= len;
    double cos_half = std::max(0.2, bis.dot(n0));
    out[i] = b + (distance_m / cos_half) * bis;
  }
  return out;
}

}  // namespace asbuilt
