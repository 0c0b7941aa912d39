#include "asbuilt/stereo/contacts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iterator>
#include <map>
#include <numeric>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "asbuilt/geometry/label_class.h"

namespace asbuilt {
namespace {

// Stereo heights under ceiling edges (PendingContacts::stereo_samples_m)
// needed to estimate the ceiling, or to check the paired estimate.
constexpr size_t kMinStereoCeilingSamples = 200;

// Ceiling-height samples counted as independent in a σ, at most: samples of
// one frame's neighbouring columns share its label edges' errors (and, for
// stereo heights, its matcher's bias along the whole wall), so a 12-frame
// turn gives about two independent ones per frame.
constexpr double kIndependentCeilingSamples = 24.0;

bool IsStructureLabel(unsigned char label) { return label >= 1 && label <= 3; }

// Depth σ of a point on a horizontal plane `dh` metres from the camera, at
// depth z, for a row error σ_v and a camera-height error σ_h.
double ContactSigma(double z, double dh, double fy, double sigma_v, double sigma_h) {
  const double from_row = z * z * sigma_v / (fy * dh);
  const double from_height = z * sigma_h / dh;
  return std::hypot(from_row, from_height);
}

// Vertical colour steps for SnapRowToImageEdge: S(y, u) is the size of the
// step from row y to row y + 1 (an edge at row y + 0.5), summed over the
// colour channels (a blue-grey wall over beige tiles differs more in colour
// than in brightness, while the tiles' grout lines differ in brightness),
// after a Gaussian (σ 1 px) against noise, averaged over columns u − 2…u + 2.
cv::Mat VerticalSteps(const cv::Mat& image) {
  cv::Mat f;
  image.convertTo(f, CV_32F);
  cv::GaussianBlur(f, f, cv::Size(0, 0), 1.0);
  cv::Mat diff = cv::abs(f.rowRange(1, f.rows) - f.rowRange(0, f.rows - 1));
  cv::Mat summed = diff.reshape(1, diff.rows * diff.cols);  // One row per pixel, one column per channel.
  cv::reduce(summed, summed, 1, cv::REDUCE_SUM);
  cv::Mat steps = cv::Mat::zeros(image.size(), CV_32F);
  summed.reshape(1, diff.rows).copyTo(steps.rowRange(0, f.rows - 1));
  cv::blur(steps, steps, cv::Size(5, 1));
  return steps;
}

// Signed brightness steps: B(y, u) = the channels' sum at row y + 1 less at
// row y, after a Gaussian blur of 1 px. Averaged over many columns, an edge of
// one sign adds up and noise cancels (SkirtingProfile).
cv::Mat SignedVerticalSteps(const cv::Mat& image) {
  cv::Mat f;
  image.convertTo(f, CV_32F);
  if (f.channels() > 1) cv::transform(f, f, cv::Matx<float, 1, 3>(1, 1, 1));
  cv::GaussianBlur(f, f, cv::Size(0, 0), 1.0);
  cv::Mat steps = cv::Mat::zeros(image.size(), CV_32F);
  cv::Mat diff = f.rowRange(1, f.rows) - f.rowRange(0, f.rows - 1);
  diff.copyTo(steps.rowRange(0, f.rows - 1));
  return steps;
}

// FramePointsOptions::contact_snap_px: the row of the strongest colour step
// within `radius` rows of a label edge at `row` (k + 0.5), refined to a
// sub-pixel peak; the label edge itself when the image shows no step of at
// least `min_step` (channels summed) there, or the peak is at the window's
// end.
double SnapRowToImageEdge(const cv::Mat& steps, int u, double row, int radius, double min_step) {
  if (radius <= 0 || steps.empty()) return row;
  const int k0 = static_cast<int>(std::floor(row - 0.5));  // Edge between rows k0 and k0 + 1.
  const int lo = std::max(0, k0 - radius), hi = std::min(steps.rows - 2, k0 + radius);
  int best = -1;
  float best_step = 0.0f;
  for (int k = lo; k <= hi; ++k) {
    const float a = steps.at<float>(k, u);
    if (a > best_step) best_step = a, best = k;
  }
  if (best <= lo || best >= hi || best_step < min_step) return row;
  const double a = steps.at<float>(best - 1, u), b = best_step, c = steps.at<float>(best + 1, u);
  const double den = a - 2.0 * b + c;
  const double offset = den < 0.0 ? std::clamp(0.5 * (a - c) / den, -0.5, 0.5) : 0.0;
  return best + 0.5 + offset;
}

// A floor contact's column, label-edge row and depth (AddContactPoints);
// the boundary points of a frame without wall stereo take their depth.
struct FloorColumn {
  int u = 0;
  double row = 0.0;
  double depth_m = 0.0;
  unsigned char label = 0;
};
// FramePointsOptions::skirting_depth_m: the height above the floor of the
// strongest colour step 3–25 cm above a wall foot at `floor_row` and depth
// `z` (the top of a skirting board), or nullopt when that stretch of the
// column shows no step of `min_step`, or only at its ends.
std::optional<double> SkirtingTop(const cv::Mat& steps, int u, double floor_row, double z, double h,
                                  const PinholeCamera& cam, double min_step) {
  constexpr double kLowest = 0.03, kHighest = 0.25;
  const int lo = std::max(0, static_cast<int>(std::floor(cam.cy + cam.fy * (h - kHighest) / z)));
  const int hi = std::min(static_cast<int>(std::floor(floor_row - 0.5)) - 1,
                          static_cast<int>(std::floor(cam.cy + cam.fy * (h - kLowest) / z - 0.5)));
  if (hi - lo < 2) return std::nullopt;
  int best = -1;
  float best_step = 0.0f;
  for (int k = lo; k <= hi; ++k) {
    const float a = steps.at<float>(k, u);
    if (a > best_step) best_step = a, best = k;
  }
  if (best <= lo || best >= hi || best_step < min_step) return std::nullopt;
  return h - (best + 0.5 - cam.cy) * z / cam.fy;
}

// Whether a frame's wall feet stand on skirting: a step in at least half of
// them, two thirds of those within 1.5 cm of their median height.
bool SkirtingSeen(std::vector<double> heights, int wall_feet, double* height_m) {
  if (wall_feet < 10 || 2 * static_cast<int>(heights.size()) < wall_feet) return false;
  std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
  const double median = heights[heights.size() / 2];
  const auto near =
      std::count_if(heights.begin(), heights.end(), [&](double s) { return std::abs(s - median) <= 0.015; });
  if (3 * near < 2 * static_cast<long>(heights.size())) return false;
  *height_m = median;
  return true;
}

// FramePointsOptions::skirting_depth_m: wall feet pooled by height above
// the floor (SkirtingEvidence). At each foot (column u, floor edge at
// `floor_row`, depth z) the signed brightness steps 3–25 cm above it
// (SignedVerticalSteps) are added into 5 mm bins, from 3 rows above the
// foot's own edge up. A skirting's top is one height all round the room and
// one sign of step (the board lighter or darker than the wall), so it adds
// up across the feet — of a frame, and of all frames of a capture — while
// sensor or render noise, which one column cannot tell from a step, cancels.
constexpr double kSkirtingBinM = 0.005;
double SkirtingBinHeight(int bin) { return 0.03 + (bin + 0.5) * kSkirtingBinM; }

// The board's height from pooled feet, or nullopt. For one frame's feet:
// the bin whose mean step stands out most from zero, when it does by
// kMinScore standard errors (each taken as if only every third foot were
// independent: neighbouring columns share the blur) and lies inside the
// range. For a whole capture's (`capture_wide`), thousands of feet, even
// shading (a wall darkening towards the floor) lies many standard errors
// from zero in every bin (Blender rooms 06 and 07, no skirting: −8 to −17),
// so the bin must stand out from the profile's own level (its median bin),
// by kMinScore and by three times the median bin's distance from it (our
// renderer's views of room 05, no skirting: a bump of 9 among bins 4 off;
// room 01's board: 41 among 8), 3 cm inside the range (room 05 rises
// towards 25 cm).
std::optional<double> PooledSkirtingTop(const SkirtingEvidence& e, bool capture_wide) {
  constexpr double kMinScore = 7.0;
  constexpr int kBins = SkirtingEvidence::kBins, kFirstBin = 3;  // Searched from 4.5 cm up.
  constexpr int kInside = 6;                                     // 3 cm, capture-wide.
  if (e.feet < 10) return std::nullopt;
  std::array<double, kBins> score{};
  for (int b = 0; b < kBins; ++b) {
    if (e.count[b] < 10) continue;
    const double n = e.count[b], mean = e.sum[b] / n;
    const double var = std::max(1e-9, e.sum_sq[b] / n - mean * mean);
    score[b] = mean / std::sqrt(3.0 * var / n);
  }
  double level = 0.0, spread = 0.0;
  if (capture_wide) {
    std::vector<double> v;
    for (int b = kFirstBin; b < kBins; ++b) {
      if (e.count[b] >= 10) v.push_back(score[b]);
    }
    if (v.size() < 5) return std::nullopt;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    level = v[v.size() / 2];
    for (double& x : v) x = std::abs(x - level);
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    spread = v[v.size() / 2];
  }
  for (int b = 0; b < kBins; ++b) score[b] = e.count[b] < 10 ? 0.0 : std::abs(score[b] - level);
  // The lowest bins carry the tail of the foot's own edge, blurred upwards
  // (a plain wall scores up to 5.6 there in a 1024-wide Blender panorama).
  const int best = static_cast<int>(std::max_element(score.begin() + kFirstBin, score.end()) - score.begin());
  if (best == kFirstBin || best == kBins - 1 || score[best] < std::max(kMinScore, 3 * spread)) return std::nullopt;
  if (capture_wide && (best < kInside || best + kInside >= kBins)) return std::nullopt;
  const double a = score[best - 1], c = score[best + 1], m = score[best];
  const double den = a - 2 * m + c;
  const double offset = den < 0 ? std::clamp(0.5 * (a - c) / den, -0.5, 0.5) : 0.0;
  return SkirtingBinHeight(best) + offset * kSkirtingBinM;
}

// One frame's feet: pooled (SkirtingEvidence), and each also read on its
// own (SkirtingTop); where those readings agree (SkirtingSeen, sharp
// images) they decide.
class SkirtingProfile {
 public:
  SkirtingProfile(const cv::Mat& steps, const cv::Mat& signed_steps, double min_step)
      : steps_(steps), signed_steps_(signed_steps), min_step_(min_step) {}

  void Add(int u, double floor_row, double z, double h, const PinholeCamera& cam) {
    if (steps_.empty() || signed_steps_.empty()) return;
    if (const auto s = SkirtingTop(steps_, u, floor_row, z, h, cam, min_step_)) per_column_.push_back(*s);
    const cv::Mat& signed_steps = signed_steps_;
    ++evidence_.feet;
    for (int b = 0; b < SkirtingEvidence::kBins; ++b) {
      const double edge = cam.cy + cam.fy * (h - SkirtingBinHeight(b)) / z;  // Image row of that height.
      const double k = edge - 0.5;                                           // Step row k: between rows k and k + 1.
      if (k < 0 || k > floor_row - 3.5 || k + 1 >= signed_steps.rows) continue;
      const int k0 = static_cast<int>(k);
      const double f = k - k0;
      const double x = (1 - f) * signed_steps.at<float>(k0, u) + f * signed_steps.at<float>(k0 + 1, u);
      evidence_.sum[b] += x;
      evidence_.sum_sq[b] += x * x;
      ++evidence_.count[b];
    }
  }

  // The skirting top's height above the floor from this frame's feet: their
  // own readings where they agree (SkirtingSeen, sharp images), else the
  // pooled profile (PooledSkirtingTop).
  std::optional<double> Top() const {
    if (double top = NAN; SkirtingSeen(per_column_, evidence_.feet, &top)) return top;
    return PooledSkirtingTop(evidence_, /*capture_wide=*/false);
  }
  const SkirtingEvidence& evidence() const { return evidence_; }

 private:
  cv::Mat steps_, signed_steps_;
  double min_step_;
  std::vector<double> per_column_;  // Each foot's own reading, where it had one.
  SkirtingEvidence evidence_;
};

// Wall floor contacts, wherever they were filed: `points` from index
// first_point, `pending`'s paired and topped ones from theirs. `samples`:
// each foot's paired ceiling sample, or null.
void GatherWallFeet(std::vector<ClassPoint>& points, std::size_t first_point, PendingContacts& pending,
                    std::size_t first_paired, std::size_t first_topped, std::vector<ClassPoint*>* feet,
                    std::vector<double*>* samples) {
  const auto wanted = [](const ClassPoint& p) {
    return p.source == PointSource::kContact && p.label == LabelClass::kWall;
  };
  for (std::size_t i = first_point; i < points.size(); ++i) {
    ClassPoint& p = points[i];
    if (wanted(p) && p.position_m.z() == 0.0) feet->push_back(&p), samples->push_back(nullptr);
  }
  for (std::size_t i = first_paired; i < pending.paired_floor.size(); ++i) {
    auto& pf = pending.paired_floor[i];
    if (wanted(pf.point)) feet->push_back(&pf.point), samples->push_back(&pf.ceiling_sample_m);
  }
  for (std::size_t i = first_topped; i < pending.topped_floor.size(); ++i) {
    auto& tf = pending.topped_floor[i];
    if (wanted(tf.point)) feet->push_back(&tf.point), samples->push_back(nullptr);
  }
}

// Moves one frame's wall floor contacts (GatherWallFeet) `depth_m` back
// from the camera, along the wall's normal there (from the contacts 2
// columns either side), and rescales their ceiling samples: the wall's face
// stands behind the skirting's foot. `floor_columns` (may be null): the
// frame's columns, whose depths the boundary points take.
void MoveWallFeetBehindSkirting(double depth_m, const Eigen::Isometry3d& world_from_cam, const PinholeCamera& cam,
                                const std::vector<ClassPoint*>& feet, const std::vector<double*>& samples,
                                std::vector<FloorColumn>* floor_columns) {
  const Eigen::Isometry3d cam_from_world = world_from_cam.inverse();
  const Vec3 origin = world_from_cam.translation();
  const double h = origin.z();
  // Order by bearing in the camera (its image column).
  std::vector<std::size_t> order(feet.size());
  std::iota(order.begin(), order.end(), 0);
  std::vector<double> bearing(feet.size());
  for (std::size_t i = 0; i < feet.size(); ++i) {
    const Vec3 c = cam_from_world * feet[i]->position_m;
    bearing[i] = c.x() / c.z();
  }
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return bearing[a] < bearing[b]; });
  std::vector<Vec3> moved(feet.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Vec3& p = feet[order[k]]->position_m;
    const Vec3& a = feet[order[k >= 2 ? k - 2 : 0]]->position_m;
    const Vec3& b = feet[order[std::min(order.size() - 1, k + 2)]]->position_m;
    Vec2 away(p.x() - origin.x(), p.y() - origin.y());
    away.normalize();
    Vec2 normal = away;
    const Vec2 along(b.x() - a.x(), b.y() - a.y());
    // A local wall direction when the neighbours are on the same wall (close
    // together); else straight away from the camera.
    if (along.norm() > 1e-6 && along.norm() < 0.5) {
      normal = Vec2(-along.y(), along.x()).normalized();
      if (normal.dot(away) < 0) normal = -normal;
    }
    moved[order[k]] = p + depth_m * Vec3(normal.x(), normal.y(), 0.0);
  }
  std::vector<double> ratio(feet.size());  // New depth over old.
  for (std::size_t i = 0; i < feet.size(); ++i) {
    const double z_old = (cam_from_world * feet[i]->position_m).z(), z_new = (cam_from_world * moved[i]).z();
    ratio[i] = z_old > 0 ? z_new / z_old : 1.0;
    feet[i]->position_m = moved[i];
    if (samples[i]) *samples[i] = h + (*samples[i] - h) * ratio[i];
  }
  // The boundary points take their wall depth from these columns.
  if (feet.empty() || floor_columns == nullptr) return;
  for (FloorColumn& c : *floor_columns) {
    if (c.label != kLabelWall) continue;
    const double b = (c.u - cam.cx) / cam.fx;
    const auto nearest = std::min_element(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
      return std::abs(bearing[x] - b) < std::abs(bearing[y] - b);
    });
    c.depth_m *= ratio[*nearest];
  }
}

// A one-camera view's column with no floor contact (a near wall: its foot
// lies below the view) that runs from its ceiling contact `ceiling` (edge at
// row ceiling_edge) down into a door or window: the opening's top edge is on
// the wall, at the ceiling contact's depth (PendingContacts::CeilingBoundary).
// `rot` turns camera vectors into the world.
void AddOpeningHeadBelowCeiling(const cv::Mat& labels, int u, double ceiling_edge, int run, const ContactRay& ceiling,
                                const PinholeCamera& cam, const Mat3& rot, PendingContacts* pending) {
  auto label_at = [&](int v) { return labels.ptr<unsigned char>(v)[u]; };
  int v = static_cast<int>(ceiling_edge + 0.5);
  while (v < labels.rows && label_at(v) == kLabelWall) ++v;
  const unsigned char below = v < labels.rows ? label_at(v) : 0;
  if (below != kLabelDoor && below != kLabelWindow) return;
  for (int k = 0; k < run; ++k) {
    if (v + k >= labels.rows || label_at(v + k) != below) return;
  }
  pending->ceiling_boundaries.push_back({.edge = {.label = static_cast<LabelClass>(below),
                                                  .origin_m = ceiling.origin_m,
                                                  .direction = rot * UnprojectToCamera(cam, Vec2(u, v - 0.5), 1.0),
                                                  .fy_px = cam.fy,
                                                  .frame = ceiling.frame},
                                         .wall_rise = ceiling.direction.z(),
                                         .source = PointSource::kContact});
}

// Where a frame's own wall feet show a board (SkirtingProfile::Top), they
// move `depth_m` back; either way the frame's evidence is kept for the
// capture (PendingContacts::MoveFeetBehindSkirting). `first`: where this
// frame's feet begin in result's points, paired and topped floor contacts.
void SettleFrameSkirting(const SkirtingProfile& skirting, int frame, const Eigen::Isometry3d& world_from_cam,
                         const PinholeCamera& cam, double depth_m, std::array<std::size_t, 3> first,
                         FrameContacts* result, std::vector<FloorColumn>* floor_columns) {
  const std::optional<double> top = skirting.Top();
  if (top) {
    result->skirting_height_m = *top;
    std::vector<ClassPoint*> feet;
    std::vector<double*> samples;
    GatherWallFeet(result->points, first[0], result->pending, first[1], first[2], &feet, &samples);
    MoveWallFeetBehindSkirting(depth_m, world_from_cam, cam, feet, samples, floor_columns);
  }
  if (skirting.evidence().feet == 0) return;
  SkirtingEvidence e = skirting.evidence();
  e.frame = frame;
  e.moved = top.has_value();
  e.world_from_cam = world_from_cam;
  e.camera = cam;
  result->pending.skirting.push_back(std::move(e));
}

// FindFrameContacts (contacts.h), before the per-column wall disparity.
// Label edges lie halfway between pixel centres. `result->covered` (zeros
// on entry) receives each contacted column's wall run, from the contact
// along the labelled structure; `floor_columns` each floor contact's column.
void AddContactPoints(const StereoFrame& frame, const cv::Mat& disparity, const FramePointsOptions& options,
                      const Eigen::Isometry3d& world_from_cam, FrameContacts* result,
                      std::vector<FloorColumn>* floor_columns) {
  cv::Mat* covered = &result->covered;
  const cv::Mat& labels = frame.labels_left;
  const PinholeCamera& cam = frame.camera;
  const double h = world_from_cam.translation().z();  // Camera height above the floor (z = 0).
  if (!(h > 0.05)) return;                            // No usable height: no contacts.
  const int rows = labels.rows, cols = labels.cols, run = options.contact_min_run_px;
  const double fxb = cam.fx * frame.baseline_m;
  const cv::Mat steps =
      options.contact_snap_px.value_or(0) > 0 || options.floor_snap_px.value_or(0) > 0 || options.skirting_depth_m > 0
          ? VerticalSteps(frame.left)
          : cv::Mat();
  const std::size_t first_point = result->points.size(), first_paired = result->pending.paired_floor.size(),
                    first_topped = result->pending.topped_floor.size();
  SkirtingProfile skirting(steps, options.skirting_depth_m > 0 ? SignedVerticalSteps(frame.left) : cv::Mat(),
                           options.contact_snap_min_step);
  auto snap = [&](int u, double row) {
    return SnapRowToImageEdge(steps, u, row, options.contact_snap_px.value_or(0), options.contact_snap_min_step);
  };
  auto label_at = [&](int v, int u) { return labels.ptr<unsigned char>(v)[u]; };
  auto runs = [&](int v0, int dir, int n, auto&& pred, int u) {
    for (int k = 0; k < n; ++k) {
      const int v = v0 + dir * k;
      if (v < 0 || v >= rows || !pred(label_at(v, u))) return false;
    }
    return true;
  };
  auto is_background = [](unsigned char l) { return l == kLabelBackground; };
  const Mat3 rot = world_from_cam.linear();
  const Vec3 origin = world_from_cam.translation();
  auto ray = [&](double u, double v) { return Vec3(rot * UnprojectToCamera(cam, Vec2(u, v), 1.0)); };
  // Marks the structure run from row v0 in direction dir (±1) in columns
  // u…u+step−1.
  auto cover = [&](int u, int v0, int dir) {
    for (int v = v0; v >= 0 && v < rows && IsStructureLabel(label_at(v, u)); v += dir) {
      for (int x = u; x < std::min(cols, u + options.contact_col_step_px); ++x) covered->at<unsigned char>(v, x) = 1;
    }
  };

  // This frame's top edge, for every frame's topped floor contacts (Resolve).
  PendingContacts::TopEdge top{.frame = frame.index, .world_from_camera = world_from_cam, .camera = cam};
  top.wall_to_row.assign(cols, -1);
  for (int u = 0; u < cols; ++u) {
    int v = 0;
    while (v < rows && IsStructureLabel(label_at(v, u))) ++v;
    top.wall_to_row[u] = v - 1;
  }
  result->pending.top_edges.push_back(std::move(top));

  for (int u = 0; u < cols; u += options.contact_col_step_px) {
    // Floor: scan up from the bottom for the lowest wall/door → background
    // edge, snapped within floor_snap_px rows only (a wider window reaches
    // skirting tops and grout lines: docs/stereo.md, "Option notes").
    // `floor_edge` is the label edge (which rows hold the wall), `floor_row`
    // where the contact is measured (snapped when asked).
    double floor_row = NAN, floor_edge = NAN;
    unsigned char floor_label = 0;
    for (int v = rows - 1 - run; v >= run; --v) {
      if (v + 0.5 <= cam.cy + 1.0) break;  // At or above the horizon: not the floor.
      const unsigned char a = label_at(v, u);
      if ((a != 1 && a != 2) || label_at(v + 1, u) != 0) continue;
      if (!runs(
              v, -1, run, [a](unsigned char l) { return l == a; }, u) ||
          !runs(v + 1, 1, run, is_background, u)) {
        continue;
      }
      // The floor plane's disparity at row y is fx·B·(y − cy)/(fy·h); something
      // standing in front of the wall base is nearer than that.
      std::vector<float> excess;
      for (int y = v + 2; y <= std::min(rows - 1, v + 10); ++y) {
        const float* d = disparity.ptr<float>(y);
        const unsigned char* l = labels.ptr<unsigned char>(y);
        const double predicted = fxb * (y - cam.cy) / (cam.fy * h);
        for (int x = std::max(0, u - 2); x <= std::min(cols - 1, u + 2); ++x) {
          if (l[x] == kLabelBackground && std::isfinite(d[x])) excess.push_back(static_cast<float>(d[x] - predicted));
        }
      }
      if (excess.size() >= 5) {
        std::nth_element(excess.begin(), excess.begin() + excess.size() / 2, excess.end());
        const double predicted = fxb * (v + 0.5 - cam.cy) / (cam.fy * h);
        if (excess[excess.size() / 2] > std::max(options.contact_floor_tolerance_px, 0.15 * predicted)) {
          ++result->floor_rejected;
          break;  // Occluded base: nothing lower in this column is the wall's.
        }
      }
      floor_edge = v + 0.5;
      floor_row =
          SnapRowToImageEdge(steps, u, floor_edge, options.floor_snap_px.value_or(0), options.contact_snap_min_step);
      if (floor_row <= cam.cy + 1.0) floor_row = floor_edge;
      floor_label = a;
      break;
    }
    std::optional<ClassPoint> floor_point;
    if (std::isfinite(floor_row)) {
      const double z = cam.fy * h / (floor_row - cam.cy);
      if (z >= options.min_depth_m && z <= options.max_depth_m) {
        Vec3 p = origin + ray(u, floor_row) * z;
        p.z() = 0.0;  // On the plane (rounding).
        floor_point = ClassPoint{static_cast<LabelClass>(floor_label), p,
                                 ContactSigma(z, h, cam.fy, options.contact_sigma_px, options.camera_height_sigma_m),
                                 PointSource::kContact, frame.index};
        ++result->floor_contacts;
        floor_columns->push_back({u, floor_row, z, floor_label});
        if (floor_label == kLabelWall) skirting.Add(u, floor_row, z, h, cam);
        cover(u, static_cast<int>(floor_edge - 0.5), -1);
      } else {
        floor_row = NAN;
      }
    }
    // Ceiling: scan down from the top for the highest background → wall edge.
    // `ceiling_edge` is the label edge (which rows hold the wall),
    // `ceiling_row` where the contact is measured (snapped when asked).
    double ceiling_row = NAN, ceiling_edge = NAN;
    for (int v = run; v < rows - run; ++v) {
      if (v - 0.5 >= cam.cy - 1.0) break;  // At or below the horizon.
      if (label_at(v, u) != 1 || label_at(v - 1, u) != 0) continue;
      if (!runs(v - 1, -1, run, is_background, u) ||
          !runs(
              v, 1, run, [](unsigned char l) { return l == kLabelWall; }, u)) {
        continue;
      }
      ceiling_edge = v - 0.5;
      ceiling_row = snap(u, ceiling_edge);
      if (ceiling_row >= cam.cy - 1.0) ceiling_row = ceiling_edge;
      break;
    }
    // One structure from ceiling to floor in this column (openings may cut
    // it): a vertical wall, so both contacts share the depth, and the
    // ceiling's height follows: H = h + h·(cy − v_c)/(v_f − cy). The floor
    // contact then waits for H: where they disagree, the "floor contact" was
    // the top of something standing in front of the wall base.
    bool paired = false;
    if (floor_point && std::isfinite(ceiling_row)) {
      paired = true;
      for (int v = static_cast<int>(ceiling_edge + 0.5); v <= static_cast<int>(floor_edge - 0.5) && paired; ++v) {
        paired = IsStructureLabel(label_at(v, u));
      }
    }
    if (paired) {
      const double below = floor_row - cam.cy, above = cam.cy - ceiling_row;
      const double sample = h + h * above / below;
      const double sigma = options.contact_sigma_px * std::hypot(h / below, h * above / (below * below));
      result->pending.paired_floor.push_back({*floor_point, sample, sigma});
    } else if (floor_point) {
      // Wall (or openings) from the image's top edge down to the contact.
      if (result->pending.top_edges.back().wall_to_row[u] >= static_cast<int>(floor_edge - 0.5)) {
        // The image's top edge (row −0.5) still shows the wall at depth z.
        const double z = cam.fy * h / (floor_row - cam.cy);
        const double rise = (cam.cy + 0.5) / cam.fy;
        result->pending.topped_floor.push_back({*floor_point, h + z * rise, floor_point->sigma_m * rise});
      } else {
        result->points.push_back(*floor_point);
      }
    }
    if (!std::isfinite(ceiling_row)) continue;
    // The wall's stereo depth just below the contact gives a rough height
    // too: the fallback when no column sees both contacts of a wall.
    {
      std::vector<float> ds;
      const int v0 = static_cast<int>(ceiling_edge + 0.5);
      for (int y = v0 + 2; y <= std::min(rows - 1, v0 + 10); ++y) {
        const float* d = disparity.ptr<float>(y);
        const unsigned char* l = labels.ptr<unsigned char>(y);
        for (int x = std::max(0, u - 2); x <= std::min(cols - 1, u + 2); ++x) {
          if (l[x] == kLabelWall && std::isfinite(d[x]) && d[x] > 0) ds.push_back(d[x]);
        }
      }
      if (ds.size() >= 5) {
        std::nth_element(ds.begin(), ds.begin() + ds.size() / 2, ds.end());
        const double z = fxb / ds[ds.size() / 2];
        result->pending.stereo_samples_m.push_back(h + z * (cam.cy - ceiling_row) / cam.fy);
      }
    }
    ContactRay r{.label = LabelClass::kWall,
                 .origin_m = origin,
                 .direction = ray(u, ceiling_row),
                 .fy_px = cam.fy,
                 .frame = frame.index};
    ++result->ceiling_contacts;
    cover(u, static_cast<int>(ceiling_edge + 0.5), 1);
    for (int x = u; x < std::min(cols, u + options.contact_col_step_px); ++x) {
      result->ceiling_rise[x] = static_cast<float>(r.direction.z());
    }
    if (!floor_point && frame.labels_right.empty()) {
      AddOpeningHeadBelowCeiling(labels, u, ceiling_edge, run, r, cam, rot, &result->pending);
    }
    result->pending.ceiling_rays.push_back(r);
  }
  if (options.skirting_depth_m > 0) {
    SettleFrameSkirting(skirting, frame.index, world_from_cam, cam, options.skirting_depth_m,
                        {first_point, first_paired, first_topped}, result, floor_columns);
  }
}

}  // namespace

FrameContacts FindFrameContacts(const StereoFrame& frame, const cv::Mat& disparity_px,
                                const FramePointsOptions& options) {
  FrameContacts result;
  result.covered = cv::Mat::zeros(frame.labels_left.size(), CV_8U);
  result.wall_disparity_px.assign(frame.labels_left.cols, NAN);
  result.ceiling_rise.assign(frame.labels_left.cols, NAN);
  const Eigen::Isometry3d world_from_cam = WorldFromCamera(frame.pose, frame.baseline_m, StereoEye::kLeft);
  std::vector<FloorColumn> floor_columns;
  AddContactPoints(frame, disparity_px, options, world_from_cam, &result, &floor_columns);
  for (const FloorColumn& c : floor_columns) {
    for (int x = c.u; x < std::min(frame.labels_left.cols, c.u + options.contact_col_step_px); ++x) {
      result.wall_disparity_px[x] = static_cast<float>(frame.camera.fx * frame.baseline_m / c.depth_m);
    }
  }
  return result;
}

std::optional<CeilingHeight> CeilingHeightFromSamples(std::vector<double> samples_m, int min_samples) {
  std::erase_if(samples_m, [](double x) { return !std::isfinite(x) || x <= 0; });
  if (static_cast<int>(samples_m.size()) < std::max(1, min_samples)) return std::nullopt;
  std::sort(samples_m.begin(), samples_m.end());
  // The densest window of width max(2 cm, 1 %): true samples pile up there;
  // a cabinet's top taken for the floor gives a spread of larger values.
  auto window_from = [&](size_t lo) {
    const double width = std::max(0.02, 0.01 * samples_m[lo]);
    size_t hi = lo;
    while (hi < samples_m.size() && samples_m[hi] <= samples_m[lo] + width) ++hi;
    return hi;
  };
  size_t best_lo = 0, best_hi = 0;
  for (size_t lo = 0; lo < samples_m.size(); ++lo) {
    const size_t hi = window_from(lo);
    if (hi - lo > best_hi - best_lo) best_lo = lo, best_hi = hi;
  }
  // A cluster of a handful among many scattered samples is no measurement.
  const size_t enough = std::max<size_t>(static_cast<size_t>(std::max(1, min_samples / 2)), samples_m.size() / 5);
  if (best_hi - best_lo < enough) return std::nullopt;
  // …but a flat top (a bed, a desk along the walls) gives a cluster of its
  // own, and it can outnumber the true one where furniture hides most wall
  // bases: its samples are h + (H − h)·h/(h − t), always above the ceiling.
  // Every mistake that takes something for a wall's base (a top, a
  // skirting board) raises the sample. So a cluster below the densest is
  // the ceiling when it stands apart: at least half `enough` samples and a
  // tenth of all in one window, and the windows either side of it hold a
  // third as many together (bench_rooms seed 22, exact labels: 15 samples at
  // 2.76–2.79 m, the truth, none within 5 cm, under 78 at 3.40 m from a
  // 0.6 m table's top). A segmenter's stray label edges give no such cluster,
  // only a tail (seed 16: 3.30–3.43 m under the true 3.45 m).
  const size_t low_enough =
      std::max<size_t>({static_cast<size_t>(std::max(1, min_samples / 2)), enough / 2, samples_m.size() / 10});
  auto rank = [&](double x) {  // Samples ≤ x.
    return static_cast<size_t>(std::upper_bound(samples_m.begin(), samples_m.end(), x) - samples_m.begin());
  };
  for (size_t lo = 0; lo < best_lo; ++lo) {
    const size_t hi = window_from(lo);
    if (hi - lo < low_enough || hi > best_lo) continue;
    const double a = samples_m[lo], b = samples_m[hi - 1], width = std::max(0.02, 0.01 * a);
    const size_t beside = (lo - rank(a - width)) + (rank(b + width) - hi);
    if (3 * beside > hi - lo) continue;
    best_lo = lo, best_hi = hi;
    break;
  }
  const double centre = 0.5 * (samples_m[best_lo] + samples_m[best_hi - 1]);
  const double half = 2 * std::max(0.02, 0.01 * centre);
  std::vector<double> near;
  for (double x : samples_m) {
    if (std::abs(x - centre) <= half) near.push_back(x);
  }
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  CeilingHeight out;
  out.height_m = median(near);
  std::vector<double> dev;
  for (double x : near) dev.push_back(std::abs(x - out.height_m));
  // σ of the median: 1.4826·MAD/√n, floored (the samples share a rig height),
  // n at most kIndependentCeilingSamples.
  out.sigma_m = std::max(
      0.002, 1.4826 * median(dev) / std::sqrt(std::min(kIndependentCeilingSamples, static_cast<double>(near.size()))));
  out.samples = static_cast<int>(near.size());
  return out;
}

namespace {

// The frames taken from the same spot as a contact point's own frame (a
// camera within 0.3 m of it; a rig turned in place keeps them within one
// baseline), each with the pixel where it sees the point, when it does:
// `visit(frame, u, v, point_in_camera)`, u the column (in range), v the row.
template <typename Visit>
void ForFramesSeeingFromTheSameSpot(const ClassPoint& p, const std::vector<PendingContacts::TopEdge>& frames,
                                    double min_depth_m, Visit&& visit) {
  constexpr double kSameSpotM = 0.3;
  const auto own =
      std::find_if(frames.begin(), frames.end(), [&](const PendingContacts::TopEdge& e) { return e.frame == p.frame; });
  if (own == frames.end()) return;
  const Vec3 own_origin = own->world_from_camera.translation();
  for (const PendingContacts::TopEdge& e : frames) {
    if ((e.world_from_camera.translation() - own_origin).head<2>().norm() > kSameSpotM) continue;
    const Vec3 in_cam = e.world_from_camera.inverse() * p.position_m;
    if (!(in_cam.z() >= min_depth_m)) continue;
    const std::optional<Vec2> px = ProjectFromCamera(e.camera, in_cam);
    if (!px) continue;
    const long u = std::lround(px->x());
    if (u < 0 || u >= static_cast<long>(e.wall_to_row.size())) continue;
    visit(e, static_cast<int>(u), px->y(), in_cam);
  }
}

// Rows of slack when a frame's top edge is compared with a point's row.
constexpr int kTopEdgeRowMargin = 3;

// The least height a topped floor contact's wall must have: the most that
// any frame taken from the same spot shows, where that frame's column
// through the contact is wall from its top edge down to within 3 rows of it.
double ToppedHeight(const PendingContacts::ToppedFloor& f, const std::vector<PendingContacts::TopEdge>& frames,
                    double min_depth_m) {
  double height = f.min_height_m;
  ForFramesSeeingFromTheSameSpot(
      f.point, frames, min_depth_m, [&](const PendingContacts::TopEdge& e, int u, double v, const Vec3& in_cam) {
        if (e.wall_to_row[u] < v - kTopEdgeRowMargin) return;
        height =
            std::max(height, e.world_from_camera.translation().z() + in_cam.z() * (e.camera.cy + 0.5) / e.camera.fy);
      });
  return height;
}

// Whether another frame taken from the same spot contradicts a ceiling
// contact: its column through the contact's point shows wall (or openings)
// from the image's top edge down past that point, so the wall rises above
// where this frame's label edge put the ceiling. A segmenter that takes a
// near wall's shadowed top for ceiling puts a "ceiling edge" there, which
// the ceiling's height places metres beyond the wall (bench_rooms seed 28:
// a door 1.2 m away, 86 ceiling contacts 2.8 m away); the frames beside it
// see that wall up to their top edge.
bool CeilingEdgeContradicted(const ClassPoint& p, const std::vector<PendingContacts::TopEdge>& frames,
                             double min_depth_m) {
  bool contradicted = false;
  ForFramesSeeingFromTheSameSpot(p, frames, min_depth_m,
                                 [&](const PendingContacts::TopEdge& e, int u, double v, const Vec3&) {
                                   if (e.frame == p.frame || v < kTopEdgeRowMargin) return;
                                   contradicted |= e.wall_to_row[u] >= v + kTopEdgeRowMargin;
                                 });
  return contradicted;
}

}  // namespace

void PendingContacts::Append(PendingContacts&& other) {
  ceiling_rays.insert(ceiling_rays.end(), other.ceiling_rays.begin(), other.ceiling_rays.end());
  ceiling_boundaries.insert(ceiling_boundaries.end(), other.ceiling_boundaries.begin(), other.ceiling_boundaries.end());
  paired_floor.insert(paired_floor.end(), other.paired_floor.begin(), other.paired_floor.end());
  topped_floor.insert(topped_floor.end(), other.topped_floor.begin(), other.topped_floor.end());
  top_edges.insert(top_edges.end(), other.top_edges.begin(), other.top_edges.end());
  stereo_samples_m.insert(stereo_samples_m.end(), other.stereo_samples_m.begin(), other.stereo_samples_m.end());
  skirting.insert(skirting.end(), other.skirting.begin(), other.skirting.end());
  other = {};
}

std::optional<double> PendingContacts::MoveFeetBehindSkirting(double depth_m, std::vector<ClassPoint>* points) {
  if (!(depth_m > 0) || std::all_of(skirting.begin(), skirting.end(), [](const auto& e) { return e.moved; })) {
    return std::nullopt;
  }
  SkirtingEvidence all;
  for (const SkirtingEvidence& e : skirting) {
    all.feet += e.feet;
    for (int b = 0; b < SkirtingEvidence::kBins; ++b) {
      all.sum[b] += e.sum[b];
      all.sum_sq[b] += e.sum_sq[b];
      all.count[b] += e.count[b];
    }
  }
  const std::optional<double> top = PooledSkirtingTop(all, /*capture_wide=*/true);
  if (!top) return std::nullopt;
  // Every wall foot once, sorted into the frames that still have to move.
  std::vector<ClassPoint*> all_feet;
  std::vector<double*> all_samples;
  GatherWallFeet(*points, 0, *this, 0, 0, &all_feet, &all_samples);
  std::map<int, std::pair<std::vector<ClassPoint*>, std::vector<double*>>> by_frame;
  for (const SkirtingEvidence& e : skirting) {
    if (!e.moved) by_frame[e.frame];
  }
  for (std::size_t i = 0; i < all_feet.size(); ++i) {
    const auto it = by_frame.find(all_feet[i]->frame);
    if (it == by_frame.end()) continue;
    it->second.first.push_back(all_feet[i]);
    it->second.second.push_back(all_samples[i]);
  }
  for (SkirtingEvidence& e : skirting) {
    if (e.moved) continue;
    const auto& [feet, samples] = by_frame[e.frame];
    MoveWallFeetBehindSkirting(depth_m, e.world_from_cam, e.camera, feet, samples, nullptr);
    e.moved = true;
  }
  return top;
}

ResolvedContacts PendingContacts::Resolve(const FramePointsOptions& options) const {
  ResolvedContacts out;
  if (options.ceiling_height_m) {
    out.ceiling = CeilingHeight{.height_m = *options.ceiling_height_m, .sigma_m = 0.0, .samples = 0};
    out.how = "given";
  } else {
    std::vector<double> samples;
    for (const PairedFloor& f : paired_floor) samples.push_back(f.ceiling_sample_m);
    // The walls' stereo depth under the ceiling edges gives rough heights of
    // its own, blind to what hides the wall bases. Where the paired estimate
    // lies outside their middle half, the pairs took some top for the floor
    // throughout: only the pairs inside that range are used, or, when they
    // form no cluster, the stereo heights' median (bench_rooms seed 22 with
    // the shipped model: pairs 3.406 m from a table's top, stereo 2.763–
    // 2.909 m, median 2.818 m, truth 2.785 m; in 27 other rooms the pairs'
    // estimate lies inside the stereo range).
    std::optional<std::pair<double, double>> stereo_range;  // Quartiles.
    std::vector<double> stereo = stereo_samples_m;
    std::erase_if(stereo, [](double x) { return !std::isfinite(x) || x <= 0; });
    std::sort(stereo.begin(), stereo.end());
    if (stereo.size() >= kMinStereoCeilingSamples) {
      stereo_range = std::pair{stereo[stereo.size() / 4], stereo[3 * stereo.size() / 4]};
    }
    const auto inside = [&](double x) { return x >= stereo_range->first && x <= stereo_range->second; };
    if ((out.ceiling = CeilingHeightFromSamples(samples)) && (!stereo_range || inside(out.ceiling->height_m))) {
      out.how = fmt::format("from {} of {} columns that saw a wall's floor and ceiling edges", out.ceiling->samples,
                            samples.size());
    } else if (out.ceiling) {
      const double rejected = out.ceiling->height_m;
      std::vector<double> kept;
      std::copy_if(samples.begin(), samples.end(), std::back_inserter(kept), inside);
      if ((out.ceiling = CeilingHeightFromSamples(kept))) {
        out.how = fmt::format(
            "from {} of {} columns that saw a wall's floor and "
            "ceiling edges, within the walls' stereo heights "
            "{:.2f}–{:.2f} m (the densest cluster, {:.3f} m, lay "
            "outside them: tops taken for wall bases)",
            out.ceiling->samples, samples.size(), stereo_range->first, stereo_range->second, rejected);
      } else {
        const double median = stereo[stereo.size() / 2];
        // σ of the median: 1.2533·σ/√n, n at most kIndependentCeilingSamples
        // (thousands of stereo heights, a few walls' matcher errors).
        const double sigma = (stereo_range->second - stereo_range->first) / 1.349;
        const double independent = std::min(kIndependentCeilingSamples, static_cast<double>(stereo.size()));
        out.ceiling = CeilingHeight{.height_m = median,
                                    .sigma_m = std::max(0.002, 1.2533 * sigma / std::sqrt(independent)),
                                    .samples = static_cast<int>(stereo.size())};
        out.how = fmt::format(
            "the median of the walls' stereo heights under {} "
            "ceiling edges: the {} columns that saw a wall's floor "
            "and ceiling edges gave {:.3f} m, outside the stereo's "
            "{:.2f}–{:.2f} m (tops taken for wall bases)",
            stereo.size(), samples.size(), rejected, stereo_range->first, stereo_range->second);
      }
    } else if ((out.ceiling = CeilingHeightFromSamples(stereo_samples_m, kMinStereoCeilingSamples))) {
      out.how = fmt::format(
          "from the walls' stereo depth under {} ceiling "
          "edges (only {} columns saw both edges)",
          out.ceiling->samples, samples.size());
    }
  }
  for (const PairedFloor& f : paired_floor) {
    out.ceiling_samples.push_back({f.point.position_m, f.point.frame, f.ceiling_sample_m});
    const bool agrees =
        !out.ceiling || std::abs(f.ceiling_sample_m - out.ceiling->height_m) <= std::max(0.03, 3 * f.sample_sigma_m);
    if (agrees) {
      out.points.push_back(f.point);
    } else {
      ++out.floor_rejected;
    }
  }
  for (const ToppedFloor& f : topped_floor) {
    if (out.ceiling &&
        ToppedHeight(f, top_edges, options.min_depth_m) > out.ceiling->height_m + std::max(0.05, 3 * f.sigma_m)) {
      ++out.floor_rejected;
    } else {
      out.points.push_back(f.point);
    }
  }
  if (out.ceiling) {
    auto ceiling_points = CeilingContactPoints(ceiling_rays, *out.ceiling, options);
    const auto contradicted = [&](const ClassPoint& p) {
      return CeilingEdgeContradicted(p, top_edges, options.min_depth_m);
    };
    const auto kept = std::partition(ceiling_points.begin(), ceiling_points.end(), std::not_fn(contradicted));
    out.ceiling_rejected = static_cast<int>(ceiling_points.end() - kept);
    out.points.insert(out.points.end(), ceiling_points.begin(), kept);
    const double sigma_h = std::hypot(options.camera_height_sigma_m, out.ceiling->sigma_m);
    for (const CeilingBoundary& b : ceiling_boundaries) {
      const double dh = out.ceiling->height_m - b.edge.origin_m.z();
      if (!(dh > 0.05) || !(b.wall_rise > 1e-9)) continue;
      const double z = dh / b.wall_rise;  // The wall's camera depth in the edge's column.
      if (z < options.min_depth_m || z > options.max_depth_m) continue;
      out.points.push_back({b.edge.label, b.edge.origin_m + b.edge.direction * z,
                            ContactSigma(z, dh, b.edge.fy_px, options.contact_sigma_px, sigma_h), b.source,
                            b.edge.frame});
      ++out.ceiling_boundary_points;
    }
  } else {
    out.ceiling_unused = static_cast<int>(ceiling_rays.size());
  }
  return out;
}

std::vector<ClassPoint> CeilingContactPoints(const std::vector<ContactRay>& rays, const CeilingHeight& ceiling,
                                             const FramePointsOptions& options) {
  std::vector<ClassPoint> out;
  for (const ContactRay& r : rays) {
    const double dh = ceiling.height_m - r.origin_m.z();
    if (!(dh > 0.05) || !(r.direction.z() > 1e-9)) continue;
    const double z = dh / r.direction.z();  // Camera depth: the ray's camera z is 1.
    if (z < options.min_depth_m || z > options.max_depth_m) continue;
    Vec3 p = r.origin_m + r.direction * z;
    p.z() = ceiling.height_m;
    const double sigma_h = std::hypot(options.camera_height_sigma_m, ceiling.sigma_m);
    out.push_back(
        {r.label, p, ContactSigma(z, dh, r.fy_px, options.contact_sigma_px, sigma_h), PointSource::kContact, r.frame});
  }
  return out;
}

}  // namespace asbuilt
