#include "asbuilt/stereo/frame_points.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <cmath>
#include <iterator>
#include <numeric>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/imageio/image_io.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

// Stereo heights under ceiling edges (PendingContacts::stereo_samples_m)
// needed to estimate the ceiling, or to check the paired estimate.
constexpr size_t kMinStereoCeilingSamples = 200;

bool IsComponent(unsigned char label) { return label >= 1 && label <= 3; }

// Median of the valid disparities in a (2r+1)² window; NaN if fewer than 3.
double GuideDisparity(const cv::Mat& disparity, const Vec2& px, int r) {
  const int cu = static_cast<int>(std::lround(px.x())), cv_ = static_cast<int>(std::lround(px.y()));
  std::vector<float> v;
  for (int y = std::max(0, cv_ - r); y <= std::min(disparity.rows - 1, cv_ + r); ++y) {
    const float* d = disparity.ptr<float>(y);
    for (int x = std::max(0, cu - r); x <= std::min(disparity.cols - 1, cu + r); ++x) {
      if (std::isfinite(d[x])) v.push_back(d[x]);
    }
  }
  if (v.size() < 3) return NAN;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Median valid disparity over the pixels of `label` within radius r; NaN if
// fewer than 5.
double ClassDisparity(const cv::Mat& disparity, const cv::Mat& labels, const Vec2& px, unsigned char label,
                      int r) {
  const int cu = static_cast<int>(std::lround(px.x())), cv_ = static_cast<int>(std::lround(px.y()));
  std::vector<float> v;
  for (int y = std::max(0, cv_ - r); y <= std::min(disparity.rows - 1, cv_ + r); ++y) {
    const float* d = disparity.ptr<float>(y);
    const unsigned char* l = labels.ptr<unsigned char>(y);
    for (int x = std::max(0, cu - r); x <= std::min(disparity.cols - 1, cu + r); ++x) {
      if (l[x] == label && std::isfinite(d[x])) v.push_back(d[x]);
    }
  }
  if (v.size() < 5) return NAN;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

bool RightLabelAgrees(const cv::Mat& labels_right, const Vec2& right_px, unsigned char label, int radius) {
  if (labels_right.empty()) return true;
  const int cu = static_cast<int>(std::lround(right_px.x())), cv_ = static_cast<int>(std::lround(right_px.y()));
  for (int y = std::max(0, cv_ - radius); y <= std::min(labels_right.rows - 1, cv_ + radius); ++y) {
    for (int x = std::max(0, cu - radius); x <= std::min(labels_right.cols - 1, cu + radius); ++x) {
      if (labels_right.at<unsigned char>(y, x) == label) return true;
    }
  }
  return false;
}

// Whether the label edge between columns u_wall (wall) and u_open (class c)
// of row v continues straight up and down for `rows` rows: each of those rows
// has the same wall → c transition within one pixel of it.
bool VerticalEdge(const cv::Mat& labels, int v, int u_wall, int u_open, unsigned char c, int rows) {
  for (int y = v - rows; y <= v + rows; ++y) {
    if (y == v) continue;
    if (y < 0 || y >= labels.rows) return false;
    const unsigned char* l = labels.ptr<unsigned char>(y);
    bool found = false;
    for (int shift = -1; shift <= 1 && !found; ++shift) {
      const int w = u_wall + shift, o = u_open + shift;
      if (std::min(w, o) < 0 || std::max(w, o) >= labels.cols) continue;
      found = l[w] == 1 && l[o] == c;
    }
    if (!found) return false;
  }
  return true;
}

cv::Mat ToGray8(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat gray;
  cv::cvtColor(image, gray, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return gray;
}

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

// The contact cue (frame_points.h). Per column: the lowest clean
// wall/door → background transition below the horizon is the floor contact
// (unless the floor's disparity below it says something nearer stands there);
// the highest clean background → wall transition above the horizon is the
// ceiling contact. Label edges lie halfway between pixel centres.
//
// `covered` (CV_8U, zeros on entry) marks the pixels of each contacted
// column's wall run (from the contact along the labelled structure): a level
// camera sees a vertical wall at one depth down a column, so the contact
// already places them, exactly; their stereo points add only noise.
// `floor_columns` receives each floor contact's column, row and depth.
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
  const auto near = std::count_if(heights.begin(), heights.end(), [&](double s) { return std::abs(s - median) <= 0.015; });
  if (3 * near < 2 * static_cast<long>(heights.size())) return false;
  *height_m = median;
  return true;
}

// Moves the wall floor contacts this frame added (from the given indices
// on) `depth_m` back from the camera, along the wall's normal there (from
// the contacts 2 columns either side), and rescales their ceiling samples:
// the wall's face stands behind the skirting's foot.
void MoveWallFeetBehindSkirting(double depth_m, const Eigen::Isometry3d& world_from_cam, const PinholeCamera& cam,
                                std::size_t first_point, std::size_t first_paired, std::size_t first_topped,
                                FramePointsResult* result, std::vector<FloorColumn>* floor_columns) {
  // This frame's wall feet in column order, wherever they were filed.
  std::vector<ClassPoint*> feet;
  std::vector<double*> samples;  // The paired ceiling sample of each foot, or null.
  for (std::size_t i = first_point; i < result->points.size(); ++i) {
    ClassPoint& p = result->points[i];
    if (p.source == PointSource::kContact && p.label == LabelClass::kWall && p.position_m.z() == 0.0) {
      feet.push_back(&p), samples.push_back(nullptr);
    }
  }
  for (std::size_t i = first_paired; i < result->contacts.paired_floor.size(); ++i) {
    auto& pf = result->contacts.paired_floor[i];
    if (pf.point.label == LabelClass::kWall) feet.push_back(&pf.point), samples.push_back(&pf.ceiling_sample_m);
  }
  for (std::size_t i = first_topped; i < result->contacts.topped_floor.size(); ++i) {
    auto& tf = result->contacts.topped_floor[i];
    if (tf.point.label == LabelClass::kWall) feet.push_back(&tf.point), samples.push_back(nullptr);
  }
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
  if (feet.empty()) return;
  for (FloorColumn& c : *floor_columns) {
    if (c.label != 1) continue;
    const double b = (c.u - cam.cx) / cam.fx;
    const auto nearest = std::min_element(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
      return std::abs(bearing[x] - b) < std::abs(bearing[y] - b);
    });
    c.depth_m *= ratio[*nearest];
  }
}

void AddContactPoints(const StereoFrame& frame, const FramePointsOptions& options,
                      const Eigen::Isometry3d& world_from_cam, FramePointsResult* result, cv::Mat* covered,
                      std::vector<FloorColumn>* floor_columns) {
  const cv::Mat& labels = frame.labels_left;
  const cv::Mat& disparity = result->disparity.disparity_px;
  const PinholeCamera& cam = frame.camera;
  const double h = world_from_cam.translation().z();  // Camera height above the floor (z = 0).
  if (!(h > 0.05)) return;                             // No usable height: no contacts.
  const int rows = labels.rows, cols = labels.cols, run = options.contact_min_run_px;
  const double fxb = cam.fx * frame.baseline_m;
  const cv::Mat steps =
      options.contact_snap_px.value_or(0) > 0 || options.skirting_depth_m > 0 ? VerticalSteps(frame.left) : cv::Mat();
  const std::size_t first_point = result->points.size(), first_paired = result->contacts.paired_floor.size(),
                    first_topped = result->contacts.topped_floor.size();
  std::vector<double> skirting_heights;  // Per wall foot: the step above it, in metres above the floor.
  int wall_feet = 0;
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
  auto is_background = [](unsigned char l) { return l == 0; };
  const Mat3 rot = world_from_cam.linear();
  const Vec3 origin = world_from_cam.translation();
  auto ray = [&](double u, double v) { return Vec3(rot * UnprojectToCamera(cam, Vec2(u, v), 1.0)); };
  // Marks the structure run from row v0 in direction dir (±1) in columns u…u+step−1.
  auto cover = [&](int u, int v0, int dir) {
    for (int v = v0; v >= 0 && v < rows && IsComponent(label_at(v, u)); v += dir) {
      for (int x = u; x < std::min(cols, u + options.contact_col_step_px); ++x) covered->at<unsigned char>(v, x) = 1;
    }
  };

  // This frame's top edge, for every frame's topped floor contacts (Resolve).
  PendingContacts::TopEdge top{.frame = frame.index, .world_from_camera = world_from_cam, .camera = cam};
  top.wall_to_row.assign(cols, -1);
  for (int u = 0; u < cols; ++u) {
    int v = 0;
    while (v < rows && IsComponent(label_at(v, u))) ++v;
    top.wall_to_row[u] = v - 1;
  }
  result->contacts.top_edges.push_back(std::move(top));

  for (int u = 0; u < cols; u += options.contact_col_step_px) {
    // Floor: scan up from the bottom for the lowest wall/door → background
    // edge (not snapped: docs/stereo.md, "Option notes", says why).
    double floor_row = NAN;
    unsigned char floor_label = 0;
    for (int v = rows - 1 - run; v >= run; --v) {
      if (v + 0.5 <= cam.cy + 1.0) break;  // At or above the horizon: not the floor.
      const unsigned char a = label_at(v, u);
      if ((a != 1 && a != 2) || label_at(v + 1, u) != 0) continue;
      if (!runs(v, -1, run, [a](unsigned char l) { return l == a; }, u) || !runs(v + 1, 1, run, is_background, u)) {
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
          if (l[x] == 0 && std::isfinite(d[x])) excess.push_back(static_cast<float>(d[x] - predicted));
        }
      }
      if (excess.size() >= 5) {
        std::nth_element(excess.begin(), excess.begin() + excess.size() / 2, excess.end());
        const double predicted = fxb * (v + 0.5 - cam.cy) / (cam.fy * h);
        if (excess[excess.size() / 2] > std::max(options.contact_floor_tolerance_px, 0.15 * predicted)) {
          ++result->cues.floor_rejected;
          break;  // Occluded base: nothing lower in this column is the wall's.
        }
      }
      floor_row = v + 0.5;
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
        ++result->cues.floor_contacts;
        floor_columns->push_back({u, floor_row, z, floor_label});
        if (floor_label == 1 && !steps.empty()) {
          ++wall_feet;
          if (const auto s = SkirtingTop(steps, u, floor_row, z, h, cam, options.contact_snap_min_step)) {
            skirting_heights.push_back(*s);
          }
        }
        cover(u, static_cast<int>(floor_row - 0.5), -1);
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
      if (!runs(v - 1, -1, run, is_background, u) || !runs(v, 1, run, [](unsigned char l) { return l == 1; }, u)) {
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
      for (int v = static_cast<int>(ceiling_edge + 0.5); v <= static_cast<int>(floor_row - 0.5) && paired; ++v) {
        paired = IsComponent(label_at(v, u));
      }
    }
    if (paired) {
      const double below = floor_row - cam.cy, above = cam.cy - ceiling_row;
      const double sample = h + h * above / below;
      const double sigma = options.contact_sigma_px * std::hypot(h / below, h * above / (below * below));
      result->contacts.paired_floor.push_back({*floor_point, sample, sigma});
    } else if (floor_point) {
      // Wall (or openings) from the image's top edge down to the contact.
      if (result->contacts.top_edges.back().wall_to_row[u] >= static_cast<int>(floor_row - 0.5)) {
        // The image's top edge (row −0.5) still shows the wall at depth z.
        const double z = cam.fy * h / (floor_row - cam.cy);
        const double rise = (cam.cy + 0.5) / cam.fy;
        result->contacts.topped_floor.push_back({*floor_point, h + z * rise, floor_point->sigma_m * rise});
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
          if (l[x] == 1 && std::isfinite(d[x]) && d[x] > 0) ds.push_back(d[x]);
        }
      }
      if (ds.size() >= 5) {
        std::nth_element(ds.begin(), ds.begin() + ds.size() / 2, ds.end());
        const double z = fxb / ds[ds.size() / 2];
        result->contacts.stereo_samples_m.push_back(h + z * (cam.cy - ceiling_row) / cam.fy);
      }
    }
    ContactRay r{.label = LabelClass::kWall, .origin_m = origin, .direction = ray(u, ceiling_row),
                 .fy_px = cam.fy, .frame = frame.index};
    ++result->cues.ceiling_contacts;
    cover(u, static_cast<int>(ceiling_edge + 0.5), 1);
    result->contacts.ceiling_rays.push_back(r);
  }
  if (options.skirting_depth_m > 0 && SkirtingSeen(skirting_heights, wall_feet, &result->cues.skirting_height_m)) {
    MoveWallFeetBehindSkirting(options.skirting_depth_m, world_from_cam, cam, first_point, first_paired, first_topped,
                               result, floor_columns);
  }
}

// The stereo check (FramePointsOptions::contacts): a level camera sees a
// vertical wall at one depth down each image column, so a wall's valid
// disparities down a column should agree with their median. Textured walls
// do (0.87–0.99 of pixels on the benchmark rooms); on plain paint SGBM
// matches noise and they scatter (0.30–0.42). Counts the wall pixels of
// columns with at least kMinRun of them, and those within max(tolerance,
// 3 %) of their column's median (cues.stereo_checked/agreed).
void CheckWallStereo(const StereoFrame& frame, const FramePointsOptions& options, const DisparityResult& disparity,
                     FrameCues* cues) {
  constexpr int kMinRun = 20;
  const cv::Mat& labels = frame.labels_left;
  std::vector<float> column;
  for (int u = 0; u < labels.cols; u += options.contact_col_step_px) {
    column.clear();
    for (int v = 0; v < labels.rows; ++v) {
      const float d = disparity.disparity_px.at<float>(v, u);
      if (labels.at<unsigned char>(v, u) == 1 && disparity.valid.at<unsigned char>(v, u) && std::isfinite(d)) {
        column.push_back(d);
      }
    }
    if (column.size() < kMinRun) continue;
    std::vector<float> sorted = column;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double median = sorted[sorted.size() / 2];
    const double tolerance = std::max(options.stereo_check_tolerance_px, 0.03 * median);
    cues->stereo_checked += static_cast<int>(column.size());
    for (float d : column) cues->stereo_agreed += std::abs(d - median) <= tolerance;
  }
}

}  // namespace

const char* ContactUseName(ContactUse use) {
  switch (use) {
    case ContactUse::kOff:
      return "off";
    case ContactUse::kWhereStereoFails:
      return "auto";
    case ContactUse::kAlways:
      return "always";
  }
  return "?";
}

ContactUse ParseContactUse(const std::string& name) {
  for (ContactUse use : {ContactUse::kOff, ContactUse::kWhereStereoFails, ContactUse::kAlways}) {
    if (name == ContactUseName(use)) return use;
  }
  throw InvalidArgument(fmt::format("contacts = \"{}\": must be off, auto or always", name));
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
  const size_t low_enough = std::max<size_t>({static_cast<size_t>(std::max(1, min_samples / 2)), enough / 2,
                                              samples_m.size() / 10});
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
  // σ of the median: 1.4826·MAD/√n, floored (the samples share a rig height).
  // Samples of one frame's neighbouring columns share its label edges' errors:
  // count at most two per frame of a 12-frame turn as independent.
  out.sigma_m =
      std::max(0.002, 1.4826 * median(dev) / std::sqrt(std::min(24.0, static_cast<double>(near.size()))));
  out.samples = static_cast<int>(near.size());
  return out;
}

// The frames taken from the same spot as a contact point's own frame (a
// camera within 0.3 m of it; a rig turned in place keeps them within one
// baseline), each with the pixel where it sees the point, when it does:
// `visit(frame, u, v, point_in_camera)`, u the column (in range), v the row.
template <typename Visit>
void ForFramesSeeingFromTheSameSpot(const ClassPoint& p, const std::vector<PendingContacts::TopEdge>& frames,
                                    double min_depth_m, Visit&& visit) {
  constexpr double kSameSpotM = 0.3;
  const auto own = std::find_if(frames.begin(), frames.end(),
                                [&](const PendingContacts::TopEdge& e) { return e.frame == p.frame; });
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
  ForFramesSeeingFromTheSameSpot(f.point, frames, min_depth_m,
                                 [&](const PendingContacts::TopEdge& e, int u, double v, const Vec3& in_cam) {
                                   if (e.wall_to_row[u] < v - kTopEdgeRowMargin) return;
                                   height = std::max(height, e.world_from_camera.translation().z() +
                                                                 in_cam.z() * (e.camera.cy + 0.5) / e.camera.fy);
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

void PendingContacts::Append(PendingContacts&& other) {
  ceiling_rays.insert(ceiling_rays.end(), other.ceiling_rays.begin(), other.ceiling_rays.end());
  paired_floor.insert(paired_floor.end(), other.paired_floor.begin(), other.paired_floor.end());
  topped_floor.insert(topped_floor.end(), other.topped_floor.begin(), other.topped_floor.end());
  top_edges.insert(top_edges.end(), other.top_edges.begin(), other.top_edges.end());
  stereo_samples_m.insert(stereo_samples_m.end(), other.stereo_samples_m.begin(), other.stereo_samples_m.end());
  other = {};
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
            "from {} of {} columns that saw a wall's floor and ceiling edges, within the walls' stereo heights "
            "{:.2f}–{:.2f} m (the densest cluster, {:.3f} m, lay outside them: tops taken for wall bases)",
            out.ceiling->samples, samples.size(), stereo_range->first, stereo_range->second, rejected);
      } else {
        const double median = stereo[stereo.size() / 2];
        const double sigma = (stereo_range->second - stereo_range->first) / 1.349;
        out.ceiling = CeilingHeight{.height_m = median,
                                    .sigma_m = std::max(0.002, 1.2533 * sigma / std::sqrt(double(stereo.size()))),
                                    .samples = static_cast<int>(stereo.size())};
        out.how = fmt::format(
            "the median of the walls' stereo heights under {} ceiling edges: the {} columns that saw a wall's floor "
            "and ceiling edges gave {:.3f} m, outside the stereo's {:.2f}–{:.2f} m (tops taken for wall bases)",
            stereo.size(), samples.size(), rejected, stereo_range->first, stereo_range->second);
      }
    } else if ((out.ceiling = CeilingHeightFromSamples(stereo_samples_m, kMinStereoCeilingSamples))) {
      out.how = fmt::format("from the walls' stereo depth under {} ceiling edges (only {} columns saw both edges)",
                            out.ceiling->samples, samples.size());
    }
  }
  for (const PairedFloor& f : paired_floor) {
    const bool agrees =
        !out.ceiling ||
        std::abs(f.ceiling_sample_m - out.ceiling->height_m) <= std::max(0.03, 3 * f.sample_sigma_m);
    if (agrees) {
      out.points.push_back(f.point);
    } else {
      ++out.floor_rejected;
    }
  }
  for (const ToppedFloor& f : topped_floor) {
    if (out.ceiling && ToppedHeight(f, top_edges, options.min_depth_m) >
                           out.ceiling->height_m + std::max(0.05, 3 * f.sigma_m)) {
      ++out.floor_rejected;
    } else {
      out.points.push_back(f.point);
    }
  }
  if (out.ceiling) {
    auto ceiling_points = CeilingContactPoints(ceiling_rays, *out.ceiling, options);
    const auto contradicted = [&](const ClassPoint& p) { return CeilingEdgeContradicted(p, top_edges, options.min_depth_m); };
    const auto kept = std::partition(ceiling_points.begin(), ceiling_points.end(), std::not_fn(contradicted));
    out.ceiling_rejected = static_cast<int>(ceiling_points.end() - kept);
    out.points.insert(out.points.end(), ceiling_points.begin(), kept);
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
    out.push_back({r.label, p, ContactSigma(z, dh, r.fy_px, options.contact_sigma_px, sigma_h),
                   PointSource::kContact, r.frame});
  }
  return out;
}

void FramePointsOptions::Check() const {
  disparity.Check();
  corners.Check();
  match.Check();
  vertices.Check();
  CheckArgument(vertex_sigma_px > 0, fmt::format("FramePointsOptions.vertex_sigma_px = {}, must be > 0", vertex_sigma_px));
  CheckArgument(dense_stride_px >= 1,
                fmt::format("FramePointsOptions.dense_stride_px = {}, must be >= 1", dense_stride_px));
  CheckArgument(dense_inset_px >= 0,
                fmt::format("FramePointsOptions.dense_inset_px = {}, must be >= 0", dense_inset_px));
  CheckArgument(edge_row_step_px >= 1,
                fmt::format("FramePointsOptions.edge_row_step_px = {}, must be >= 1", edge_row_step_px));
  CheckArgument(edge_min_gradient > 0,
                fmt::format("FramePointsOptions.edge_min_gradient = {}, must be > 0", edge_min_gradient));
  CheckArgument(boundary_row_step_px >= 1,
                fmt::format("FramePointsOptions.boundary_row_step_px = {}, must be >= 1", boundary_row_step_px));
  CheckArgument(boundary_wall_gap_px >= 0 && boundary_wall_span_px >= 1 && boundary_inside_px >= 1,
                fmt::format("FramePointsOptions.boundary_wall_gap_px = {}, boundary_wall_span_px = {}, "
                            "boundary_inside_px = {}: need gap >= 0, span >= 1, inside >= 1",
                            boundary_wall_gap_px, boundary_wall_span_px, boundary_inside_px));
  CheckArgument(boundary_tolerance_px > 0 && boundary_sigma_px > 0,
                fmt::format("FramePointsOptions.boundary_tolerance_px = {}, boundary_sigma_px = {}: must be > 0",
                            boundary_tolerance_px, boundary_sigma_px));
  CheckArgument(guide_radius_px >= 1,
                fmt::format("FramePointsOptions.guide_radius_px = {}, must be >= 1", guide_radius_px));
  CheckArgument(corner_sigma_px > 0 && edge_sigma_px > 0 && dense_sigma_px > 0,
                "FramePointsOptions.*_sigma_px must be > 0");
  CheckArgument(min_depth_m > 0 && max_depth_m > min_depth_m,
                fmt::format("FramePointsOptions.min_depth_m = {}, max_depth_m = {}: need 0 < min < max",
                            min_depth_m, max_depth_m));
  CheckArgument(window_band_px > 0,
                fmt::format("FramePointsOptions.window_band_px = {}, must be > 0", window_band_px));
  CheckArgument(contact_col_step_px >= 1 && contact_min_run_px >= 1 && contact_sigma_px > 0 &&
                    camera_height_sigma_m >= 0 && contact_floor_tolerance_px > 0,
                fmt::format("FramePointsOptions: contact_col_step_px = {}, contact_min_run_px = {}, "
                            "contact_sigma_px = {}, camera_height_sigma_m = {}, contact_floor_tolerance_px = {}: "
                            "need step, run >= 1 and sigmas, tolerance > 0",
                            contact_col_step_px, contact_min_run_px, contact_sigma_px, camera_height_sigma_m,
                            contact_floor_tolerance_px));
  CheckArgument(contact_snap_px.value_or(0) >= 0 && contact_snap_min_step >= 0,
                fmt::format("FramePointsOptions: contact_snap_px = {}, contact_snap_min_step = {}: must be >= 0",
                            contact_snap_px.value_or(0), contact_snap_min_step));
  CheckArgument(skirting_depth_m >= 0 && skirting_depth_m < 0.1,
                fmt::format("FramePointsOptions.skirting_depth_m = {}, must be in [0, 0.1)", skirting_depth_m));
  CheckArgument(stereo_check_tolerance_px > 0 && stereo_check_min_agree >= 0 && stereo_check_min_agree <= 1 &&
                    stereo_check_min_pixels >= 0 && stereo_check_min_contacts >= 0,
                fmt::format("FramePointsOptions: stereo_check_tolerance_px = {}, stereo_check_min_agree = {}, "
                            "stereo_check_min_pixels = {}, stereo_check_min_contacts = {}: need tolerance > 0, "
                            "agree in [0, 1], counts >= 0",
                            stereo_check_tolerance_px, stereo_check_min_agree, stereo_check_min_pixels,
                            stereo_check_min_contacts));
  CheckArgument(!ceiling_height_m || (std::isfinite(*ceiling_height_m) && *ceiling_height_m > 0),
                "FramePointsOptions.ceiling_height_m must be > 0");
  CheckArgument(right_label_radius_px >= 0,
                fmt::format("FramePointsOptions.right_label_radius_px = {}, must be >= 0", right_label_radius_px));
}

std::string FrameCues::CarriedBy() const {
  std::string out;
  auto add = [&](bool on, const char* name) {
    if (!on) return;
    if (!out.empty()) out += '+';
    out += name;
  };
  add(corners_matched > 0, "corner");
  add(edge_points > 0, "edge");
  add(dense_points > 0, "dense");
  add(boundary_points > 0, "boundary");
  add(vertex_points > 0, "vertex");
  add(floor_contacts + ceiling_contacts > 0, "contact");
  return out.empty() ? "none" : out;
}

std::string FrameCues::BriefReport() const {
  return fmt::format(
      "frame {}: corners {}/{}, edges {}/{}, dense {} ({:.0f}% of labelled px consistent), boundary {}, "
      "vertices {}, contacts floor {} (+{} occluded) ceiling {}{} — {}, {:.0f} ms",
      index, corners_matched, corners_found, edge_points, edge_candidates, dense_points, 100.0 * dense_valid_fraction,
      boundary_points, vertex_points, floor_contacts, floor_rejected, ceiling_contacts,
      stereo_checked == 0 ? ""
                          : fmt::format(", wall stereo consistent down its columns at {}/{} px ({:.0f} %)",
                                        stereo_agreed, stereo_checked, 100.0 * stereo_agreed / stereo_checked),
      CarriedBy(), 1000.0 * seconds);
}

namespace {

// One pass over a frame. `contacts`: add contact points (and run the stereo
// check); `wall_stereo`: wall pixels give corner/edge/dense points (outside
// contacted columns) and boundary points take the wall's stereo depth —
// without it they take the contacts'. `disparity`: reuse this one.
FramePointsResult FramePointsPass(const StereoFrame& frame, const FramePointsOptions& options, bool contacts,
                                  bool wall_stereo, const DisparityResult* disparity_given) {
  const auto start = std::chrono::steady_clock::now();
  FramePointsResult result;
  result.cues.index = frame.index;
  const cv::Mat gray_left8 = ToGray8(frame.left), gray_right8 = ToGray8(frame.right);
  cv::Mat gray_left, gray_right;
  gray_left8.convertTo(gray_left, CV_32F);
  gray_right8.convertTo(gray_right, CV_32F);
  result.disparity =
      disparity_given ? *disparity_given : ComputeDisparity(frame.left, frame.right, options.disparity);
  const cv::Mat& disparity = result.disparity.disparity_px;
  const double full_min = result.disparity.min_disparity_px;
  const double full_max = full_min + result.disparity.num_disparities_px - 1;

  const Eigen::Isometry3d world_from_cam = WorldFromCamera(frame.pose, frame.baseline_m, StereoEye::kLeft);
  const double fx = frame.camera.fx;
  // Triangulate (Z = f·B/d, X = (u − cx)·Z/fx, Y = (v − cy)·Z/fy) → world.
  auto add_point = [&](unsigned char label, const Vec2& px, double d, double sigma_d,
                       PointSource source) -> std::optional<Vec3> {
    const std::optional<double> z = DepthFromDisparity(fx, frame.baseline_m, d);
    if (!z || *z < options.min_depth_m || *z > options.max_depth_m) return std::nullopt;
    const Vec3 p = world_from_cam * UnprojectToCamera(frame.camera, px, *z);
    result.points.push_back({static_cast<LabelClass>(label), p,
                             DepthSigmaFromDisparitySigma(fx, frame.baseline_m, *z, sigma_d), source,
                             frame.index});
    return p;
  };
  auto match_guided = [&](const Vec2& px) -> std::optional<RowMatch> {
    const double guide = GuideDisparity(disparity, px, static_cast<int>(std::ceil(options.guide_radius_px)));
    const double lo = std::isfinite(guide) ? guide - options.guide_radius_px : full_min;
    const double hi = std::isfinite(guide) ? guide + options.guide_radius_px : full_max;
    return MatchAlongRow(gray_left, gray_right, px, lo, hi, options.match);
  };

  // Contacts first: wall (door) label edges with the floor below the horizon
  // and with the ceiling above it, cut with those planes (frame_points.h).
  // Wall pixels of contacted columns give no stereo points below.
  cv::Mat covered = cv::Mat::zeros(frame.labels_left.size(), CV_8U);
  // Per column, the wall's disparity from its floor contact (NaN: none) —
  // what boundary points use when the wall's stereo is not kept.
  std::vector<float> contact_disparity(frame.labels_left.cols, NAN);
  if (contacts) {
    std::vector<FloorColumn> floor_columns;
    AddContactPoints(frame, options, world_from_cam, &result, &covered, &floor_columns);
    if (!wall_stereo) CheckWallStereo(frame, options, result.disparity, &result.cues);
    for (const FloorColumn& c : floor_columns) {
      for (int x = c.u; x < std::min(frame.labels_left.cols, c.u + options.contact_col_step_px); ++x) {
        contact_disparity[x] = static_cast<float>(fx * frame.baseline_m / c.depth_m);
      }
    }
  }
  auto explained = [&](const Vec2& px, unsigned char label) {
    if (label != 1) return false;
    if (!wall_stereo) return true;
    const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
    return u >= 0 && v >= 0 && u < covered.cols && v < covered.rows && covered.at<unsigned char>(v, u) != 0;
  };

  // Corners: contour polygons per class, matched along the row.
  if (options.use_corners) {
    const auto corners = FindClassCorners(frame.labels_left, gray_left8, options.corners);
    result.cues.corners_found = static_cast<int>(corners.size());
    for (const ClassCorner& c : corners) {
      if (explained(c.pixel, static_cast<unsigned char>(c.label))) continue;
      const auto m = match_guided(c.pixel);
      if (!m) continue;
      const unsigned char label = static_cast<unsigned char>(c.label);
      // A corner where a nearer object cuts the region (a T-junction) takes
      // the occluder's disparity; the region's own pixels disagree.
      const double own = ClassDisparity(result.disparity.disparity_px, frame.labels_left, c.pixel, label,
                                        2 * options.match.patch_radius_px);
      if (std::isfinite(own) && std::abs(own - m->disparity_px) > options.corner_region_tolerance_px) continue;
      const Vec2 right_px(c.pixel.x() - m->disparity_px, c.pixel.y() + m->row_offset_px);
      if (!RightLabelAgrees(frame.labels_right, right_px, label, options.right_label_radius_px)) continue;
      if (auto p = add_point(label, c.pixel, m->disparity_px, options.corner_sigma_px, PointSource::kCorner)) {
        result.corners.push_back({c, *m, *p});
        ++result.cues.corners_matched;
      }
    }
  }

  // Edges: row maxima of the horizontal gradient inside component regions,
  // away from background (whose edges may be occlusions: furniture).
  if (options.use_edges) {
    cv::Mat gx;
    cv::Sobel(gray_left, gx, CV_32F, 1, 0, 3, 0.25);  // Gray levels per pixel.
    gx = cv::abs(gx);
    const int h = options.match.patch_radius_px;
    // Door/window regions hold the glass and what lies beyond; only their
    // frames (a band along the region border) give edge points.
    cv::Mat band_distance;
    {
      cv::Mat opening = (frame.labels_left == 2) | (frame.labels_left == 3);
      cv::distanceTransform(opening, band_distance, cv::DIST_L2, 3);
    }
    const float opening_band_px = static_cast<float>(options.window_band_px);
    for (int v = h + 2; v < gray_left.rows - h - 2; v += options.edge_row_step_px) {
      const float* g = gx.ptr<float>(v);
      const unsigned char* lab = frame.labels_left.ptr<unsigned char>(v);
      for (int u = h + 2; u < gray_left.cols - h - 2; ++u) {
        if (!IsComponent(lab[u]) || g[u] < options.edge_min_gradient || g[u] < g[u - 1] || g[u] <= g[u + 1]) {
          continue;
        }
        if (explained(Vec2(u, v), lab[u])) continue;
        if (lab[u] != 1 && band_distance.at<float>(v, u) > opening_band_px) continue;
        bool clean = true;
        for (int y = v - 1; y <= v + 1 && clean; ++y) {
          const unsigned char* row = frame.labels_left.ptr<unsigned char>(y);
          for (int x = u - h; x <= u + h; ++x) {
            if (!IsComponent(row[x])) {
              clean = false;
              break;
            }
          }
        }
        if (!clean) continue;
        ++result.cues.edge_candidates;
        const Vec2 px(u, v);
        const auto m = match_guided(px);
        if (!m) continue;
        // The region's own disparity over a window wider than the matcher's
        // foreground fattening: an edge of a nearer object (an open door
        // leaf) must not lend its disparity to the wall behind it.
        const double own = ClassDisparity(result.disparity.disparity_px, frame.labels_left, px, lab[u],
                                          2 * options.match.patch_radius_px);
        if (std::isfinite(own) && std::abs(own - m->disparity_px) > options.corner_region_tolerance_px) continue;
        if (!RightLabelAgrees(frame.labels_right, Vec2(u - m->disparity_px, v + m->row_offset_px), lab[u],
                              options.right_label_radius_px)) {
          continue;
        }
        if (add_point(lab[u], px, m->disparity_px, options.edge_sigma_px, PointSource::kEdge)) {
          ++result.cues.edge_points;
        }
      }
    }
  }

  // Vertices: wall–wall corner columns, placed by their own matches (they
  // need no texture on the walls, nor a contact).
  if (options.use_vertices) {
    for (const WallVertex& wv :
         FindWallVertices(gray_left, gray_right, frame.labels_left, full_min, full_max, options.vertices)) {
      if (add_point(1, Vec2(wv.u_left_px, wv.v_mid_px), wv.disparity_px, options.vertex_sigma_px,
                    PointSource::kVertex)) {
        ++result.cues.vertex_points;
      }
    }
  }

  // Boundaries: where a door/window label meets the wall along a row, the
  // label edge lies halfway between the two pixel centres; it is placed at
  // the wall's depth there, so the opening's edge is measured on the wall
  // surface (the plan then slides it along its viewing ray onto the fitted
  // wall). Casings protrude only 1.5 cm, so near the edge the opening's own
  // depth is the wall's; where it is not, the edge is an occlusion.
  if (options.use_boundaries) {
    const cv::Mat& labels = frame.labels_left;
    const cv::Mat& valid = result.disparity.valid;
    const int rows = labels.rows, cols = labels.cols;
    // Median valid disparity of `label` pixels in rows v ± 2, at columns
    // u0 + dir·k for k in [from, to]; NaN if fewer than 3.
    auto side_disparity = [&](int v, int u0, int dir, int from, int to, unsigned char label) {
      std::vector<float> vals;
      for (int y = std::max(0, v - 2); y <= std::min(rows - 1, v + 2); ++y) {
        const unsigned char* l = labels.ptr<unsigned char>(y);
        const unsigned char* ok = valid.ptr<unsigned char>(y);
        const float* d = disparity.ptr<float>(y);
        for (int k = from; k <= to; ++k) {
          const int x = u0 + dir * k;
          if (x < 0 || x >= cols) break;
          if (l[x] == label && ok[x] && std::isfinite(d[x])) vals.push_back(d[x]);
        }
      }
      if (vals.size() < 3) return static_cast<double>(NAN);
      std::nth_element(vals.begin(), vals.begin() + vals.size() / 2, vals.end());
      return static_cast<double>(vals[vals.size() / 2]);
    };
    // The contact disparity of the wall beside the edge: the median over the
    // contacted columns u0 + dir·k, k in [0, to]; NaN if none.
    auto contact_side = [&](int u0, int dir, int to) {
      std::vector<float> vals;
      for (int k = 0; k <= to; ++k) {
        const int x = u0 + dir * k;
        if (x < 0 || x >= cols) break;
        if (std::isfinite(contact_disparity[x])) vals.push_back(contact_disparity[x]);
      }
      if (vals.empty()) return static_cast<double>(NAN);
      std::nth_element(vals.begin(), vals.begin() + vals.size() / 2, vals.end());
      return static_cast<double>(vals[vals.size() / 2]);
    };
    auto run_of = [&](const unsigned char* row, int u0, int dir, unsigned char label, int n) {
      for (int k = 0; k < n; ++k) {
        const int x = u0 + dir * k;
        if (x < 0 || x >= cols || row[x] != label) return false;
      }
      return true;
    };
    for (int v = 2; v < rows - 2; v += options.boundary_row_step_px) {
      const unsigned char* lab = labels.ptr<unsigned char>(v);
      for (int u = 1; u < cols; ++u) {
        const unsigned char a = lab[u - 1], b = lab[u];
        unsigned char c = 0;
        int u_wall = 0, u_open = 0, to_wall = 0;
        if (a == 1 && (b == 2 || b == 3)) {
          c = b, u_wall = u - 1, u_open = u, to_wall = -1;
        } else if (b == 1 && (a == 2 || a == 3)) {
          c = a, u_wall = u, u_open = u - 1, to_wall = 1;
        } else {
          continue;
        }
        // Both sides a few pixels wide (no label slivers).
        if (!run_of(lab, u_wall, to_wall, 1, 3) || !run_of(lab, u_open, -to_wall, c, 3)) continue;
        // Only the sides of an opening: the cameras are level, so its
        // vertical edges are image columns; a row also crosses the slanted
        // top and bottom edges of an obliquely seen opening.
        if (!VerticalEdge(labels, v, u_wall, u_open, c, options.boundary_vertical_rows)) continue;
        const double d_wall =
            wall_stereo ? side_disparity(v, u_wall, to_wall, options.boundary_wall_gap_px,
                                         options.boundary_wall_gap_px + options.boundary_wall_span_px, 1)
                        : contact_side(u_wall, to_wall, options.boundary_wall_gap_px + options.boundary_wall_span_px);
        if (!std::isfinite(d_wall)) continue;
        // (Without the wall's stereo, the opening's own is no better: no check.)
        if (wall_stereo) {
          const double d_in = side_disparity(v, u_open, -to_wall, 0, options.boundary_inside_px - 1, c);
          if (!std::isfinite(d_in) ||
              std::abs(d_in - d_wall) > std::max(options.boundary_tolerance_px, 0.08 * d_wall)) {
            continue;
          }
        }
        const Vec2 px(u - 0.5, v);
        if (!RightLabelAgrees(frame.labels_right, Vec2(px.x() - d_wall, v), c, options.right_label_radius_px)) {
          continue;
        }
        if (add_point(c, px, d_wall, options.boundary_sigma_px, PointSource::kBoundary)) {
          ++result.cues.boundary_points;
        }
      }
    }
  }

  // Dense: consistent disparities well inside each enabled class region.
  {
    int labelled = 0, consistent = 0;
    for (int v = 0; v < frame.labels_left.rows; ++v) {
      const unsigned char* lab = frame.labels_left.ptr<unsigned char>(v);
      const unsigned char* ok = result.disparity.valid.ptr<unsigned char>(v);
      for (int u = 0; u < frame.labels_left.cols; ++u) {
        if (IsComponent(lab[u])) {
          ++labelled;
          consistent += ok[u] != 0;
        }
      }
    }
    result.cues.dense_valid_fraction = labelled > 0 ? static_cast<double>(consistent) / labelled : NAN;
  }
  if (options.use_dense) {
    const bool enabled[4] = {false, options.dense_wall, options.dense_door, options.dense_window};
    const cv::Mat kernel = cv::getStructuringElement(
        cv::MORPH_RECT, cv::Size(2 * options.dense_inset_px + 1, 2 * options.dense_inset_px + 1));
    for (int c = 1; c <= 3; ++c) {
      if (!enabled[c]) continue;
      cv::Mat mask = frame.labels_left == c;
      if (options.dense_inset_px > 0) cv::erode(mask, mask, kernel);
      if (c == 3) {
        // Windows: only the frame and casing band along the region border;
        // the glass shows the outside.
        cv::Mat distance;
        cv::distanceTransform(frame.labels_left == c, distance, cv::DIST_L2, 3);
        mask &= distance <= options.window_band_px;
      }
      for (int v = 0; v < mask.rows; v += options.dense_stride_px) {
        const unsigned char* m = mask.ptr<unsigned char>(v);
        const unsigned char* ok = result.disparity.valid.ptr<unsigned char>(v);
        const float* d = disparity.ptr<float>(v);
        for (int u = 0; u < mask.cols; u += options.dense_stride_px) {
          if (!m[u] || !ok[u] || !std::isfinite(d[u])) continue;
          if (c == 1 && (!wall_stereo || covered.at<unsigned char>(v, u))) continue;
          if (!RightLabelAgrees(frame.labels_right, Vec2(u - d[u], v), static_cast<unsigned char>(c), 0)) continue;
          if (add_point(static_cast<unsigned char>(c), Vec2(u, v), d[u], options.dense_sigma_px,
                        PointSource::kDense)) {
            ++result.cues.dense_points;
          }
        }
      }
    }
  }
  result.cues.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace

FramePointsResult ComputeFramePoints(const StereoFrame& frame, const FramePointsOptions& options) {
  options.Check();
  frame.camera.Check();
  CheckArgument(!frame.left.empty() && frame.left.size() == frame.right.size() &&
                    frame.left.type() == frame.right.type(),
                "ComputeFramePoints: left and right images must be non-empty, same size and type");
  CheckArgument(frame.labels_left.type() == CV_8UC1 && frame.labels_left.size() == frame.left.size(),
                fmt::format("ComputeFramePoints: frame {}: left labels must be CV_8UC1 of the image size", frame.index));
  CheckArgument(frame.labels_right.empty() ||
                    (frame.labels_right.type() == CV_8UC1 && frame.labels_right.size() == frame.left.size()),
                fmt::format("ComputeFramePoints: frame {}: right labels must be CV_8UC1 of the image size", frame.index));
  CheckArgument(frame.baseline_m > 0, "ComputeFramePoints: baseline_m must be > 0");
  switch (options.contacts) {
    case ContactUse::kOff:
      return FramePointsPass(frame, options, /*contacts=*/false, /*wall_stereo=*/true, nullptr);
    case ContactUse::kAlways:
      return FramePointsPass(frame, options, /*contacts=*/true, /*wall_stereo=*/true, nullptr);
    case ContactUse::kWhereStereoFails:
      break;
  }
  // Both alternatives from one disparity map; the capture decides between
  // them (CapturePoints). Door and window corner, edge and dense points, and
  // vertex points, are
  // the same in both, so the contact pass computes only what differs —
  // contacts, the stereo check, boundaries at the contacts' depth — and
  // takes those from the stereo pass.
  FramePointsResult result = FramePointsPass(frame, options, /*contacts=*/false, /*wall_stereo=*/true, nullptr);
  FramePointsOptions contact_options = options;
  contact_options.use_corners = contact_options.use_edges = contact_options.use_dense = false;
  contact_options.use_vertices = false;  // The same in both: taken from the stereo pass below.
  FramePointsResult with_contacts =
      FramePointsPass(frame, contact_options, /*contacts=*/true, /*wall_stereo=*/false, &result.disparity);
  FrameCues& cues = with_contacts.cues;
  for (const ClassPoint& p : result.points) {
    // Vertex points need neither the wall's stereo nor contacts: both alternatives keep them.
    if (p.source == PointSource::kVertex) {
      with_contacts.points.push_back(p);
      ++cues.vertex_points;
      continue;
    }
    if (p.label == LabelClass::kWall || p.source == PointSource::kBoundary) continue;
    with_contacts.points.push_back(p);
    cues.corners_matched += p.source == PointSource::kCorner;
    cues.edge_points += p.source == PointSource::kEdge;
    cues.dense_points += p.source == PointSource::kDense;
  }
  cues.corners_found = result.cues.corners_found;
  cues.edge_candidates = result.cues.edge_candidates;
  // Each alternative's cues say what it found; both carry the check and the
  // time of both passes.
  const double seconds = result.cues.seconds + cues.seconds;
  result.contact_points = std::move(with_contacts.points);
  result.contacts = std::move(with_contacts.contacts);
  result.cues.stereo_checked = cues.stereo_checked;
  result.cues.stereo_agreed = cues.stereo_agreed;
  result.cues.seconds = seconds;
  result.contact_cues = cues;
  result.contact_cues.seconds = seconds;
  return result;
}

LabelProvider LabelsFromDirectory(const fs::path& dir) {
  return [dir](const CaptureFrame& frame, StereoEye eye) -> cv::Mat {
    const std::string name = fmt::format("{:03d}.png", frame.index);
    if (eye == StereoEye::kLeft) {
      const fs::path path = dir / name;
      if (!fs::exists(path)) {
        throw InputError(path.string(), "", fmt::format("no labels for frame {} (expected {})", frame.index, name));
      }
      return ReadLabelImage(path);
    }
    const fs::path path = dir / "right" / name;
    return fs::exists(path) ? ReadLabelImage(path) : cv::Mat();
  };
}

LabelProvider LabelsFromCapture(const Capture& capture) {
  const fs::path base = capture.base_dir;
  return [base](const CaptureFrame& frame, StereoEye eye) -> cv::Mat {
    if (eye != StereoEye::kLeft) return cv::Mat();
    if (!frame.labels) {
      throw InputError("capture.json", fmt::format("frames[index {}].labels", frame.index),
                       "missing (needed with --use-capture-labels)");
    }
    return ReadLabelImage(base / *frame.labels);
  };
}

StereoFrame LoadStereoFrame(const Capture& capture, const CaptureFrame& frame, const LabelProvider& labels,
                            const StereoRectifier* rectifier) {
  StereoFrame out;
  auto read = [&](const std::string& rel) {
    const fs::path path = capture.Resolve(rel);
    cv::Mat image = cv::imread(path.string(), cv::IMREAD_COLOR);
    if (image.empty()) throw InputError(path.string(), "", "cannot read the image");
    if (image.cols != capture.camera.width || image.rows != capture.camera.height) {
      throw InputError(path.string(), "",
                       fmt::format("image is {}x{}, capture camera is {}x{}", image.cols, image.rows,
                                   capture.camera.width, capture.camera.height));
    }
    return image;
  };
  out.left = read(frame.left);
  out.right = read(frame.right);
  out.labels_left = labels(frame, StereoEye::kLeft);
  out.labels_right = labels(frame, StereoEye::kRight);
  for (const cv::Mat* l : {&out.labels_left, &out.labels_right}) {
    if (!l->empty() && l->size() != out.left.size()) {
      throw InputError(capture.Resolve(frame.left).string(), "labels",
                       fmt::format("frame {}: labels are {}x{}, images {}x{}", frame.index, l->cols, l->rows,
                                   out.left.cols, out.left.rows));
    }
  }
  if (out.labels_left.empty()) {
    throw InputError(capture.Resolve(frame.left).string(), "labels", fmt::format("frame {}: no left labels", frame.index));
  }
  out.camera = capture.camera.Pinhole();
  out.baseline_m = capture.camera.baseline_m;
  out.pose = frame.Pose();
  out.index = frame.index;
  if (!capture.rectified) {
    CheckArgument(rectifier != nullptr, "LoadStereoFrame: an unrectified capture needs a rectifier");
    out.left = RectifyImage(*rectifier, StereoEye::kLeft, out.left);
    out.right = RectifyImage(*rectifier, StereoEye::kRight, out.right);
    out.labels_left = RectifyImage(*rectifier, StereoEye::kLeft, out.labels_left, Interpolation::kNearest);
    if (!out.labels_right.empty()) {
      out.labels_right = RectifyImage(*rectifier, StereoEye::kRight, out.labels_right, Interpolation::kNearest);
    }
    out.camera = rectifier->camera;
    out.baseline_m = rectifier->baseline_m;
  }
  return out;
}

std::string CapturePointsResult::BriefReport() const {
  int by_class[4] = {0, 0, 0, 0}, by_source[6] = {0, 0, 0, 0, 0, 0};
  for (const ClassPoint& p : points) {
    ++by_class[static_cast<int>(p.label) & 3];
    ++by_source[std::min(5, static_cast<int>(p.source))];
  }
  int carried = 0;
  for (const FrameCues& f : frames) carried += f.CarriedBy() != "none";
  return fmt::format(
      "{} frames ({} with points), {} points (wall {}, door {}, window {}; corner {}, edge {}, dense {}, boundary {}, "
      "contact {}){}, {:.1f} s",
      frames.size(), carried, points.size(), by_class[1], by_class[2], by_class[3], by_source[0], by_source[2],
      by_source[1], by_source[4], by_source[5],
      ceiling ? fmt::format(", ceiling {:.3f} ± {:.3f} m", ceiling->height_m, ceiling->sigma_m) : "", seconds);
}

namespace {

// Door and window pixels of a mono frame placed on their wall's plane: a
// level camera sees a vertical wall at one depth down each column, and its
// inverse depth is affine in the column (1/z = a + b·u for any vertical
// plane). The floor contacts give 1/z per column; across an opening's run of
// columns along a row, bordered by wall on both sides, it is interpolated
// linearly between the nearest contact columns on either side (or taken
// from the column's own contact: a window above a wall base). What a stereo
// frame's dense points do for an opening's interior — without them the plan
// sees only the opening's two label edges and no opening between them.
// Every dense_stride_px-th row and column; source kDense, σ of the contacts.
void AddMonoOpeningPoints(const MonoFrame& frame, const FramePointsOptions& options, FramePointsResult* result) {
  const PinholeCamera& cam = frame.camera;
  const double h = frame.pose.position_m.z();
  if (!(h > 0.05)) return;
  const int rows = frame.labels.rows, cols = frame.labels.cols;
  const Mat3 world_from_cam = WorldFromCameraRotation(frame.pose.yaw_rad);
  const Vec3 origin = frame.pose.position_m;
  // Inverse depth per column from every floor contact of this frame.
  std::vector<double> inv_z(cols, NAN), sigma(cols, NAN);
  auto take = [&](const ClassPoint& p) {
    if (p.source != PointSource::kContact || p.frame != frame.index || std::abs(p.position_m.z()) > 1e-6) return;
    const Vec3 q = world_from_cam.transpose() * (p.position_m - origin);
    if (q.z() <= 0) return;
    const int u = static_cast<int>(std::lround(cam.fx * q.x() / q.z() + cam.cx));
    if (u < 0 || u >= cols) return;
    for (int x = u; x < std::min(cols, u + options.contact_col_step_px); ++x) {
      inv_z[x] = 1.0 / q.z();
      sigma[x] = p.sigma_m;
    }
  };
  for (const ClassPoint& p : result->points) take(p);
  for (const auto& f : result->contacts.paired_floor) take(f.point);
  for (const auto& f : result->contacts.topped_floor) take(f.point);
  const int stride = std::max(1, options.dense_stride_px);
  for (int v = 0; v < rows; v += stride) {
    const unsigned char* lab = frame.labels.ptr<unsigned char>(v);
    for (int u0 = 1; u0 < cols - 1; ++u0) {
      const unsigned char c = lab[u0];
      if ((c != 2 && c != 3) || lab[u0 - 1] != 1) continue;
      int u1 = u0;
      while (u1 + 1 < cols && lab[u1 + 1] == c) ++u1;
      if (u1 + 1 >= cols || lab[u1 + 1] != 1) {
        u0 = u1;
        continue;
      }
      // The nearest contact columns beside the run (at most a run's width away).
      const int reach = u1 - u0 + 1;
      int left = -1, right = -1;
      for (int x = u0 - 1; x >= std::max(0, u0 - reach) && left < 0; --x) left = std::isfinite(inv_z[x]) ? x : -1;
      for (int x = u1 + 1; x <= std::min(cols - 1, u1 + reach) && right < 0; ++x) right = std::isfinite(inv_z[x]) ? x : -1;
      for (int u = u0; u <= u1; u += stride) {
        double iz = inv_z[u], s = sigma[u];
        if (!std::isfinite(iz)) {
          if (left < 0 || right < 0) continue;
          const double w = double(u - left) / (right - left);
          iz = (1 - w) * inv_z[left] + w * inv_z[right];
          s = std::max(sigma[left], sigma[right]);
        }
        if (!(iz > 0)) continue;
        const double z = 1.0 / iz;
        if (z < options.min_depth_m || z > options.max_depth_m) continue;
        const Vec3 p = origin + world_from_cam * UnprojectToCamera(cam, Vec2(u, v), z);
        result->points.push_back({static_cast<LabelClass>(c), p, s, PointSource::kDense, frame.index});
        ++result->cues.dense_points;
      }
      u0 = u1;
    }
  }
}

}  // namespace

FramePointsResult ComputeMonoFramePoints(const MonoFrame& frame, const FramePointsOptions& options) {
  options.Check();
  frame.camera.Check();
  CheckArgument(!frame.image.empty() && frame.image.cols == frame.camera.width_px &&
                    frame.image.rows == frame.camera.height_px,
                fmt::format("ComputeMonoFramePoints: frame {}: the image must be non-empty and of the camera's size",
                            frame.index));
  CheckArgument(frame.labels.type() == CV_8UC1 && frame.labels.size() == frame.image.size(),
                fmt::format("ComputeMonoFramePoints: frame {}: labels must be CV_8UC1 of the image size", frame.index));
  // The stereo pass with a nominal 1 m "baseline" whose disparities are all
  // invalid: it then adds contacts and boundaries at the contacts' depth
  // (disparity and depth convert through the same f·B both ways, so B
  // cancels) and nothing that needs a match. The rig centre is moved by
  // half that baseline so the left camera sits at the frame's position.
  constexpr double kNominalBaselineM = 1.0;
  const double yaw = frame.pose.yaw_rad;
  StereoFrame stereo{.left = frame.image, .right = frame.image, .labels_left = frame.labels,
                     .camera = frame.camera, .baseline_m = kNominalBaselineM,
                     .pose = {frame.pose.position_m + 0.5 * kNominalBaselineM * Vec3(std::cos(yaw), std::sin(yaw), 0),
                              yaw},
                     .index = frame.index};
  DisparityResult none;
  none.disparity_px = cv::Mat(frame.labels.size(), CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  none.valid = cv::Mat::zeros(frame.labels.size(), CV_8U);
  none.num_disparities_px = 16;
  FramePointsOptions mono = options;
  mono.use_corners = mono.use_edges = mono.use_dense = mono.use_vertices = false;
  FramePointsResult result = FramePointsPass(stereo, mono, /*contacts=*/true, /*wall_stereo=*/false, &none);
  if (options.use_dense) AddMonoOpeningPoints(frame, options, &result);
  return result;
}

void CapturePoints::Add(FramePointsResult& r) {
  auto take = [](std::vector<ClassPoint>& from, std::vector<ClassPoint>& to) {
    to.insert(to.end(), std::make_move_iterator(from.begin()), std::make_move_iterator(from.end()));
    from.clear();
  };
  take(r.points, stereo_points_);
  take(r.contact_points, contact_points_);
  pending_.Append(std::move(r.contacts));
  stereo_checked_ += r.cues.stereo_checked;
  stereo_agreed_ += r.cues.stereo_agreed;
  stereo_cues_.push_back(r.cues);
  contact_cues_.push_back(r.contact_cues);
}

CapturePoints::Result CapturePoints::Finish() {
  Result out{.stereo_checked = stereo_checked_, .stereo_agreed = stereo_agreed_};
  switch (options_.contacts) {
    case ContactUse::kOff:
      out.points = std::move(stereo_points_);
      out.frames = std::move(stereo_cues_);
      return out;
    case ContactUse::kAlways:
      out.points = std::move(stereo_points_);
      out.contacts_used = true;
      out.decision = "contacts with every frame's stereo (--contacts always)";
      break;
    case ContactUse::kWhereStereoFails: {
      const double agree = stereo_checked_ > 0 ? static_cast<double>(stereo_agreed_) / stereo_checked_ : NAN;
      std::size_t contacts = pending_.paired_floor.size() + pending_.ceiling_rays.size();
      for (const ClassPoint& p : contact_points_) contacts += p.source == PointSource::kContact;
      const bool stereo_fails =
          stereo_checked_ >= options_.stereo_check_min_pixels && agree < options_.stereo_check_min_agree;
      if (stereo_fails && contacts < static_cast<std::size_t>(options_.stereo_check_min_contacts)) {
        out.points = std::move(stereo_points_);
        out.decision = fmt::format(
            "walls placed by stereo, though it was consistent at only {:.0f} % of {} wall pixels: only {} "
            "floor/ceiling contacts to replace it (is the rig level, are wall bases in view?)",
            100 * agree, stereo_checked_, contacts);
      } else if (stereo_fails) {
        out.points = std::move(contact_points_);
        out.frames = std::move(contact_cues_);
        out.contacts_used = true;
        out.decision = fmt::format(
            "walls placed by their floor/ceiling contacts: their stereo was consistent at only {:.0f} % of {} wall "
            "pixels (plain walls; {:.0f} % needed to keep it)",
            100 * agree, stereo_checked_, 100 * options_.stereo_check_min_agree);
      } else {
        out.points = std::move(stereo_points_);
        out.decision = stereo_checked_ >= options_.stereo_check_min_pixels
                           ? fmt::format("walls placed by stereo: it was consistent at {:.0f} % of {} wall pixels",
                                         100 * agree, stereo_checked_)
                           : fmt::format("walls placed by stereo: only {} wall pixels could be checked",
                                         stereo_checked_);
      }
      break;
    }
  }
  if (out.frames.empty()) out.frames = std::move(stereo_cues_);
  if (out.contacts_used) {
    out.contacts = pending_.Resolve(options_);
    out.points.insert(out.points.end(), out.contacts.points.begin(), out.contacts.points.end());
    out.contacts.points.clear();
  }
  return out;
}

CapturePointsResult ComputeCapturePoints(const Capture& capture, const LabelProvider& labels,
                                         const FramePointsOptions& options, const ProgressCallback& progress) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  std::optional<StereoRectifier> rectifier;
  if (!capture.rectified) {
    if (!capture.calibration) throw InputError("capture.json", "calibration", "needed when rectified is false");
    rectifier = MakeStereoRectifier(LoadCalibration(capture.Resolve(*capture.calibration)), {});
  }
  CapturePointsResult result;
  CapturePoints gathered(options);
  int done = 0;
  for (const CaptureFrame& frame : capture.frames) {
    ReportProgress(progress, {"points", done, static_cast<std::int64_t>(capture.frames.size()), ""});
    const StereoFrame stereo = LoadStereoFrame(capture, frame, labels, rectifier ? &*rectifier : nullptr);
    FramePointsResult r = ComputeFramePoints(stereo, options);
    gathered.Add(r);
    ++done;
  }
  CapturePoints::Result finished = gathered.Finish();
  result.frames = std::move(finished.frames);
  result.points = std::move(finished.points);
  result.ceiling = finished.contacts.ceiling;
  result.wall_cue = finished.decision;
  ReportProgress(progress, {"points", done, static_cast<std::int64_t>(capture.frames.size()), ""});
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

void WritePointsPly(const std::vector<ClassPoint>& points, const fs::path& path) {
  static const int kColour[4][3] = {{128, 128, 128}, {150, 160, 190}, {150, 90, 40}, {40, 200, 220}};
  std::string out = fmt::format(
      "ply\nformat ascii 1.0\ncomment asbuilt points (world metres; wall, door, window)\n"
      "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar label\nend_header\n",
      points.size());
  for (const ClassPoint& p : points) {
    const int c = static_cast<int>(p.label) & 3;
    out += fmt::format("{:.4f} {:.4f} {:.4f} {} {} {} {}\n", p.position_m.x(), p.position_m.y(), p.position_m.z(),
                       kColour[c][0], kColour[c][1], kColour[c][2], c);
  }
  WriteFileAtomic(path, out);
}

}  // namespace asbuilt
