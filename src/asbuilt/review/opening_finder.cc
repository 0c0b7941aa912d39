#include "asbuilt/review/opening_finder.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "asbuilt/review/view_geometry.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/stats.h"

namespace asbuilt {
namespace {

constexpr int kSamplesPerLine = 32;
constexpr double kCornerM = 0.03;
constexpr double kClickM = 0.12;

// Bilinear sample of a CV_32F image; a panorama wraps around in u.
double Sample(const cv::Mat& m, const Vec2& p, bool wrap) {
  double x = p.x(), y = std::clamp(p.y(), 0.0, m.rows - 1.0);
  if (wrap) {
    x = std::fmod(x, static_cast<double>(m.cols));
    if (x < 0) x += m.cols;
    if (x >= m.cols) x = 0.0;  // -1e-17 + cols rounds to cols.
  } else {
    x = std::clamp(x, 0.0, m.cols - 1.0);
  }
  const int x0 = static_cast<int>(std::floor(x)), y0 = std::min(static_cast<int>(std::floor(y)), m.rows - 1);
  const int x1 = wrap ? (x0 + 1) % m.cols : std::min(x0 + 1, m.cols - 1), y1 = std::min(y0 + 1, m.rows - 1);
  const double fx = x - x0, fy = y - y0;
  const float* r0 = m.ptr<float>(y0);
  const float* r1 = m.ptr<float>(y1);
  return (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x1]) + fy * ((1 - fx) * r1[x0] + fx * r1[x1]);
}

// How strongly the photo changes across the 3D segment a→b: at points along
// it, the gradient across the segment's image (the image direction of
// `across`), its `quantile`; 0 when most of the segment is out of view.
double LineStrength(const ImageGradients& g, const ReviewImage& image, const Vec3& a, const Vec3& b, const Vec3& across,
                    double quantile) {
  const bool panorama = image.frame < 0;
  std::vector<double> s;
  s.reserve(kSamplesPerLine);
  for (int k = 0; k < kSamplesPerLine; ++k) {
    const Vec3 p = a + (b - a) * ((k + 0.5) / kSamplesPerLine);
    const std::optional<Vec2> u = PixelOfPoint(image, p), v = PixelOfPoint(image, p + 0.01 * across);
    if (!u || !v || !PixelInside(image, *u)) continue;
    Vec2 t = *v - *u;
    if (panorama) t.x() = std::remainder(t.x(), static_cast<double>(image.width_px));
    if (t.norm() < 1e-9) continue;
    t.normalize();
    s.push_back(std::abs(Sample(g.gx, *u, panorama) * t.x() + Sample(g.gy, *u, panorama) * t.y()));
  }
  if (static_cast<int>(s.size()) < kSamplesPerLine / 2) return 0.0;
  const auto k = s.begin() + static_cast<std::ptrdiff_t>(quantile * (s.size() - 1));
  std::nth_element(s.begin(), k, s.end());
  return *k;
}

// A wall of the plan as a line on the floor.
struct WallLine {
  Vec2 a, d;  // Start and unit direction.
  double length = 0.0;
  Vec3 At(double s, double z) const { return Vec3(a.x() + s * d.x(), a.y() + s * d.y(), z); }
  Vec3 Dir() const { return Vec3(d.x(), d.y(), 0.0); }
};

struct Jambs {
  double s0 = 0.0, s1 = 0.0;
  bool found = false;
};

// The two vertical lines from z0 to z1, one either side of s_click (and
// not under it), a width in [min_w, max_w] apart: on each side the nearest
// that stands out from the median line along the wall and is nearly as
// strong as that side's strongest.
Jambs FindJambs(const ImageGradients& g, const ReviewImage& image, const WallLine& w, double s_click, double z0,
                double z1, double min_w, double max_w, const OpeningSearchOptions& o) {
  // Not the wall's own ends: a room's corner is an edge too.
  const double lo = std::max(kCornerM, s_click - o.reach_m), hi = std::min(w.length - kCornerM, s_click + o.reach_m);
  std::vector<double> s, e;
  for (double x = lo; x <= hi + 1e-9; x += o.step_m) {
    s.push_back(x);
    e.push_back(LineStrength(g, image, w.At(x, z0), w.At(x, z1), w.Dir(), o.quantile));
  }
  const double floor = o.min_contrast * UpperMedian(e);
  // Each side's strongest line; a jamb is the line nearest the click at
  // least `o.jamb_share` as strong (an edge beyond it, a cupboard's or a
  // corner's, is outside the opening).
  double left_max = 0.0, right_max = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] <= s_click - kClickM) left_max = std::max(left_max, e[i]);
    if (s[i] >= s_click + kClickM) right_max = std::max(right_max, e[i]);
  }
  auto strong = [&](std::size_t i, double side_max) { return e[i] > floor && e[i] >= o.jamb_share * side_max; };
  Jambs out;
  double best = -1.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    // A person clicks inside the opening, not on its jamb: an edge under
    // the click is a mullion's or a panel's.
    if (s[i] > s_click - kClickM || !strong(i, left_max)) continue;
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      const double width = s[j] - s[i];
      if (width > max_w) break;
      if (s[j] < s_click + kClickM || width < min_w || !strong(j, right_max)) continue;
      // The nearest pair of strong lines: the narrowest.
      if (best < 0 || width < best) best = width, out = {s[i], s[j], true};
    }
  }
  return out;
}

// The strongest horizontal line between s0 and s1 at a height in [z_lo, z_hi];
// nullopt when none stands out from the median there.
std::optional<double> FindLevel(const ImageGradients& g, const ReviewImage& image, const WallLine& w, double s0,
                                double s1, double z_lo, double z_hi, const OpeningSearchOptions& o) {
  if (z_hi < z_lo) return std::nullopt;
  const double inset = std::min(0.05, 0.25 * (s1 - s0));
  std::vector<double> z, e;
  for (double x = z_lo; x <= z_hi + 1e-9; x += o.step_m) {
    z.push_back(x);
    e.push_back(LineStrength(g, image, w.At(s0 + inset, x), w.At(s1 - inset, x), Vec3::UnitZ(), o.quantile));
  }
  const auto best = std::max_element(e.begin(), e.end());
  if (best == e.end() || *best <= o.min_contrast * UpperMedian(e)) return std::nullopt;
  return z[static_cast<std::size_t>(best - e.begin())];
}

// How far up and down from z_click both jambs run on as edges: short
// vertical lines at s0 and s1 at least half as strong as the jambs' own
// median in [z0, z1], gaps up to kGapM bridged. Returns the lowest and
// highest such height.
std::pair<double, double> JambExtent(const ImageGradients& g, const ReviewImage& image, const WallLine& w,
                                     const Jambs& j, double z_click, double z0, double z1, double top,
                                     const OpeningSearchOptions& o) {
  constexpr double kStepM = 0.02, kHalfM = 0.03, kGapM = 0.20;
  auto strength = [&](double z) {
    double e = INFINITY;
    for (double s : {j.s0, j.s1}) {
      e = std::min(e, LineStrength(g, image, w.At(s, z - kHalfM), w.At(s, z + kHalfM), w.Dir(), 0.5));
    }
    return e;
  };
  std::vector<double> band;
  for (double z = z0; z <= z1 + 1e-9; z += kStepM) band.push_back(strength(z));
  const double tau = 0.5 * UpperMedian(band);
  auto walk = [&](double dir, double limit) {
    double last = z_click, z = z_click;
    while ((dir < 0 ? z - kStepM >= limit : z + kStepM <= limit) && std::abs(z - last) <= kGapM + 1e-9) {
      z += dir * kStepM;
      if (strength(z) >= tau) last = z;
    }
    return last;
  };
  return {walk(-1.0, 0.0), walk(1.0, top)};
}

}  // namespace

void OpeningSearchOptions::Check() const {
  if (!(min_door_m > 0 && max_door_m > min_door_m && min_window_m > 0 && max_window_m > min_window_m)) {
    throw InvalidArgument("opening search: width limits must be positive and increasing");
  }
  if (!(reach_m > 0 && step_m > 0 && step_m < reach_m && quantile >= 0 && quantile <= 1 && min_contrast >= 1 &&
        jamb_share > 0 && jamb_share <= 1 && window_band_m > 0 && door_head_max_m > door_head_min_m)) {
    throw InvalidArgument(
        "opening search: reach_m, step_m, quantile, min_contrast, jamb_share, window_band_m or the door head range "
        "out of range");
  }
}

ImageGradients GradientsOf(const cv::Mat& grey) {
  CV_Assert(grey.type() == CV_8UC1);
  ImageGradients g{cv::Mat(grey.size(), CV_32F, cv::Scalar(0)), cv::Mat(grey.size(), CV_32F, cv::Scalar(0))};
  for (int y = 0; y < grey.rows; ++y) {
    const uchar* up = grey.ptr<uchar>(std::max(0, y - 1));
    const uchar* row = grey.ptr<uchar>(y);
    const uchar* down = grey.ptr<uchar>(std::min(grey.rows - 1, y + 1));
    float* gx = g.gx.ptr<float>(y);
    float* gy = g.gy.ptr<float>(y);
    for (int x = 0; x < grey.cols; ++x) {
      const int l = std::max(0, x - 1), r = std::min(grey.cols - 1, x + 1);
      gx[x] = 0.5f * (static_cast<float>(row[r]) - static_cast<float>(row[l]));
      gy[x] = 0.5f * (static_cast<float>(down[x]) - static_cast<float>(up[x]));
    }
  }
  return g;
}

std::optional<FoundOpening> FindOpeningAt(const ImageGradients& gradients, const ReviewImage& image, const Plan& plan,
                                          const Vec2& pixel, OpeningKind kind, double ceiling_m, std::string* why,
                                          const OpeningSearchOptions& o) {
  o.Check();
  auto fail = [&](std::string reason) -> std::optional<FoundOpening> {
    if (why) *why = std::move(reason);
    return std::nullopt;
  };
  const std::optional<WallHit> hit = WallOfPixel(image, plan, pixel);
  if (!hit) return fail("the click does not look at a wall of the plan");
  const PlanWall& pw = plan.walls[static_cast<std::size_t>(hit->wall)];
  WallLine w{pw.start, (pw.end - pw.start).normalized(), (pw.end - pw.start).norm()};
  const double s_click = (hit->xy_m - w.a).dot(w.d);
  const double z_click = HeightAtDistance(image, pixel, hit->distance_m);
  const double top = ceiling_m - 0.02;
  FoundOpening out{.wall = hit->wall};
  Jambs jambs;
  if (kind == OpeningKind::kDoor) {
    jambs = FindJambs(gradients, image, w, s_click, 0.1, std::min(1.9, top - 0.1), o.min_door_m, o.max_door_m, o);
    if (!jambs.found) return fail("no door jambs stand out on that wall either side of the click");
    out.bottom_m = 0.0;
    out.top_m =
        FindLevel(gradients, image, w, jambs.s0, jambs.s1, o.door_head_min_m, std::min(o.door_head_max_m, top), o)
            .value_or(std::min(2.0, top));
  } else {
    if (!(z_click > 0.05 && z_click < top)) return fail("a window is clicked between the floor and the ceiling");
    const double z0 = std::max(0.05, z_click - o.window_band_m), z1 = std::min(top - 0.02, z_click + o.window_band_m);
    jambs = FindJambs(gradients, image, w, s_click, z0, z1, o.min_window_m, o.max_window_m, o);
    if (!jambs.found) return fail("no window jambs stand out on that wall either side of the click");
    // The sill and head: the strongest level lines near where the jambs end
    // (a desk's edge or a reflection in the glass crosses no jamb).
    const auto [low, high] = JambExtent(gradients, image, w, jambs, z_click, z0, z1, top, o);
    out.top_m =
        FindLevel(gradients, image, w, jambs.s0, jambs.s1, std::max(z_click, high - 0.1), std::min(top, high + 0.1), o)
            .value_or(high);
    out.bottom_m =
        FindLevel(gradients, image, w, jambs.s0, jambs.s1, std::max(0.0, low - 0.1), std::min(z_click, low + 0.1), o)
            .value_or(low);
    // The jambs again over the window's own height.
    if (out.top_m - out.bottom_m > 0.2) {
      const Jambs again = FindJambs(gradients, image, w, s_click, out.bottom_m + 0.05, out.top_m - 0.05, o.min_window_m,
                                    o.max_window_m, o);
      if (again.found) jambs = again;
    }
  }
  out.start_m = w.a + jambs.s0 * w.d;
  out.end_m = w.a + jambs.s1 * w.d;
  return out;
}

}  // namespace asbuilt
