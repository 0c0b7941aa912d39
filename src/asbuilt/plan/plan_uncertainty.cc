#include "asbuilt/plan/plan_uncertainty.h"

#include <algorithm>
#include <functional>
#include <numeric>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/plan/plan_ring.h"

namespace asbuilt {
namespace {

// Copies of the ring's lines without their member lists (cheap to copy),
// their offset variances raised by what their points share.
std::vector<WallLine> LinesWithSharedVariance(const WallPoints& walls, const std::vector<WallLine>& ring,
                                              const PlanOptions& o) {
  std::vector<WallLine> light;
  light.reserve(ring.size());
  for (const WallLine& l : ring) {
    WallLine& copy = light.emplace_back();
    copy = l;
    copy.members = {};
    if (l.members.empty()) continue;
    std::vector<double> sigmas;
    sigmas.reserve(l.members.size());
    for (int k : l.members) {
      const WallPoint& p = walls.points[k];
      sigmas.push_back((p.contact ? o.shared_sigma_fraction : o.shared_stereo_sigma_fraction) * p.sigma);
    }
    std::nth_element(sigmas.begin(), sigmas.begin() + sigmas.size() / 2, sigmas.end());
    copy.var_rho += std::pow(sigmas[sigmas.size() / 2], 2);
  }
  return light;
}

// Variance of f(lines) from the θ and ρ variances of lines[l], l ∈ `used`,
// by central differences.
double PropagatedVariance(const std::vector<WallLine>& lines,
                          const std::function<double(const std::vector<WallLine>&)>& f,
                          const std::vector<int>& used) {
  auto perturbed = [&](int line, int param, double h) {
    std::vector<WallLine> moved = lines;
    if (param == 0) {
      moved[line].theta += h;
    } else {
      moved[line].c += h * moved[line].Normal();
    }
    return moved;
  };
  double var = 0;
  for (int l : used) {
    for (int param = 0; param < 2; ++param) {
      double v = param == 0 ? lines[l].var_theta : lines[l].var_rho;
      if (v <= 0) continue;
      double h = std::max(1e-7, 1e-3 * std::sqrt(v));
      double d = (f(perturbed(l, param, h)) - f(perturbed(l, param, -h))) / (2 * h);
      var += d * d * v;
    }
  }
  return var;
}

}  // namespace

RingSigmas PropagateRingSigmas(const WallPoints& walls, const std::vector<WallLine>& ring, const PlanOptions& o) {
  const std::vector<WallLine> lines = LinesWithSharedVariance(walls, ring, o);
  const int n = static_cast<int>(lines.size());
  RingSigmas out;
  for (int i = 0; i < n; ++i) {
    auto length = [i, n](const std::vector<WallLine>& L) {
      std::vector<Vec2> c = RingCorners(L);
      return (c[(i + 1) % n] - c[i]).norm();
    };
    out.wall_length_m.push_back(std::sqrt(PropagatedVariance(lines, length, {(i + n - 1) % n, i, (i + 1) % n})));
  }
  std::vector<int> all_lines(n);
  std::iota(all_lines.begin(), all_lines.end(), 0);
  out.area_m2 = std::sqrt(
      PropagatedVariance(lines, [](const std::vector<WallLine>& L) { return std::abs(PolygonArea(RingCorners(L))); },
                         all_lines));
  return out;
}

}  // namespace asbuilt
