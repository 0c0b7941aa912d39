#include "asbuilt/pano/level.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <fmt/format.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/pano/perspective.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/stats.h"

namespace asbuilt {
namespace {

// Columns copied from the other side of the seam, so bilinear sampling wraps.
constexpr int kSeamPad = 2;
// Extra yaw each view sees beyond its sector on either side, so an edge near
// a sector's border is seen whole in the view that keeps it.
constexpr double kViewMarginDeg = 10.0;
// View pixels per panorama pixel at the view's centre.
constexpr double kViewScale = 1.0;
// Two sets of views, the second turned by half a sector: each direction is
// cut out twice, differently, and the two detections' noise averages.
constexpr int kViewSets = 2;
// Bootstrap clusters: segments whose midpoints share a cell this size
// (yaw × elevation, degrees) are resampled together, as one edge's pieces
// and its second detection are not independent.
constexpr double kClusterYawDeg = 2.0, kClusterElevationDeg = 4.0;
// Cauchy's tuning constant (95 % efficiency under Gaussian noise).
constexpr double kCauchyC = 2.385;
constexpr int kIrlsIterations = 50;

// One detected segment as a constraint on the up direction.
struct Segment {
  Vec3 normal;        // Unit normal of the plane through the centre and the segment.
  Vec3 midpoint;      // Unit ray to the segment's midpoint.
  double length_rad;  // Angle the segment spans, seen from the centre.
  bool vertical;      // Its plane passes within the max tilt of the frame's up.
};

void CheckEquirect(const Image& equirect, const char* function) {
  CheckArgument(!equirect.empty(), fmt::format("{}: the panorama is empty", function));
  CheckArgument(std::abs(equirect.width() - 2 * equirect.height()) <= 1,
                fmt::format("{}: an equirectangular panorama is twice as wide as high, got {}x{}", function,
                            equirect.width(), equirect.height()));
}

double YawOf(const Vec3& d) { return std::atan2(-d.x(), d.y()); }

// Wraps an angle to (−π, π].
double WrapPi(double a) { return std::remainder(a, 2 * kPi); }

// The line segments of one view (8-bit grey) as planes through the centre,
// appended to `out`; with a finite `half_sector_rad`, only those whose
// midpoint's yaw lies within it of the view's.
void ViewSegments(const cv::Mat& grey, const PanoView& view, const LevelOptions& options, double half_sector_rad,
                  std::vector<Segment>& out) {
  const cv::Ptr<cv::LineSegmentDetector> lsd = cv::createLineSegmentDetector(cv::LSD_REFINE_STD);
  const double min_length_rad = DegToRad(options.min_segment_deg);
  const double max_normal_z = std::sin(DegToRad(options.max_tilt_deg));
  std::vector<cv::Vec4f> lines;
  lsd->detect(grey, lines);
  const double view_yaw = DegToRad(view.yaw_deg);
  for (const cv::Vec4f& l : lines) {
    const Vec3 r1 = view.RayInWorld(Vec2(l[0], l[1])).normalized();
    const Vec3 r2 = view.RayInWorld(Vec2(l[2], l[3])).normalized();
    const Vec3 cross = r1.cross(r2);
    const double length_rad = std::atan2(cross.norm(), r1.dot(r2));
    if (length_rad < min_length_rad) continue;
    const Vec3 normal = cross.normalized();
    const bool vertical = std::abs(normal.z()) <= max_normal_z;  // Its plane passes near the frame's up.
    const Vec3 midpoint = (r1 + r2).normalized();
    if (std::abs(WrapPi(YawOf(midpoint) - view_yaw)) > half_sector_rad) continue;  // Another view's.
    out.push_back({.normal = normal, .midpoint = midpoint, .length_rad = length_rad, .vertical = vertical});
  }
}

// Line segments of every view, as planes through the centre, each kept by
// the one view whose yaw sector holds its midpoint.
std::vector<Segment> DetectSegments(const cv::Mat& grey, const LevelOptions& options) {
  const double sector_deg = 360.0 / options.views;
  const double f = kViewScale * grey.cols / (2 * kPi);
  const int width = static_cast<int>(std::ceil(2 * f * std::tan(DegToRad(0.5 * sector_deg + kViewMarginDeg))));
  const int height = static_cast<int>(std::ceil(2 * f * std::tan(DegToRad(0.5 * options.view_vertical_fov_deg))));
  std::vector<PanoView> views;
  for (int set = 0; set < kViewSets; ++set) {
    const std::vector<PanoView> turn = TurnInPlaceViews({.width_px = width,
                                                         .height_px = height,
                                                         .fx = f,
                                                         .views = options.views,
                                                         .yaw_step_deg = sector_deg,
                                                         .first_yaw_deg = set * sector_deg / kViewSets});
    views.insert(views.end(), turn.begin(), turn.end());
  }
  const Image pano = AsImage(grey);
  std::vector<Segment> segments;
  for (const PanoView& view : views) {
    ViewSegments(AsMat(RenderPanoView(pano, view)), view, options, DegToRad(0.5 * sector_deg), segments);
  }
  return segments;
}

// The relative 1σ of a segment's residual n · a against a vanishing
// direction a: its plane turns about its midpoint by (end point noise) /
// length, which moves the plane at a by that times the sine of the angle
// from the midpoint to a (floored: a segment pointing at a still shifts).
double ResidualScale(const Segment& s, const Vec3& axis) {
  return std::max(s.midpoint.cross(axis).norm(), 0.05) / s.length_rad;
}

struct UpFit {
  Vec3 up = Vec3::UnitZ();
  double scale = NAN;  // Robust scale of the standardised residuals.
  int inliers = 0;
};

// Minimises Σ ρ((n_i · u) / σ_i) over unit u by iteratively reweighted least
// squares (Cauchy ρ): each step u = the smallest eigenvector of Σ w n nᵀ. The
// scale is the median absolute standardised residual (× 1.4826) unless
// `fixed_scale` is given.
UpFit FitUp(const std::vector<Segment>& segments, const std::vector<int>& index, const Vec3& start,
            double fixed_scale = NAN) {
  UpFit fit{.up = start};
  std::vector<double> z(index.size());
  for (int iteration = 0; iteration < kIrlsIterations; ++iteration) {
    for (std::size_t k = 0; k < index.size(); ++k) {
      const Segment& s = segments[index[k]];
      z[k] = s.normal.dot(fit.up) / ResidualScale(s, fit.up);
    }
    if (std::isfinite(fixed_scale)) {
      fit.scale = fixed_scale;
    } else {
      std::vector<double> abs_z(z.size());
      for (std::size_t k = 0; k < z.size(); ++k) abs_z[k] = std::abs(z[k]);
      fit.scale = std::max(1.4826 * UpperMedian(abs_z), 1e-9);
    }
    Mat3 m = Mat3::Zero();
    for (std::size_t k = 0; k < index.size(); ++k) {
      const Segment& s = segments[index[k]];
      const double sigma = ResidualScale(s, fit.up);
      const double t = z[k] / (kCauchyC * fit.scale);
      m += (1.0 / (sigma * sigma * (1 + t * t))) * s.normal * s.normal.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Mat3> eigen(m);
    Vec3 up = eigen.eigenvectors().col(0);
    if (up.z() < 0) up = -up;
    const double change = (up - fit.up).norm();
    fit.up = up;
    if (change < 1e-10) break;
  }
  fit.inliers = 0;
  for (int i : index) {
    const Segment& s = segments[i];
    fit.inliers += std::abs(s.normal.dot(fit.up) / ResidualScale(s, fit.up)) < kCauchyC * fit.scale;
  }
  return fit;
}

struct FrameFit {
  Mat3 frame = Mat3::Identity();  // Columns: the two horizontal Manhattan directions and the up, in the pano frame.
  double scale = NAN;
  int inliers = 0;
  int vertical_inliers = 0;
};

// The standardised residual of a segment against axis k of `frame`, and which axis fits it best.
std::pair<double, int> BestAxis(const Segment& s, const Mat3& frame) {
  std::pair<double, int> best{INFINITY, 0};
  for (int k = 0; k < 3; ++k) {
    const double z = s.normal.dot(frame.col(k)) / ResidualScale(s, frame.col(k));
    if (std::abs(z) < std::abs(best.first)) best = {z, k};
  }
  return best;
}

// The frame whose up is `up` and whose horizontal axes best explain the
// non-vertical segments (yaw searched in 0.25° steps over 90°).
Mat3 FrameAroundUp(const std::vector<Segment>& segments, const Vec3& up, double scale) {
  const Mat3 pano_from_level = LevelFromPano(up).transpose();
  double best_score = -1;
  Mat3 best = pano_from_level;
  for (int step = 0; step < 360; ++step) {
    const double yaw = DegToRad(0.25 * step);
    const Vec3 h1 = pano_from_level * Vec3(std::cos(yaw), std::sin(yaw), 0);
    const Vec3 h2 = pano_from_level * Vec3(-std::sin(yaw), std::cos(yaw), 0);
    double score = 0;
    for (const Segment& s : segments) {
      const double z = std::min(std::abs(s.normal.dot(h1) / ResidualScale(s, h1)),
                                std::abs(s.normal.dot(h2) / ResidualScale(s, h2))) /
                       (kCauchyC * scale);
      score += 1.0 / (1 + z * z);
    }
    if (score > best_score) {
      best_score = score;
      best.col(0) = h1;
      best.col(1) = h2;
      best.col(2) = up;
    }
  }
  return best;
}

// Minimises Σ ρ((n_i · f_k(i)) / σ_i) over rotations of the frame (Cauchy ρ,
// each segment against the axis it fits best), by reweighted Gauss–Newton
// steps on a small rotation ω: n · (f + ω × f) = n · f + ω · (f × n).
FrameFit FitFrame(const std::vector<Segment>& segments, const std::vector<int>& index, const Mat3& start,
                  double fixed_scale = NAN) {
  FrameFit fit{.frame = start};
  std::vector<std::pair<double, int>> z(index.size());
  for (int iteration = 0; iteration < kIrlsIterations; ++iteration) {
    for (std::size_t k = 0; k < index.size(); ++k) z[k] = BestAxis(segments[index[k]], fit.frame);
    if (std::isfinite(fixed_scale)) {
      fit.scale = fixed_scale;
    } else {
      std::vector<double> abs_z(z.size());
      for (std::size_t k = 0; k < z.size(); ++k) abs_z[k] = std::abs(z[k].first);
      fit.scale = std::max(1.4826 * UpperMedian(abs_z), 1e-9);
    }
    Mat3 normal_matrix = Mat3::Zero();
    Vec3 rhs = Vec3::Zero();
    for (std::size_t k = 0; k < index.size(); ++k) {
      const Segment& s = segments[index[k]];
      const Vec3 axis = fit.frame.col(z[k].second);
      const double sigma = ResidualScale(s, axis);
      const double t = z[k].first / (kCauchyC * fit.scale);
      const double w = 1.0 / (sigma * sigma * (1 + t * t));
      const Vec3 j = axis.cross(s.normal);
      normal_matrix += w * j * j.transpose();
      rhs -= w * s.normal.dot(axis) * j;
    }
    const Vec3 omega = normal_matrix.ldlt().solve(rhs);
    if (!omega.allFinite()) break;
    const Mat3 turn =
        omega.norm() > 0 ? Eigen::AngleAxisd(omega.norm(), omega.normalized()).toRotationMatrix() : Mat3::Identity();
    fit.frame = turn * fit.frame;
    if (omega.norm() < 1e-10) break;
  }
  fit.inliers = fit.vertical_inliers = 0;
  for (int i : index) {
    const auto [zi, axis] = BestAxis(segments[i], fit.frame);
    if (std::abs(zi) >= kCauchyC * fit.scale) continue;
    ++fit.inliers;
    fit.vertical_inliers += axis == 2;
  }
  return fit;
}

// The larger axis (1σ, radians) of the scatter about `up` of the up
// directions `fit_up` finds on bootstrap resamples of the segments, drawn a
// cluster (kClusterYawDeg × kClusterElevationDeg cell) at a time.
template <typename FitUpFunction>
double BootstrapSigma(const std::vector<Segment>& segments, const std::vector<int>& index, const Vec3& up,
                      const LevelOptions& options, FitUpFunction fit_up) {
  if (options.bootstrap_samples == 0) return NAN;
  std::map<std::pair<int, int>, std::vector<int>> cells;
  for (int i : index) {
    const Vec3& m = segments[i].midpoint;
    const double elevation_deg = RadToDeg(std::asin(std::clamp(m.z(), -1.0, 1.0)));
    cells[{static_cast<int>(std::floor(RadToDeg(YawOf(m)) / kClusterYawDeg)),
           static_cast<int>(std::floor(elevation_deg / kClusterElevationDeg))}]
        .push_back(i);
  }
  std::vector<const std::vector<int>*> clusters;
  for (const auto& [cell, members] : cells) clusters.push_back(&members);
  const Vec3 e1 = up.unitOrthogonal();
  const Vec3 e2 = up.cross(e1);
  std::mt19937 rng(options.seed);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(clusters.size()) - 1);
  std::vector<int> sample;
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  for (int b = 0; b < options.bootstrap_samples; ++b) {
    sample.clear();
    for (std::size_t c = 0; c < clusters.size(); ++c) {
      const std::vector<int>& members = *clusters[pick(rng)];
      sample.insert(sample.end(), members.begin(), members.end());
    }
    const Vec3 u = fit_up(sample);
    const Eigen::Vector2d d(u.dot(e1), u.dot(e2));
    covariance += d * d.transpose();
  }
  covariance /= options.bootstrap_samples;
  return std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(covariance).eigenvalues()(1));
}

PanoTilt TiltFromSegments(const std::vector<Segment>& segments, const LevelOptions& options);

}  // namespace

void LevelOptions::Check() const {
  CheckArgument(std::isfinite(max_tilt_deg) && max_tilt_deg > 0 && max_tilt_deg <= 45,
                fmt::format("LevelOptions.max_tilt_deg = {}, must be in (0, 45]", max_tilt_deg));
  CheckArgument(views >= 3 && views <= 360, fmt::format("LevelOptions.views = {}, must be in 3..360", views));
  CheckArgument(std::isfinite(view_vertical_fov_deg) && view_vertical_fov_deg >= 30 && view_vertical_fov_deg < 170,
                fmt::format("LevelOptions.view_vertical_fov_deg = {}, must be in [30, 170)", view_vertical_fov_deg));
  CheckArgument(std::isfinite(min_segment_deg) && min_segment_deg > 0 && min_segment_deg < 90,
                fmt::format("LevelOptions.min_segment_deg = {}, must be in (0, 90)", min_segment_deg));
  CheckArgument(min_lines >= 3, fmt::format("LevelOptions.min_lines = {}, must be >= 3", min_lines));
  CheckArgument(bootstrap_samples >= 0 && bootstrap_samples <= 100000,
                fmt::format("LevelOptions.bootstrap_samples = {}, must be in 0..100000", bootstrap_samples));
}

double PanoTilt::TowardColumn(int width_px) const {
  const double turn = -toward_yaw_deg / 360.0;
  return width_px * (turn - std::floor(turn)) - 0.5;
}

std::string PanoTilt::BriefReport(int width_px) const {
  if (!found) return fmt::format("no tilt estimate: {} vertical lines, too few", vertical_lines);
  const std::string column =
      width_px > 0 ? fmt::format(" (column {:.0f} of {})", TowardColumn(width_px), width_px) : std::string();
  const std::string sigma = std::isfinite(sigma_deg) ? fmt::format(" ± {:.2f}°", sigma_deg) : std::string();
  return fmt::format("tilted {:.2f}° toward yaw {:.0f}°{}{}, {} lines ({} vertical)", tilt_deg, toward_yaw_deg, column,
                     sigma, lines_used, vertical_lines);
}

PanoTilt EstimatePanoTilt(const Image& equirect, const LevelOptions& options) {
  options.Check();
  CheckEquirect(equirect, "EstimatePanoTilt");
  CheckArgument(equirect.type() == PixelType::kU8 && (equirect.channels() == 1 || equirect.channels() == 3),
                fmt::format("EstimatePanoTilt: the panorama must be 8-bit grey or BGR, got {} channels, {}",
                            equirect.channels(), PixelTypeName(equirect.type())));
  cv::Mat grey = AsMat(equirect);
  if (grey.channels() == 3) cv::cvtColor(grey, grey, cv::COLOR_BGR2GRAY);

  return TiltFromSegments(DetectSegments(grey, options), options);
}

PanoTilt EstimateViewsTilt(const std::vector<Image>& views, const std::vector<PanoView>& geometry,
                           const LevelOptions& options) {
  options.Check();
  CheckArgument(!views.empty() && views.size() == geometry.size(),
                fmt::format("EstimateViewsTilt: {} views for {} view geometries", views.size(), geometry.size()));
  std::vector<Segment> segments;
  for (std::size_t i = 0; i < views.size(); ++i) {
    CheckArgument(views[i].type() == PixelType::kU8 && (views[i].channels() == 1 || views[i].channels() == 3) &&
                      views[i].width() == geometry[i].camera.width_px &&
                      views[i].height() == geometry[i].camera.height_px,
                  fmt::format("EstimateViewsTilt: view {} must be 8-bit grey or BGR of its camera's size", i));
    cv::Mat grey = AsMat(views[i]);
    if (grey.channels() == 3) cv::cvtColor(grey, grey, cv::COLOR_BGR2GRAY);
    ViewSegments(grey, geometry[i], options, kPi, segments);
  }
  return TiltFromSegments(segments, options);
}

namespace {

PanoTilt TiltFromSegments(const std::vector<Segment>& segments, const LevelOptions& options) {
  std::vector<int> vertical, all;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    all.push_back(static_cast<int>(i));
    if (segments[i].vertical) vertical.push_back(static_cast<int>(i));
  }
  PanoTilt tilt{.lines_used = static_cast<int>(vertical.size()),
                .vertical_lines = static_cast<int>(vertical.size()),
                .sigma_deg = NAN};
  if (tilt.vertical_lines < options.min_lines) return tilt;

  // The vertical lines alone; then, from there, the whole Manhattan frame.
  const UpFit up_fit = FitUp(segments, vertical, Vec3::UnitZ());
  Vec3 up = up_fit.up;
  tilt.lines_used = tilt.vertical_lines = up_fit.inliers;
  FrameFit frame_fit;
  if (options.use_horizontal_lines) {
    frame_fit = FitFrame(segments, all, FrameAroundUp(segments, up, up_fit.scale));
    up = frame_fit.frame.col(2);
    if (up.z() < 0) up = -up;
    tilt.lines_used = frame_fit.inliers;
    tilt.vertical_lines = frame_fit.vertical_inliers;
  }
  const double tilt_rad = std::acos(std::clamp(up.z(), -1.0, 1.0));
  if (tilt.vertical_lines < options.min_lines || tilt_rad > DegToRad(options.max_tilt_deg)) return tilt;

  tilt.found = true;
  tilt.up_in_pano = up;
  tilt.tilt_deg = RadToDeg(tilt_rad);
  if (std::hypot(up.x(), up.y()) > 0) {
    const double yaw_deg = RadToDeg(YawOf(up));
    tilt.toward_yaw_deg = yaw_deg < 0 ? yaw_deg + 360 : yaw_deg;
  }
  if (options.use_horizontal_lines) {
    tilt.sigma_deg = RadToDeg(BootstrapSigma(segments, all, up, options, [&](const std::vector<int>& index) {
      const Vec3 u = FitFrame(segments, index, frame_fit.frame, frame_fit.scale).frame.col(2);
      return u.z() < 0 ? Vec3(-u) : u;
    }));
  } else {
    tilt.sigma_deg = RadToDeg(BootstrapSigma(segments, vertical, up, options, [&](const std::vector<int>& index) {
      return FitUp(segments, index, up, up_fit.scale).up;
    }));
  }
  return tilt;
}

}  // namespace

Mat3 LevelFromPano(const Vec3& up_in_pano) {
  const Vec3 axis = up_in_pano.cross(Vec3::UnitZ());
  const double angle = std::atan2(axis.norm(), up_in_pano.dot(Vec3::UnitZ()));
  if (axis.norm() < 1e-15) return Mat3::Identity();
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

Image LevelPanorama(const Image& equirect, const PanoTilt& tilt) {
  CheckEquirect(equirect, "LevelPanorama");
  CheckArgument(tilt.up_in_pano.allFinite() && std::abs(tilt.up_in_pano.norm() - 1) < 1e-6,
                fmt::format("LevelPanorama: PanoTilt.up_in_pano = ({}, {}, {}), must be a unit vector",
                            tilt.up_in_pano.x(), tilt.up_in_pano.y(), tilt.up_in_pano.z()));
  const cv::Mat pano = AsMat(equirect);
  if (!tilt.found) return AsImage(pano.clone());
  const Mat3 pano_from_level = LevelFromPano(tilt.up_in_pano).transpose();
  const int w = equirect.width(), h = equirect.height();
  cv::Mat map_x(h, w, CV_32F), map_y(h, w, CV_32F);
  for (int v = 0; v < h; ++v) {
    float* mx = map_x.ptr<float>(v);
    float* my = map_y.ptr<float>(v);
    for (int u = 0; u < w; ++u) {
      const Vec2 p = EquirectPixelFromDirection(pano_from_level * DirectionFromEquirectPixel(Vec2(u, v), w, h), w, h);
      mx[u] = static_cast<float>(p.x() + kSeamPad);
      my[u] = static_cast<float>(p.y());
    }
  }
  cv::Mat padded, out;
  cv::copyMakeBorder(pano, padded, 0, 0, kSeamPad, kSeamPad, cv::BORDER_WRAP);
  cv::remap(padded, out, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return AsImage(out);
}

Image LevelView(const Image& view, const PanoView& geometry, const PanoTilt& tilt) {
  CheckArgument(!view.empty() && view.width() == geometry.camera.width_px && view.height() == geometry.camera.height_px,
                fmt::format("LevelView: the view is {}x{}, its camera {}x{}", view.width(), view.height(),
                            geometry.camera.width_px, geometry.camera.height_px));
  const cv::Mat image = AsMat(view);
  if (!tilt.found) return AsImage(image.clone());
  // A level view's pixel → its ray in the level frame → the rig's frame →
  // the camera that took the view, which saw it at the pixel sampled.
  const Mat3 rig_from_level = LevelFromPano(tilt.up_in_pano).transpose();
  const Mat3 world_from_camera = geometry.WorldFromCamera();
  const Mat3 camera_from_level = world_from_camera.transpose() * rig_from_level;
  const PinholeCamera& cam = geometry.camera;
  cv::Mat map_x(image.rows, image.cols, CV_32F), map_y(image.rows, image.cols, CV_32F);
  for (int v = 0; v < image.rows; ++v) {
    float* mx = map_x.ptr<float>(v);
    float* my = map_y.ptr<float>(v);
    for (int u = 0; u < image.cols; ++u) {
      const Vec3 ray = camera_from_level * geometry.RayInWorld(Vec2(u, v));
      const bool ahead = ray.z() > 1e-9;
      mx[u] = ahead ? static_cast<float>(cam.fx * ray.x() / ray.z() + cam.cx) : -1.0f;
      my[u] = ahead ? static_cast<float>(cam.fy * ray.y() / ray.z() + cam.cy) : -1.0f;
    }
  }
  cv::Mat out;
  cv::remap(image, out, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return AsImage(out);
}

}  // namespace asbuilt
