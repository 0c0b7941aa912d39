#include "asbuilt/plan/plan_uncertainty.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/plan/plan_ring.h"

namespace asbuilt {
namespace {

double MedianOf(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// The variance of a line's offset that its floor and ceiling contacts'
// disagreement shows: each set's median distance to the line (r_f, r_c)
// carries its own label edge's error along the whole wall (a skirting taken
// for floor, a segmenter's edge a pixel off), which no number of points
// averages out. Taking the two errors as independent and alike, E[(r_f −
// r_c)²] = 2σ², and the line, a mix a·floor + (1 − a)·ceiling (a the floor's
// share of the weight), is off by σ² (a² + (1 − a)²). 0 unless both sets
// have kMinEdgeContacts points.
double FloorCeilingDisagreementVariance(const WallPoints& walls, const WallLine& l) {
  constexpr int kMinEdgeContacts = 10;
  std::vector<double> floor, ceiling;
  double w_floor = 0, w_ceiling = 0;
  for (int k : l.members) {
    const WallPoint& p = walls.points[k];
    if (!p.contact) continue;
    const bool on_floor = p.z < kCeilingContactMinZ;
    (on_floor ? floor : ceiling).push_back(l.Distance(p.p));
    (on_floor ? w_floor : w_ceiling) += p.w;
  }
  if (floor.size() < kMinEdgeContacts || ceiling.size() < kMinEdgeContacts) return 0;
  const double a = w_floor / (w_floor + w_ceiling);
  return std::pow(MedianOf(floor) - MedianOf(ceiling), 2) / 2 * (a * a + (1 - a) * (1 - a));
}

// Copies of the ring's lines without their member lists (cheap to copy),
// their offset variances raised by what their points share: the larger of
// (f · median σ) and the floor/ceiling contacts' disagreement.
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
    copy.var_rho += std::max(std::pow(MedianOf(std::move(sigmas)), 2), FloorCeilingDisagreementVariance(walls, l));
  }
  return light;
}

// Variance of f(lines) from the θ and ρ variances of lines[l], l ∈ `used`,
// by central differences.
double PropagatedVariance(const std::vector<WallLine>& lines,
                          const std::function<double(const std::vector<WallLine>&)>& f, const std::vector<int>& used) {
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

// Each line's share of its members' weight that contacts carry (all of
// them, or only the ceiling's, above the floor): how far it follows a scale
// error of those contacts.
std::vector<double> ContactShares(const WallPoints& walls, const std::vector<WallLine>& ring, bool ceiling_only) {
  std::vector<double> shares;
  for (const WallLine& l : ring) {
    double contact = 0, all = 0;
    for (int k : l.members) {
      const WallPoint& p = walls.points[k];
      all += p.w;
      if (p.contact && (!ceiling_only || p.z > kCeilingContactMinZ)) contact += p.w;
    }
    shares.push_back(all > 0 ? contact / all : 0.0);
  }
  return shares;
}

// Variance of f(lines) from a room-wide scale error s of the contacts, 1σ
// `sigma`: line l moves away from `viewpoint` by shares[l] · s · its
// distance from it (its centroid scaled about the viewpoint), all lines at
// once, by central differences.
double ScaleModeVariance(const std::vector<WallLine>& lines, const std::vector<double>& shares, const Vec2& viewpoint,
                         double sigma, const std::function<double(const std::vector<WallLine>&)>& f) {
  if (sigma <= 0) return 0;
  auto scaled = [&](double s) {
    std::vector<WallLine> moved = lines;
    for (std::size_t l = 0; l < moved.size(); ++l)
      moved[l].c = viewpoint + (1 + shares[l] * s) * (moved[l].c - viewpoint);
    return moved;
  };
  const double h = 1e-3 * sigma;
  const double d = (f(scaled(h)) - f(scaled(-h))) / (2 * h);
  return d * d * sigma * sigma;
}

}  // namespace

RingSigmas PropagateRingSigmas(const WallPoints& walls, const std::vector<WallLine>& ring, const PlanOptions& o) {
  const std::vector<WallLine> lines = LinesWithSharedVariance(walls, ring, o);
  const int n = static_cast<int>(lines.size());
  const std::vector<double> shares = ContactShares(walls, ring, false),
                            ceiling_shares = ContactShares(walls, ring, true);
  const double scale_sigma = o.viewpoint_m ? *o.ForLabels(false).contact_scale_sigma : 0.0;
  const double ceiling_sigma = o.viewpoint_m ? o.ceiling_scale_sigma.value_or(0.0) : 0.0;
  const Vec2 viewpoint = o.viewpoint_m ? Vec2(o.viewpoint_m->head<2>()) : Vec2::Zero();
  // The two room-wide modes: the contacts' scale, and the ceiling height's.
  auto modes = [&](const std::function<double(const std::vector<WallLine>&)>& f) {
    return ScaleModeVariance(lines, shares, viewpoint, scale_sigma, f) +
           ScaleModeVariance(lines, ceiling_shares, viewpoint, ceiling_sigma, f);
  };
  RingSigmas out;
  for (int i = 0; i < n; ++i) {
    auto length = [i, n](const std::vector<WallLine>& L) {
      std::vector<Vec2> c = RingCorners(L);
      return (c[(i + 1) % n] - c[i]).norm();
    };
    out.wall_length_m.push_back(
        std::sqrt(PropagatedVariance(lines, length, {(i + n - 1) % n, i, (i + 1) % n}) + modes(length)));
  }
  std::vector<int> all_lines(n);
  std::iota(all_lines.begin(), all_lines.end(), 0);
  const auto area = [](const std::vector<WallLine>& L) { return std::abs(PolygonArea(RingCorners(L))); };
  out.area_m2 = std::sqrt(PropagatedVariance(lines, area, all_lines) + modes(area));
  return out;
}

}  // namespace asbuilt
