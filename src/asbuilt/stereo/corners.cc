#include "asbuilt/stereo/corners.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// Sub-pixel disparity by Gauss–Newton on the zero-mean, unit-variance patch
// difference (a 1-D Lucas–Kanade along the row); starts from the parabola
// estimate and keeps it if the refinement wanders off by more than a pixel.
double RefineDisparity(const cv::Mat& patch, const cv::Mat& right_gray, double u, double v, double d0, int iterations) {
  const int side = patch.cols;
  cv::Scalar pm, ps;
  cv::meanStdDev(patch, pm, ps);
  if (ps[0] <= 0) return d0;
  cv::Mat p = (patch - pm[0]) / ps[0];
  double d = d0;
  for (int it = 0; it < iterations; ++it) {
    cv::Mat wide;
    cv::getRectSubPix(right_gray, cv::Size(side + 2, side), cv::Point2f(u - d, v), wide, CV_32F);
    cv::Mat q = wide(cv::Rect(1, 0, side, side));
    cv::Scalar qm, qs;
    cv::meanStdDev(q, qm, qs);
    if (qs[0] <= 0) return d0;
    double num = 0, den = 0;
    for (int y = 0; y < side; ++y) {
      const float* w = wide.ptr<float>(y);
      const float* pp = p.ptr<float>(y);
      for (int x = 0; x < side; ++x) {
        const double qn = (w[x + 1] - qm[0]) / qs[0];
        const double j = -0.5 * (w[x + 2] - w[x]) / qs[0];  // ∂q/∂d: x_right = u − d.
        num += (qn - pp[x]) * j;
        den += j * j;
      }
    }
    if (den <= 1e-9) return d0;
    const double step = -num / den;
    d += std::clamp(step, -0.5, 0.5);
    if (std::abs(d - d0) > 1.0) return d0;
    if (std::abs(step) < 1e-3) break;
  }
  return d;
}

}  // namespace

void CornerOptions::Check() const {
  CheckArgument(min_region_area_px >= 1,
                fmt::format("CornerOptions.min_region_area_px = {}, must be >= 1", min_region_area_px));
  CheckArgument(approx_epsilon_px > 0,
                fmt::format("CornerOptions.approx_epsilon_px = {}, must be > 0", approx_epsilon_px));
  CheckArgument(
      approx_epsilon_fraction >= 0 && approx_epsilon_fraction < 0.5,
      fmt::format("CornerOptions.approx_epsilon_fraction = {}, must be in [0, 0.5)", approx_epsilon_fraction));
  CheckArgument(border_margin_px >= 0,
                fmt::format("CornerOptions.border_margin_px = {}, must be >= 0", border_margin_px));
  CheckArgument(refine_radius_px >= 0,
                fmt::format("CornerOptions.refine_radius_px = {}, must be >= 0", refine_radius_px));
  CheckArgument(max_refine_shift_px >= 0,
                fmt::format("CornerOptions.max_refine_shift_px = {}, must be >= 0", max_refine_shift_px));
}

void RowMatchOptions::Check() const {
  CheckArgument(patch_radius_px >= 1 && patch_radius_px <= 50,
                fmt::format("RowMatchOptions.patch_radius_px = {}, must be in [1, 50]", patch_radius_px));
  CheckArgument(row_tolerance_px >= 0 && row_tolerance_px <= 10,
                fmt::format("RowMatchOptions.row_tolerance_px = {}, must be in [0, 10]", row_tolerance_px));
  CheckArgument(min_score > -1 && min_score <= 1,
                fmt::format("RowMatchOptions.min_score = {}, must be in (-1, 1]", min_score));
  CheckArgument(ambiguity_margin >= 0,
                fmt::format("RowMatchOptions.ambiguity_margin = {}, must be >= 0", ambiguity_margin));
  CheckArgument(min_patch_stddev >= 0,
                fmt::format("RowMatchOptions.min_patch_stddev = {}, must be >= 0", min_patch_stddev));
  CheckArgument(
      gauss_newton_iterations >= 0 && gauss_newton_iterations <= 100,
      fmt::format("RowMatchOptions.gauss_newton_iterations = {}, must be in [0, 100]", gauss_newton_iterations));
  CheckArgument(
      min_horizontal_structure >= 0 && min_horizontal_structure <= 1,
      fmt::format("RowMatchOptions.min_horizontal_structure = {}, must be in [0, 1]", min_horizontal_structure));
}

std::string ClassCorner::ToString() const {
  return fmt::format("{} corner at ({:.2f}, {:.2f}) region {}{}", LabelClassName(label), pixel.x(), pixel.y(), region,
                     refined ? " refined" : "");
}

std::string RowMatch::ToString() const {
  return fmt::format("disparity {:.3f} px (row {:+.0f}), score {:.3f}, second {:.3f}", disparity_px, row_offset_px,
                     score, second_score);
}

std::vector<ClassCorner> FindClassCorners(const cv::Mat& labels, const cv::Mat& gray, const CornerOptions& options) {
  options.Check();
  CheckArgument(labels.type() == CV_8UC1, "FindClassCorners: labels must be CV_8UC1");
  CheckArgument(gray.empty() || (gray.size() == labels.size() && gray.type() == CV_8UC1),
                "FindClassCorners: gray must be CV_8UC1 of the labels' size");
  std::vector<ClassCorner> corners;
  const int margin = options.border_margin_px;
  int region = 0;
  for (LabelClass c : {LabelClass::kWall, LabelClass::kDoor, LabelClass::kWindow}) {
    // Binarize → outer contours → polygons.
    cv::Mat mask = labels == static_cast<int>(c);
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    for (const auto& contour : contours) {
      if (cv::contourArea(contour) < options.min_region_area_px) continue;
      const double eps =
          std::max(options.approx_epsilon_px, options.approx_epsilon_fraction * cv::arcLength(contour, true));
      std::vector<cv::Point> polygon;
      cv::approxPolyDP(contour, polygon, eps, true);
      for (const cv::Point& p : polygon) {
        if (p.x < margin || p.y < margin || p.x >= labels.cols - margin || p.y >= labels.rows - margin) {
          continue;
        }
        corners.push_back({c, Vec2(p.x, p.y), region, false});
      }
      ++region;
    }
  }
  // Sub-pixel refinement on the image edges.
  if (!gray.empty() && options.refine_radius_px > 0 && !corners.empty()) {
    std::vector<cv::Point2f> pts;
    for (const auto& c : corners) pts.emplace_back(c.pixel.x(), c.pixel.y());
    cv::cornerSubPix(gray, pts, cv::Size(options.refine_radius_px, options.refine_radius_px), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.01));
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Vec2 refined(pts[i].x, pts[i].y);
      if (std::isfinite(refined.x()) && std::isfinite(refined.y()) &&
          (refined - corners[i].pixel).norm() <= options.max_refine_shift_px) {
        corners[i].pixel = refined;
        corners[i].refined = true;
      }
    }
  }
  return corners;
}

std::optional<RowMatch> MatchAlongRow(const cv::Mat& left_gray, const cv::Mat& right_gray, const Vec2& left_px,
                                      double min_disparity_px, double max_disparity_px,
                                      const RowMatchOptions& options) {
  CheckArgument(left_gray.type() == CV_32FC1 && right_gray.type() == CV_32FC1 && left_gray.size() == right_gray.size(),
                "MatchAlongRow: images must be CV_32FC1 of one size");
  const int h = options.patch_radius_px;
  const int side = 2 * h + 1;
  const double u = left_px.x(), v = left_px.y();
  if (u < h + 1 || v < h + 1 + options.row_tolerance_px || u > left_gray.cols - h - 2 ||
      v > left_gray.rows - h - 2 - options.row_tolerance_px) {
    return std::nullopt;
  }
  // Left patch; reject textureless or purely horizontal structure.
  cv::Mat patch;
  cv::getRectSubPix(left_gray, cv::Size(side, side), cv::Point2f(u, v), patch, CV_32F);
  cv::Scalar mean, stddev;
  cv::meanStdDev(patch, mean, stddev);
  if (stddev[0] < options.min_patch_stddev) return std::nullopt;
  double gx = 0, gall = 0;
  for (int y = 1; y < side - 1; ++y) {
    for (int x = 1; x < side - 1; ++x) {
      const double dx = patch.at<float>(y, x + 1) - patch.at<float>(y, x - 1);
      const double dy = patch.at<float>(y + 1, x) - patch.at<float>(y - 1, x);
      gx += std::abs(dx);
      gall += std::hypot(dx, dy);
    }
  }
  if (gall <= 0 || gx / gall < options.min_horizontal_structure) return std::nullopt;

  // Integer disparity range that keeps the right patch inside the image,
  // padded by one for the sub-pixel fit.
  int dmin = static_cast<int>(std::ceil(min_disparity_px)) - 1;
  int dmax = static_cast<int>(std::floor(max_disparity_px)) + 1;
  dmax = std::min(dmax, static_cast<int>(std::floor(u - h - 1)));
  dmin = std::max(dmin, static_cast<int>(std::ceil(u + h + 2 - right_gray.cols)));
  if (dmax - dmin < 2) return std::nullopt;
  const int width = dmax - dmin + side;

  RowMatch best;
  best.score = -2;
  std::vector<float> best_curve;
  for (int dy = -options.row_tolerance_px; dy <= options.row_tolerance_px; ++dy) {
    cv::Mat strip, scores;
    cv::getRectSubPix(right_gray, cv::Size(width, side), cv::Point2f(u - 0.5 * (dmin + dmax), v + dy), strip, CV_32F);
    cv::matchTemplate(strip, patch, scores, cv::TM_CCOEFF_NORMED);
    // Column k ↔ disparity dmax − k.
    const float* s = scores.ptr<float>(0);
    int k_best = static_cast<int>(std::max_element(s, s + scores.cols) - s);
    if (s[k_best] > best.score) {
      best.score = s[k_best];
      best.row_offset_px = dy;
      best_curve.assign(s, s + scores.cols);
      best.disparity_px = k_best;  // Column for now.
    }
  }
  const int k = static_cast<int>(best.disparity_px);
  const int n = static_cast<int>(best_curve.size());
  if (best.score < options.min_score) return std::nullopt;
  // The peak must be inside the searched range, not clipped at its end.
  if (k == 0 || k == n - 1) return std::nullopt;
  // Ambiguity: any other local peak farther than 2 px.
  for (int i = 0; i < n; ++i) {
    if (std::abs(i - k) <= 2) continue;
    const bool peak =
        (i == 0 || best_curve[i] >= best_curve[i - 1]) && (i == n - 1 || best_curve[i] >= best_curve[i + 1]);
    if (peak) best.second_score = std::max<double>(best.second_score, best_curve[i]);
  }
  if (best.second_score > best.score - options.ambiguity_margin) return std::nullopt;
  // Sub-pixel: parabola through the peak and its neighbours.
  const double a = best_curve[k - 1], b = best_curve[k], c = best_curve[k + 1];
  const double denom = a - 2 * b + c;
  const double delta = denom < 0 ? std::clamp(0.5 * (a - c) / denom, -0.5, 0.5) : 0.0;
  best.disparity_px = dmax - (k + delta);
  if (options.gauss_newton_iterations > 0) {
    best.disparity_px = RefineDisparity(patch, right_gray, u, v + best.row_offset_px, best.disparity_px,
                                        options.gauss_newton_iterations);
  }
  return best;
}

}  // namespace asbuilt
