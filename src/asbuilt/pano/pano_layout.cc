#include "asbuilt/pano/pano_layout.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "asbuilt/formats/points_file.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

constexpr std::uint8_t kBackground = static_cast<std::uint8_t>(LabelClass::kBackground);
constexpr std::uint8_t kWall = static_cast<std::uint8_t>(LabelClass::kWall);
constexpr std::uint8_t kDoor = static_cast<std::uint8_t>(LabelClass::kDoor);
constexpr std::uint8_t kWindow = static_cast<std::uint8_t>(LabelClass::kWindow);

// Row (fractional, OpenCV centres) of an elevation in a panorama `rows` high.
double RowOfElevation(double elevation_rad, int rows) { return rows * (0.5 - elevation_rad / kPi) - 0.5; }

// Elevations, radians, of a wall's floor edge and ceiling edge seen from a
// camera camera_m above the floor, the wall distance_m away.
double FloorEdgeElevation(double camera_m, double distance_m) { return -std::atan2(camera_m, distance_m); }
double CeilingEdgeElevation(double camera_m, double ceiling_m, double distance_m) {
  return std::atan2(ceiling_m - camera_m, distance_m);
}

// The row nearest an elevation, inside the panorama.
int EdgeRow(double elevation_rad, int rows) {
  return std::clamp(static_cast<int>(std::lround(RowOfElevation(elevation_rad, rows))), 0, rows - 1);
}

// Column of a direction's yaw in a panorama `columns` wide, rounded, wrapped.
int ColumnOf(const Vec3& direction, int columns) {
  const Vec2 pixel = EquirectPixelFromDirection(direction, columns, columns / 2);
  int u = static_cast<int>(std::lround(pixel.x()));
  u %= columns;
  return u < 0 ? u + columns : u;
}

// Strength of horizontal steps in the image: where the region above a row
// differs from the region below it (a wall meeting the floor or the
// ceiling), not where a texture (carpet, wood grain) varies row to row. Per
// Lab channel, the difference of the means of `half` rows above and below,
// smoothed along the row; the larger of lightness and colour. Returned as a
// saturating 0..1 response at the image's own scale, so a faint wall–ceiling
// crease still counts beside a picture frame's hard edge.
cv::Mat HorizontalSteps(const cv::Mat& bgr, double max_elevation_deg) {
  constexpr int kHalf = 3;  // Rows each side of the step.
  cv::Mat lab;
  cv::cvtColor(bgr, lab, cv::COLOR_BGR2Lab);
  std::vector<cv::Mat> channels;
  cv::split(lab, channels);
  cv::Mat strength(bgr.size(), CV_32F, cv::Scalar(0));
  const float channel_weight[3] = {1.0f, 1.5f, 1.5f};
  for (int c = 0; c < 3; ++c) {
    cv::Mat f, mean;
    channels[c].convertTo(f, CV_32F);
    // Mean of kHalf rows and 5 columns around each pixel.
    cv::blur(f, mean, cv::Size(5, kHalf), cv::Point(-1, -1), cv::BORDER_REPLICATE);
    for (int y = 0; y < f.rows; ++y) {
      const int above = std::max(0, y - (kHalf + 1) / 2), below = std::min(f.rows - 1, y + (kHalf + 1) / 2);
      const float* a = mean.ptr<float>(above);
      const float* b = mean.ptr<float>(below);
      float* s = strength.ptr<float>(y);
      for (int x = 0; x < f.cols; ++x) s[x] = std::max(s[x], channel_weight[c] * std::abs(a[x] - b[x]));
    }
  }
  // Scale: the 90th percentile of the steps (most of a room is flat).
  std::vector<float> values(strength.begin<float>(), strength.end<float>());
  const std::size_t k = values.size() * 9 / 10;
  std::nth_element(values.begin(), values.begin() + k, values.end());
  const double scale = values[k] + 1e-3;
  cv::Mat response = strength / (strength + scale);
  cv::Mat widened;
  cv::dilate(response, widened, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(1, 3)));
  // Nothing near the poles: the camera's own mount and the stitching's
  // smear at the nadir, a ceiling light's rim at the zenith.
  const int rows = widened.rows;
  for (int y = 0; y < rows; ++y) {
    const double elevation = kPi * (0.5 - (y + 0.5) / rows);
    if (std::abs(elevation) > DegToRad(max_elevation_deg)) widened.row(y).setTo(0);
  }
  return widened;
}

// Per column, the cumulative sum down the rows of each row's label vote:
// +1 wall/door/window, −1 background, 0 unknown. cumulative(y, x) is the sum
// over rows < y (rows + 1 entries).
cv::Mat CumulativeLabelVotes(const cv::Mat& labels, int rows, int columns, bool lower_only) {
  cv::Mat cumulative(rows + 1, columns, CV_32F, cv::Scalar(0));
  if (labels.empty()) return cumulative;
  cv::Mat resized;
  cv::resize(labels, resized, cv::Size(columns, rows), 0, 0, cv::INTER_NEAREST);
  for (int y = 0; y < rows; ++y) {
    const std::uint8_t* l = resized.ptr<std::uint8_t>(y);
    const float* above = cumulative.ptr<float>(y);
    float* here = cumulative.ptr<float>(y + 1);
    if (lower_only && y < rows / 2) {
      for (int x = 0; x < columns; ++x) here[x] = above[x];
      continue;
    }
    for (int x = 0; x < columns; ++x) {
      const float vote = l[x] == kBackground                                   ? -1.0f
                         : (l[x] == kWall || l[x] == kDoor || l[x] == kWindow) ? 1.0f
                                                                               : 0.0f;
      here[x] = above[x] + vote;
    }
  }
  return cumulative;
}

// Each column's cost of each distance bin for one ceiling height: minus the
// edge strengths at the bin's floor and ceiling rows and the labels'
// agreement with the band between (columns × bins, row-major).
std::vector<float> ColumnCosts(const cv::Mat& edges, const cv::Mat& votes, const std::vector<double>& distances_m,
                               double camera_height_m, double ceiling_height_m, const PanoLayoutOptions& o) {
  const int rows = edges.rows, columns = edges.cols, bins = static_cast<int>(distances_m.size());
  std::vector<int> floor_row(bins), ceiling_row(bins);
  for (int k = 0; k < bins; ++k) {
    floor_row[k] = EdgeRow(FloorEdgeElevation(camera_height_m, distances_m[k]), rows);
    ceiling_row[k] = EdgeRow(CeilingEdgeElevation(camera_height_m, ceiling_height_m, distances_m[k]), rows);
  }
  std::vector<float> costs(static_cast<std::size_t>(columns) * bins);
  for (int x = 0; x < columns; ++x) {
    const float total = votes.at<float>(rows, x);
    float* c = &costs[static_cast<std::size_t>(x) * bins];
    for (int k = 0; k < bins; ++k) {
      const int yc = ceiling_row[k], yf = floor_row[k];
      const float inside = votes.at<float>(yf + 1, x) - votes.at<float>(yc, x);
      const float agreement = inside - (total - inside);
      c[k] = -static_cast<float>(o.floor_edge_weight * edges.at<float>(yf, x) +
                                 o.ceiling_edge_weight * edges.at<float>(yc, x) + o.label_weight_per_row * agreement);
    }
  }
  return costs;
}

// A best path round the panorama: per column its distance bin.
struct PathFit {
  std::vector<int> bins;    // Per column: the distance bin.
  std::vector<int> states;  // Manhattan: per column normal · bins + perpendicular distance bin.
  double score = -std::numeric_limits<double>::infinity();
};

// The states of a dynamic programme's best path, step by step, from its
// last costs and each step's back-pointers (steps × states); `score` gets
// minus the path's cost.
std::vector<int> Backtrack(const std::vector<float>& last_cost, const std::vector<std::int16_t>& from, double* score) {
  const int states = static_cast<int>(last_cost.size());
  const int steps = static_cast<int>(from.size() / last_cost.size());
  int state = static_cast<int>(std::min_element(last_cost.begin(), last_cost.end()) - last_cost.begin());
  *score = -last_cost[state];
  std::vector<int> path(steps);
  for (int step = steps - 1; step >= 0; --step) {
    path[step] = state;
    if (step > 0) state = from[static_cast<std::size_t>(step) * states + state];
  }
  return path;
}

// A path run twice round the panorama, per column once: its middle turn
// (columns/2 … columns/2 + columns − 1), far from both ends.
std::vector<int> MiddleTurn(const std::vector<int>& path, int columns) {
  std::vector<int> out(columns, 0);
  for (int step = columns / 2; step < columns / 2 + columns; ++step) out[step % columns] = path[step];
  return out;
}

// Free dynamic programme over the columns: any distance per column, paying
// for changes of bin. Run twice round the panorama and keep the middle turn,
// so the seam has no start of its own.
PathFit FitFreePath(const std::vector<float>& costs, int columns, int bins, const PanoLayoutOptions& o) {
  const int steps = 2 * columns;
  std::vector<float> cost(bins), next(bins);
  std::vector<std::int16_t> from(static_cast<std::size_t>(steps) * bins);
  std::copy_n(costs.begin(), bins, cost.begin());
  const float smooth = static_cast<float>(o.smooth_cost_per_bin), jump = static_cast<float>(o.jump_cost);
  for (int step = 1; step < steps; ++step) {
    const float* unary = &costs[static_cast<std::size_t>(step % columns) * bins];
    const int best = static_cast<int>(std::min_element(cost.begin(), cost.end()) - cost.begin());
    for (int k = 0; k < bins; ++k) {
      float b = cost[best] + jump;
      int arg = best;
      const int lo = std::max(0, k - o.smooth_bins), hi = std::min(bins - 1, k + o.smooth_bins);
      for (int j = lo; j <= hi; ++j) {
        const float c = cost[j] + smooth * static_cast<float>(std::abs(j - k));
        if (c < b) b = c, arg = j;
      }
      next[k] = b + unary[k];
      from[static_cast<std::size_t>(step) * bins + k] = static_cast<std::int16_t>(arg);
    }
    std::swap(cost, next);
  }
  PathFit fit;
  fit.bins = MiddleTurn(Backtrack(cost, from, &fit.score), columns);
  return fit;
}

// Horizontal unit direction of each working column.
std::vector<Vec2> ColumnDirections(int columns) {
  std::vector<Vec2> out;
  for (int x = 0; x < columns; ++x) {
    const Vec3 d = DirectionFromEquirectPixel(Vec2(x, columns / 4 - 0.5), columns, columns / 2);
    out.push_back(d.head<2>().normalized());
  }
  return out;
}

// The walls' direction (radians in [0, π/2)) from a free path: the
// length-weighted histogram, modulo 90°, of the directions between points a
// few columns apart along it (not across jumps), smoothed, at its peak.
double DominantWallDirection(const std::vector<int>& bins, const std::vector<double>& distances_m,
                             const std::vector<Vec2>& directions) {
  constexpr int kSpan = 10, kBins = 180;
  const int columns = static_cast<int>(bins.size());
  std::vector<double> histogram(kBins, 0.0);
  for (int x = 0; x < columns; ++x) {
    const int y = (x + kSpan) % columns;
    if (std::abs(bins[x] - bins[y]) > 2 * kSpan) continue;
    const Vec2 p = distances_m[bins[x]] * directions[x], q = distances_m[bins[y]] * directions[y];
    const Vec2 v = q - p;
    double a = std::atan2(v.y(), v.x());
    a = std::fmod(a, kPi / 2);
    if (a < 0) a += kPi / 2;
    histogram[static_cast<int>(a / (kPi / 2) * kBins) % kBins] += v.norm();
  }
  int peak = 0;
  double peak_value = -1.0;
  for (int b = 0; b < kBins; ++b) {
    double v = 0.0;
    for (int t = -3; t <= 3; ++t) v += histogram[(b + t + kBins) % kBins] * (4 - std::abs(t));
    if (v > peak_value) peak_value = v, peak = b;
  }
  return (peak + 0.5) * (kPi / 2) / kBins;
}

// Manhattan dynamic programme: each column sees a wall of one of four
// normals (the walls' direction and its right angles, each side) at a
// perpendicular distance D; a column's distance is D / cos(angle between its
// ray and the normal). Along a wall the state stays (free); at a room corner
// the next wall continues where this one ends (corner_cost); any other change
// is one wall before another (jump_cost). Distances share the free path's
// log bins, so a state's column distance is bin k + shift(normal, column).
PathFit FitManhattanPath(const std::vector<float>& costs, int columns, int bins, double wall_direction_rad,
                         const std::vector<Vec2>& directions, double log_step, const PanoLayoutOptions& o) {
  constexpr int kNormals = 4;
  constexpr float kInvalid = 1e6f;
  const int states = kNormals * bins;
  // shift(n, x) = −ln cos / log_step, or −1 where the ray grazes the wall.
  std::vector<int> shift(static_cast<std::size_t>(kNormals) * columns);
  for (int n = 0; n < kNormals; ++n) {
    const double a = wall_direction_rad + kPi / 2 + n * kPi / 2;
    const Vec2 normal(std::cos(a), std::sin(a));
    for (int x = 0; x < columns; ++x) {
      const double c = directions[x].dot(normal);
      shift[n * columns + x] = c < 0.08 ? -1 : static_cast<int>(std::lround(-std::log(c) / log_step));
    }
  }
  auto unary = [&](int n, int k, int x) {
    const int s = shift[n * columns + x];
    if (s < 0 || k + s >= bins) return kInvalid;
    return costs[static_cast<std::size_t>(x) * bins + k + s];
  };
  const int steps = 2 * columns;
  std::vector<float> cost(states), next(states);
  std::vector<std::int16_t> from(static_cast<std::size_t>(steps) * states);
  for (int n = 0; n < kNormals; ++n) {
    for (int k = 0; k < bins; ++k) cost[n * bins + k] = unary(n, k, 0);
  }
  const float corner = static_cast<float>(o.corner_cost), jump = static_cast<float>(o.jump_cost);
  for (int step = 1; step < steps; ++step) {
    const int x = step % columns;
    const int best = static_cast<int>(std::min_element(cost.begin(), cost.end()) - cost.begin());
    for (int n = 0; n < kNormals; ++n) {
      const int sn = shift[n * columns + x];
      for (int k = 0; k < bins; ++k) {
        const int here = n * bins + k;
        // Stay on the wall.
        float b = cost[here];
        int arg = here;
        if (cost[best] + jump < b) b = cost[best] + jump, arg = best;
        // A corner: the previous wall ends where this one starts.
        if (sn >= 0) {
          for (int m = 0; m < kNormals; ++m) {
            const int sm = shift[m * columns + x];
            if (m == n || sm < 0) continue;
            const int centre = k + sn - sm;
            for (int j = std::max(0, centre - 1); j <= std::min(bins - 1, centre + 1); ++j) {
              const float c = cost[m * bins + j] + corner;
              if (c < b) b = c, arg = m * bins + j;
            }
          }
        }
        next[here] = b + unary(n, k, x);
        from[static_cast<std::size_t>(step) * states + here] = static_cast<std::int16_t>(arg);
      }
    }
    std::swap(cost, next);
  }
  PathFit fit;
  fit.states = MiddleTurn(Backtrack(cost, from, &fit.score), columns);
  fit.bins = fit.states;
  for (int x = 0; x < columns; ++x) {
    const int n = fit.states[x] / bins, k = fit.states[x] % bins;
    fit.bins[x] = std::clamp(k + std::max(0, shift[n * columns + x]), 0, bins - 1);
  }
  return fit;
}

// Whether each column's wall shows in the image: the median over the
// columns around it of the edge strengths at its floor and ceiling rows.
std::vector<bool> SupportedColumns(const cv::Mat& edges, const PanoLayout& layout, const PanoLayoutOptions& o) {
  const int rows = edges.rows, columns = edges.cols;
  std::vector<float> support(columns);
  for (int x = 0; x < columns; ++x) {
    const double d = layout.distance_m[x];
    const int yf = EdgeRow(FloorEdgeElevation(layout.camera_height_m, d), rows);
    const int yc = EdgeRow(CeilingEdgeElevation(layout.camera_height_m, layout.ceiling_height_m, d), rows);
    support[x] = edges.at<float>(yf, x) + edges.at<float>(yc, x);
  }
  std::vector<bool> out(columns);
  std::vector<float> window;
  for (int x = 0; x < columns; ++x) {
    window.clear();
    for (int t = -o.support_half_width; t <= o.support_half_width; ++t) {
      window.push_back(support[(x + t + columns) % columns]);
    }
    std::nth_element(window.begin(), window.begin() + window.size() / 2, window.end());
    out[x] = window[window.size() / 2] >= o.min_column_support;
  }
  return out;
}

// A wall of a Manhattan path: its line {p : p·normal = offset_m} and the
// columns it holds, first … last (wrapping).
struct PathWall {
  Vec2 normal;
  double offset_m = 0.0;
  int state = 0;
  int first = 0, last = 0, columns = 0, supported = 0;
};

// The room polygon (pano frame, camera at the origin, vertices in column
// order) a Manhattan path describes, the way layout networks close theirs:
// its walls, those held by at least min_wall_columns columns mostly
// supported; neighbouring walls at right angles meet at their lines'
// crossing when it lies between them, else (and for parallel walls) joined
// along the ray between their runs (one wall stands before the other).
// Empty when fewer than three walls or no right angle remain.
std::vector<Vec2> ManhattanPolygon(const std::vector<int>& states, const std::vector<bool>& supported,
                                   const std::vector<double>& distances_m, double wall_direction_rad,
                                   const std::vector<Vec2>& directions, int min_wall_columns) {
  const int columns = static_cast<int>(states.size()), bins = static_cast<int>(distances_m.size());
  // Start at a change of state, so no run wraps past the first column.
  int start = 0;
  while (start < columns && states[start] == states[(start + columns - 1) % columns]) ++start;
  if (start == columns) return {};
  std::vector<PathWall> walls;
  for (int i = 0; i < columns; ++i) {
    const int x = (start + i) % columns;
    if (walls.empty() || walls.back().state != states[x]) {
      const int n = states[x] / bins;
      const double a = wall_direction_rad + kPi / 2 + n * kPi / 2;
      walls.push_back({.normal = Vec2(std::cos(a), std::sin(a)),
                       .offset_m = distances_m[states[x] % bins],
                       .state = states[x],
                       .first = x});
    }
    PathWall& w = walls.back();
    w.last = x;
    ++w.columns;
    w.supported += supported[x] ? 1 : 0;
  }
  std::vector<PathWall> kept;
  for (const PathWall& w : walls) {
    if (w.columns < min_wall_columns || 2 * w.supported < w.columns) continue;
    if (!kept.empty() && kept.back().state == w.state) {
      kept.back().last = w.last;
      kept.back().columns += w.columns;
      continue;
    }
    kept.push_back(w);
  }
  if (kept.size() > 1 && kept.front().state == kept.back().state) {
    kept.front().first = kept.back().first;
    kept.pop_back();
  }
  if (kept.size() < 3) return {};
  // Bearing order: a point's column position, unwrapped after `from`.
  auto column_of = [&](const Vec2& p) {
    return EquirectPixelFromDirection(Vec3(p.x(), p.y(), 0.0), columns, columns / 2).x();
  };
  auto ahead = [&](double column, int from) {  // Columns from `from` to `column`, in [0, columns).
    double d = column - from;
    while (d < 0) d += columns;
    while (d >= columns) d -= columns;
    return d;
  };
  std::vector<Vec2> polygon;
  bool right_angle = false;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const PathWall& a = kept[i];
    const PathWall& b = kept[(i + 1) % kept.size()];
    const double cross = a.normal.x() * b.normal.y() - a.normal.y() * b.normal.x();
    if (std::abs(cross) > 0.5) {
      // Crossing of the two lines: normal_a·p = D_a, normal_b·p = D_b.
      const Vec2 p((a.offset_m * b.normal.y() - b.offset_m * a.normal.y()) / cross,
                   (b.offset_m * a.normal.x() - a.offset_m * b.normal.x()) / cross);
      const double gap = ahead(b.first, a.last);
      const double at = ahead(column_of(p), a.last);
      if (at <= gap + 2 || at >= columns - 2) {
        polygon.push_back(p);
        right_angle = true;
        continue;
      }
    }
    // Joined along the ray midway between the two runs.
    const double mid = a.last + 0.5 * ahead(b.first, a.last);
    const int x = static_cast<int>(std::lround(mid)) % columns;
    const Vec2 r = directions[x];
    const double ca = r.dot(a.normal), cb = r.dot(b.normal);
    if (ca < 0.05 || cb < 0.05) return {};
    polygon.push_back(r * (a.offset_m / ca));
    polygon.push_back(r * (b.offset_m / cb));
  }
  if (!right_angle) return {};
  return polygon;
}

// Distance along a horizontal unit direction from the origin to a polygon
// around it (the nearest crossing ahead; +inf when none).
double RayPolygonDistance(const Vec2& direction, const std::vector<Vec2>& polygon) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2& p = polygon[i];
    const Vec2& q = polygon[(i + 1) % polygon.size()];
    const Vec2 e = q - p;
    const double det = direction.x() * (-e.y()) - direction.y() * (-e.x());
    if (std::abs(det) < 1e-12) continue;
    // Solve t·direction = p + s·e.
    const double t = (p.x() * (-e.y()) - p.y() * (-e.x())) / det;
    const double u = (direction.x() * p.y() - direction.y() * p.x()) / det;
    if (t > 1e-9 && u >= -1e-9 && u <= 1 + 1e-9) best = std::min(best, t);
  }
  return best;
}

}  // namespace

// Every single-option bound is stated once, in PanoLayoutOptionFields();
// here only the rules that involve several options, or what a bound cannot say.
void PanoLayoutOptions::Check() const {
  PanoLayoutOptionFields().CheckValues(*this, "PanoLayoutOptions");
  CheckArgument(width_px % 2 == 0, fmt::format("PanoLayoutOptions.width_px = {}, must be even", width_px));
  CheckArgument(max_distance_m > min_distance_m,
                fmt::format("PanoLayoutOptions.max_distance_m = {}, must be > min_distance_m", max_distance_m));
  CheckArgument(max_ceiling_m >= min_ceiling_m,
                fmt::format("PanoLayoutOptions.max_ceiling_m = {}, must be >= min_ceiling_m", max_ceiling_m));
  CheckArgument(smooth_bins < distance_bins,
                fmt::format("PanoLayoutOptions.smooth_bins = {}, must be in 0..distance_bins − 1", smooth_bins));
}

const FieldList<PanoLayoutOptions>& PanoLayoutOptionFields() {
  using O = PanoLayoutOptions;
  static const FieldList<PanoLayoutOptions> kList = {
      Bind(&O::width_px, {.name = "width_px",
                          .description = "Working panorama width (height half of it), px.",
                          .minimum = 64.0,
                          .maximum = 8192.0}),
      Bind(&O::min_distance_m,
           {.name = "min_distance_m", .description = "Nearest wall distance tried, m.", .exclusive_minimum = 0.0}),
      Bind(&O::max_distance_m,
           {.name = "max_distance_m", .description = "Farthest wall distance tried, m.", .exclusive_minimum = 0.0}),
      Bind(&O::distance_bins, {.name = "distance_bins",
                               .description = "Log-spaced distance bins between them.",
                               .minimum = 8.0,
                               .maximum = 4096.0}),
      Bind(&O::min_ceiling_m,
           {.name = "min_ceiling_m", .description = "Lowest ceiling height tried, m.", .exclusive_minimum = 0.0}),
      Bind(&O::max_ceiling_m,
           {.name = "max_ceiling_m", .description = "Highest ceiling height tried, m.", .exclusive_minimum = 0.0}),
      Bind(&O::ceiling_step_m, {.name = "ceiling_step_m",
                                .description = "Step between ceiling heights tried, m.",
                                .exclusive_minimum = 0.0}),
      Bind(&O::floor_edge_weight, {.name = "floor_edge_weight",
                                   .description = "Weight of the image's edge at a column's floor edge.",
                                   .minimum = 0.0}),
      Bind(&O::ceiling_edge_weight, {.name = "ceiling_edge_weight",
                                     .description = "Weight of the image's edge at a column's ceiling edge.",
                                     .minimum = 0.0}),
      Bind(&O::label_weight_per_row,
           {.name = "label_weight_per_row",
            .description = "Weight per row of the labels agreeing with the wall band (0: labels unused).",
            .minimum = 0.0}),
      Bind(&O::max_edge_elevation_deg,
           {.name = "max_edge_elevation_deg",
            .description = "Edges count only this close to the horizon (not the camera mount or a ceiling light), deg.",
            .exclusive_minimum = 0.0,
            .maximum = 90.0}),
      Bind(&O::labels_below_horizon_only,
           {.name = "labels_below_horizon_only",
            .description = "Labels vote only below the horizon (a segmenter trained on renders takes a real "
                           "white ceiling for wall)."}),
      Bind(&O::smooth_cost_per_bin, {.name = "smooth_cost_per_bin",
                                     .description = "Cost per distance bin changed between columns.",
                                     .minimum = 0.0}),
      Bind(&O::manhattan,
           {.name = "manhattan",
            .description = "Walls meet at right angles (one direction and its right angles); off: any distances."}),
      Bind(&O::corner_cost, {.name = "corner_cost",
                             .description = "Manhattan: cost of a room corner (one wall meeting the next).",
                             .minimum = 0.0}),
      Bind(&O::min_column_support,
           {.name = "min_column_support",
            .description = "A column shows its wall when the median edge strength at its floor plus ceiling row, "
                           "over the columns around it, is at least this (0: every column).",
            .minimum = 0.0}),
      Bind(&O::support_half_width, {.name = "support_half_width",
                                    .description = "Columns each side in that median.",
                                    .minimum = 0.0,
                                    .maximum = 256.0}),
      Bind(&O::close_polygon,
           {.name = "close_polygon",
            .description = "Manhattan: redraw every column on the room polygon the path's walls close into."}),
      Bind(&O::min_wall_columns,
           {.name = "min_wall_columns",
            .description = "A wall of that polygon holds at least this many columns, mostly supported.",
            .minimum = 1.0}),
      Bind(&O::polygon_gaps_only,
           {.name = "polygon_gaps_only",
            .description = "With close_polygon: take the polygon's distance only where the photo shows no wall."}),
      Bind(&O::openings_from_labels,
           {.name = "openings_from_labels",
            .description = "Survey: keep the segmenter's doors and windows inside the layout's wall band."}),
      Bind(&O::smooth_bins,
           {.name = "smooth_bins", .description = "Largest smooth change between columns, bins.", .minimum = 0.0}),
      Bind(&O::jump_cost,
           {.name = "jump_cost", .description = "Cost of a larger change (one wall before another).", .minimum = 0.0}),
  };
  return kList;
}

int PanoLayout::ColumnAlong(const Vec3& direction) const {
  CheckArgument(!distance_m.empty(), "PanoLayout.distance_m is empty");
  return ColumnOf(direction, Columns());
}

double PanoLayout::DistanceAlong(const Vec3& direction) const { return distance_m[ColumnAlong(direction)]; }

bool PanoLayout::Supported(const Vec3& direction) const {
  return supported.empty() || supported[ColumnAlong(direction)];
}

double PanoLayout::FloorElevation(const Vec3& direction) const {
  return FloorEdgeElevation(camera_height_m, DistanceAlong(direction));
}

double PanoLayout::CeilingElevation(const Vec3& direction) const {
  return CeilingEdgeElevation(camera_height_m, ceiling_height_m, DistanceAlong(direction));
}

std::string PanoLayout::BriefReport() const {
  if (distance_m.empty()) return "layout: none";
  std::vector<double> sorted = distance_m;
  std::sort(sorted.begin(), sorted.end());
  const int shown = static_cast<int>(std::count(supported.begin(), supported.end(), true));
  return fmt::format("layout: ceiling {:.2f} m, walls {:.1f}–{:.1f} m away (median {:.1f} m), {}", ceiling_height_m,
                     sorted.front(), sorted.back(), sorted[sorted.size() / 2],
                     polygon_m.empty()
                         ? fmt::format("{} of {} columns shown", supported.empty() ? Columns() : shown, Columns())
                         : fmt::format("closed into a {}-corner polygon", polygon_m.size()));
}

PanoLayout EstimatePanoLayout(const cv::Mat& equirect_bgr, double camera_height_m, const cv::Mat& labels_equirect,
                              const PanoLayoutOptions& options) {
  options.Check();
  CheckArgument(!equirect_bgr.empty() && equirect_bgr.type() == CV_8UC3 &&
                    std::abs(equirect_bgr.cols - 2 * equirect_bgr.rows) <= 1,
                fmt::format("EstimatePanoLayout: the panorama must be 8-bit BGR and 2:1, got {}x{} type {}",
                            equirect_bgr.cols, equirect_bgr.rows, equirect_bgr.type()));
  CheckArgument(std::isfinite(camera_height_m) && camera_height_m > 0,
                fmt::format("EstimatePanoLayout: camera_height_m = {}, must be > 0", camera_height_m));
  CheckArgument(labels_equirect.empty() || labels_equirect.type() == CV_8UC1,
                "EstimatePanoLayout: labels_equirect must be CV_8UC1 label ids or empty");
  const int columns = options.width_px, rows = columns / 2;
  cv::Mat small;
  cv::resize(equirect_bgr, small, cv::Size(columns, rows), 0, 0, cv::INTER_AREA);
  const cv::Mat edges = HorizontalSteps(small, options.max_edge_elevation_deg);
  const cv::Mat votes = CumulativeLabelVotes(labels_equirect, rows, columns, options.labels_below_horizon_only);

  std::vector<double> distances_m(options.distance_bins);
  const double log_step = std::log(options.max_distance_m / options.min_distance_m) / (options.distance_bins - 1);
  for (int k = 0; k < options.distance_bins; ++k) distances_m[k] = options.min_distance_m * std::exp(k * log_step);
  const int bins = options.distance_bins;
  const std::vector<Vec2> directions = ColumnDirections(columns);
  auto fit = [&](double ceiling_m, std::optional<double> wall_direction_rad) {
    const std::vector<float> costs = ColumnCosts(edges, votes, distances_m, camera_height_m, ceiling_m, options);
    return wall_direction_rad
               ? FitManhattanPath(costs, columns, bins, *wall_direction_rad, directions, log_step, options)
               : FitFreePath(costs, columns, bins, options);
  };

  // The walls' direction from a free path at a typical ceiling height, then
  // the ceiling height under which the path fits best, then the direction
  // refined at that height.
  PanoLayout layout{.camera_height_m = camera_height_m};
  const double lowest = std::max(options.min_ceiling_m, camera_height_m + 0.2);
  CheckArgument(lowest <= options.max_ceiling_m,
                fmt::format("EstimatePanoLayout: no ceiling height to try above the camera ({} m) up to "
                            "max_ceiling_m = {}",
                            camera_height_m, options.max_ceiling_m));
  std::optional<double> direction;
  if (options.manhattan) {
    const PathFit rough = fit(std::clamp(camera_height_m + 1.0, lowest, options.max_ceiling_m), std::nullopt);
    direction = DominantWallDirection(rough.bins, distances_m, directions);
  }
  PathFit best;
  for (double h = lowest; h <= options.max_ceiling_m + 1e-9; h += options.ceiling_step_m) {
    PathFit f = fit(h, direction);
    if (f.score > best.score) {
      best = std::move(f);
      layout.ceiling_height_m = h;
    }
  }
  if (direction) {
    // Climb to the best direction nearby: steps of 2°, halved down to 0.25°.
    for (double step_deg = 2.0; step_deg >= 0.25; step_deg /= 2) {
      for (bool moved = true; moved;) {
        moved = false;
        for (const double sign : {-1.0, 1.0}) {
          const double candidate = *direction + sign * DegToRad(step_deg);
          PathFit f = fit(layout.ceiling_height_m, candidate);
          if (f.score > best.score) {
            best = std::move(f);
            direction = candidate;
            moved = true;
            break;
          }
        }
      }
    }
    layout.wall_direction_deg = std::fmod(RadToDeg(*direction) + 360.0, 90.0);
  }
  layout.score = best.score;
  layout.distance_m.resize(columns);
  for (int x = 0; x < columns; ++x) layout.distance_m[x] = distances_m[best.bins[x]];
  layout.supported = SupportedColumns(edges, layout, options);
  if (direction && options.close_polygon) {
    std::vector<Vec2> polygon =
        ManhattanPolygon(best.states, layout.supported, distances_m, *direction, directions, options.min_wall_columns);
    std::vector<double> closed(columns);
    bool inside = !polygon.empty();
    for (int x = 0; x < columns && inside; ++x) {
      closed[x] = RayPolygonDistance(directions[x], polygon);
      inside = std::isfinite(closed[x]) && closed[x] > 0.05;
    }
    if (inside) {
      layout.polygon_m = std::move(polygon);
      for (int x = 0; x < columns; ++x) {
        if (options.polygon_gaps_only && layout.supported[x]) continue;
        layout.distance_m[x] = closed[x];
        layout.supported[x] = true;
      }
    }
  }
  return layout;
}

cv::Mat EquirectFromViewLabels(const std::vector<PanoView>& views, const std::vector<cv::Mat>& labels, int width_px) {
  CheckArgument(views.size() == labels.size(),
                fmt::format("EquirectFromViewLabels: {} views but {} label maps", views.size(), labels.size()));
  CheckArgument(width_px >= 2 && width_px % 2 == 0,
                fmt::format("EquirectFromViewLabels: width_px = {}, must be even and >= 2", width_px));
  const int rows = width_px / 2;
  cv::Mat out(rows, width_px, CV_8UC1, cv::Scalar(kLabelIgnore));
  std::vector<Mat3> camera_from_world;
  for (const PanoView& v : views) camera_from_world.push_back(v.WorldFromCamera().transpose());
  for (int y = 0; y < rows; ++y) {
    std::uint8_t* o = out.ptr<std::uint8_t>(y);
    for (int x = 0; x < width_px; ++x) {
      const Vec3 d = DirectionFromEquirectPixel(Vec2(x, y), width_px, rows);
      double best_forward = 0.0;
      for (std::size_t i = 0; i < views.size(); ++i) {
        if (labels[i].empty()) continue;
        const Vec3 c = camera_from_world[i] * d;
        if (c.z() <= best_forward) continue;
        const PinholeCamera& cam = views[i].camera;
        const double u = cam.fx * c.x() / c.z() + cam.cx, v = cam.fy * c.y() / c.z() + cam.cy;
        const int iu = static_cast<int>(std::lround(u)), iv = static_cast<int>(std::lround(v));
        if (iu < 0 || iv < 0 || iu >= labels[i].cols || iv >= labels[i].rows) continue;
        best_forward = c.z();
        o[x] = labels[i].at<std::uint8_t>(iv, iu);
      }
    }
  }
  return out;
}

cv::Mat LayoutViewLabels(const PanoLayout& layout, const PanoView& view, const cv::Mat& view_labels) {
  const PinholeCamera& cam = view.camera;
  CheckArgument(view_labels.empty() || (view_labels.type() == CV_8UC1 && view_labels.cols == cam.width_px &&
                                        view_labels.rows == cam.height_px),
                fmt::format("LayoutViewLabels: labels {}x{} for a view {}x{}", view_labels.cols, view_labels.rows,
                            cam.width_px, cam.height_px));
  cv::Mat out(cam.height_px, cam.width_px, CV_8UC1, cv::Scalar(kBackground));
  if (layout.distance_m.empty()) return out;
  const Mat3 world_from_camera = view.WorldFromCamera();
  const double above_m = layout.ceiling_height_m - layout.camera_height_m;
  for (int v = 0; v < cam.height_px; ++v) {
    std::uint8_t* o = out.ptr<std::uint8_t>(v);
    for (int u = 0; u < cam.width_px; ++u) {
      // One column per pixel; the band compared as slopes (tan elevation).
      const Vec3 d = world_from_camera * UnprojectToCamera(cam, Vec2(u, v), 1.0);
      const int column = layout.ColumnAlong(d);
      if (!layout.supported.empty() && !layout.supported[column]) continue;
      const double distance = layout.distance_m[column];
      const double slope = d.z() / std::hypot(d.x(), d.y());
      if (slope < -layout.camera_height_m / distance || slope > above_m / distance) continue;
      const std::uint8_t l = view_labels.empty() ? kWall : view_labels.at<std::uint8_t>(v, u);
      o[u] = (l == kDoor || l == kWindow) ? l : kWall;
    }
  }
  return out;
}

cv::Mat DrawPanoLayout(const cv::Mat& equirect_bgr, const PanoLayout& layout) {
  cv::Mat out = equirect_bgr.clone();
  if (layout.distance_m.empty() || out.empty()) return out;
  const int columns = layout.Columns(), rows = out.rows;
  const double scale = static_cast<double>(out.cols) / columns;
  const int thickness = std::max(1, out.cols / 1024);
  auto curve = [&](bool ceiling, const cv::Scalar& colour) {
    std::vector<cv::Point> points;
    auto flush = [&] {
      if (points.size() > 1) cv::polylines(out, points, false, colour, thickness, cv::LINE_AA);
      points.clear();
    };
    for (int x = 0; x < columns; ++x) {
      if (!layout.supported.empty() && !layout.supported[x]) {
        flush();
        continue;
      }
      const double d = layout.distance_m[x];
      const double e = ceiling ? CeilingEdgeElevation(layout.camera_height_m, layout.ceiling_height_m, d)
                               : FloorEdgeElevation(layout.camera_height_m, d);
      points.emplace_back(static_cast<int>(std::lround((x + 0.5) * scale - 0.5)),
                          static_cast<int>(std::lround(RowOfElevation(e, rows))));
    }
    flush();
  };
  curve(false, cv::Scalar(0, 0, 255));
  curve(true, cv::Scalar(0, 255, 0));
  return out;
}

}  // namespace asbuilt
