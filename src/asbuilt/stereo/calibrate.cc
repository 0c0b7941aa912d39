#include "asbuilt/stereo/calibrate.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/imageio/image_io.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/stats.h"

namespace asbuilt {
namespace {

// Chessboard corners at full size, then on a 2× upscale (small boards), then
// refined to sub-pixel. Empty when the board is not found.
std::vector<cv::Point2f> FindBoard(const cv::Mat& gray, cv::Size board, int subpix_radius) {
  std::vector<cv::Point2f> corners;
  const int max_scale = gray.cols <= 1000 ? 2 : 1;  // Upscaling big images costs seconds.
  for (int scale = 1; scale <= max_scale; ++scale) {
    cv::Mat img = gray;
    if (scale > 1) cv::resize(gray, img, cv::Size(), scale, scale, cv::INTER_LINEAR);
    if (cv::findChessboardCorners(img, board, corners, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) {
      for (auto& c : corners) c *= 1.0f / scale;
      cv::cornerSubPix(gray, corners, cv::Size(subpix_radius, subpix_radius), cv::Size(-1, -1),
                       cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 30, 0.01));
      return corners;
    }
  }
  return {};
}

// Mean distance of each point to its epipolar line, both images (as OpenCV's
// stereo_calib sample measures it), on undistorted points.
double MeanEpipolarError(const std::vector<std::vector<cv::Point2f>>& pts1,
                         const std::vector<std::vector<cv::Point2f>>& pts2, const StereoCalibration& c,
                         const cv::Mat& F) {
  double err = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < pts1.size(); ++i) {
    std::vector<cv::Point2f> u1, u2;
    cv::undistortPoints(pts1[i], u1, c.K1, c.D1, cv::noArray(), c.K1);
    cv::undistortPoints(pts2[i], u2, c.K2, c.D2, cv::noArray(), c.K2);
    std::vector<cv::Vec3f> l1, l2;
    cv::computeCorrespondEpilines(u1, 1, F, l1);
    cv::computeCorrespondEpilines(u2, 2, F, l2);
    for (std::size_t j = 0; j < u1.size(); ++j) {
      err += std::abs(u1[j].x * l2[j][0] + u1[j].y * l2[j][1] + l2[j][2]) +
             std::abs(u2[j].x * l1[j][0] + u2[j].y * l1[j][1] + l1[j][2]);
    }
    n += u1.size();
  }
  return n ? err / n : NAN;
}

}  // namespace

void CalibrateOptions::Check() const {
  CheckArgument(
      board_cols >= 2 && board_rows >= 2,
      fmt::format("CalibrateOptions.board = {}x{}, needs at least 2x2 inner corners", board_cols, board_rows));
  CheckArgument(square_m > 0 && std::isfinite(square_m),
                fmt::format("CalibrateOptions.square_m = {}, must be > 0", square_m));
  CheckArgument(subpix_radius_px >= 1,
                fmt::format("CalibrateOptions.subpix_radius_px = {}, must be >= 1", subpix_radius_px));
  CheckArgument(max_view_error_px > 0,
                fmt::format("CalibrateOptions.max_view_error_px = {}, must be > 0", max_view_error_px));
  CheckArgument(view_error_factor >= 1,
                fmt::format("CalibrateOptions.view_error_factor = {}, must be >= 1", view_error_factor));
  CheckArgument(min_views >= 2, fmt::format("CalibrateOptions.min_views = {}, must be >= 2", min_views));
}

std::string ViewReport::ToString() const {
  if (!used) return fmt::format("{} + {}: rejected: {}", left, right, reason);
  return fmt::format("{} + {}: used, reprojection {:.3f} / {:.3f} px", left, right, left_error_px, right_error_px);
}

std::string CalibrationSummary::BriefReport() const {
  return fmt::format(
      "{}/{} views, RMS {:.3f} px (mono {:.3f} / {:.3f}), mean epipolar error {:.3f} px, baseline {:.4f}", views_used,
      views.size(), calibration.rms_px, left_rms_px, right_rms_px, calibration.epipolar_error_px,
      calibration.T.empty() ? NAN : cv::norm(calibration.T));
}

CalibrationSummary CalibrateStereo(const std::vector<std::filesystem::path>& left,
                                   const std::vector<std::filesystem::path>& right, const CalibrateOptions& options,
                                   const ProgressCallback& progress) {
  options.Check();
  CheckArgument(left.size() == right.size(),
                fmt::format("CalibrateStereo: {} left images but {} right images", left.size(), right.size()));
  CheckArgument(!left.empty(), "CalibrateStereo: no images");
  const cv::Size board(options.board_cols, options.board_rows);
  CalibrationSummary summary;
  cv::Size image_size;
  std::vector<std::vector<cv::Point2f>> pts1, pts2;
  std::vector<int> view_of;  // Index into summary.views for each kept pair.

  // Detect the board in every pair.
  for (std::size_t i = 0; i < left.size(); ++i) {
    ReportProgress(progress, {"find boards", static_cast<std::int64_t>(i), static_cast<std::int64_t>(left.size()), ""});
    ViewReport view{left[i].string(), right[i].string()};
    cv::Mat l, r;
    try {
      l = ReadGrayImage(left[i]);
      r = ReadGrayImage(right[i]);
    } catch (const InputError& e) {
      view.reason = e.what();
    }
    if (!view.reason.empty()) {
      // Unreadable: skipped like a pair without a board, the reason names the file.
    } else if (l.size() != r.size()) {
      view.reason = fmt::format("left is {}x{}, right {}x{}", l.cols, l.rows, r.cols, r.rows);
    } else if (image_size.width > 0 && l.size() != image_size) {
      view.reason = fmt::format("size {}x{} differs from the first view's {}x{}", l.cols, l.rows, image_size.width,
                                image_size.height);
    } else {
      auto c1 = FindBoard(l, board, options.subpix_radius_px);
      auto c2 = c1.empty() ? std::vector<cv::Point2f>() : FindBoard(r, board, options.subpix_radius_px);
      if (c1.empty() || c2.empty()) {
        view.reason = fmt::format("no {}x{} board found in the {} image", board.width, board.height,
                                  c1.empty() ? "left" : "right");
      } else {
        image_size = l.size();
        pts1.push_back(std::move(c1));
        pts2.push_back(std::move(c2));
        view_of.push_back(static_cast<int>(summary.views.size()));
        view.used = true;
      }
    }
    summary.views.push_back(view);
  }

  auto too_few = [&]() {
    std::vector<Problem> problems;
    for (const ViewReport& v : summary.views) {
      if (!v.used) problems.push_back({v.left, "", v.reason});
    }
    problems.insert(
        problems.begin(),
        {left.front().string(), "", fmt::format("only {} usable view pairs, need {}", pts1.size(), options.min_views)});
    return InputError(problems);
  };

  std::vector<cv::Point3f> grid;
  for (int y = 0; y < board.height; ++y)
    for (int x = 0; x < board.width; ++x) grid.emplace_back(x * options.square_m, y * options.square_m, 0);

  const int dist_flags = options.rational_model ? cv::CALIB_RATIONAL_MODEL : 0;
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-6);
  StereoCalibration& c = summary.calibration;
  for (int round = 0; round < 2; ++round) {
    if (static_cast<int>(pts1.size()) < options.min_views) throw too_few();
    ReportProgress(progress, {"calibrate", round, 2, ""});
    std::vector<std::vector<cv::Point3f>> objects(pts1.size(), grid);
    // Mono calibrations, then the stereo refinement of everything.
    std::vector<cv::Mat> rv, tv;
    c.K1 = cv::Mat();
    c.K2 = cv::Mat();
    summary.left_rms_px = cv::calibrateCamera(objects, pts1, image_size, c.K1, c.D1, rv, tv, dist_flags, criteria);
    summary.right_rms_px = cv::calibrateCamera(objects, pts2, image_size, c.K2, c.D2, rv, tv, dist_flags, criteria);
    cv::Mat E, F, per_view;
    c.rms_px = cv::stereoCalibrate(objects, pts1, pts2, c.K1, c.D1, c.K2, c.D2, image_size, c.R, c.T, E, F, per_view,
                                   cv::CALIB_USE_INTRINSIC_GUESS | dist_flags, criteria);
    c.image_size = image_size;
    c.epipolar_error_px = MeanEpipolarError(pts1, pts2, c, F);
    std::vector<double> errors;
    for (int i = 0; i < per_view.rows; ++i) {
      auto& v = summary.views[view_of[i]];
      v.left_error_px = per_view.at<double>(i, 0);
      v.right_error_px = per_view.at<double>(i, 1);
      errors.push_back(std::max(v.left_error_px, v.right_error_px));
    }
    if (round == 1) break;
    // Reject outlying views and calibrate again.
    const double limit = std::max(options.max_view_error_px, options.view_error_factor * UpperMedian(errors));
    std::vector<std::vector<cv::Point2f>> keep1, keep2;
    std::vector<int> keep_of;
    for (std::size_t i = 0; i < errors.size(); ++i) {
      auto& v = summary.views[view_of[i]];
      if (errors[i] > limit) {
        v.used = false;
        v.reason = fmt::format("reprojection error {:.2f} px > limit {:.2f} px", errors[i], limit);
      } else {
        keep1.push_back(pts1[i]);
        keep2.push_back(pts2[i]);
        keep_of.push_back(view_of[i]);
      }
    }
    if (keep1.size() == pts1.size()) break;
    pts1 = std::move(keep1);
    pts2 = std::move(keep2);
    view_of = std::move(keep_of);
  }
  summary.views_used = static_cast<int>(pts1.size());
  ReportProgress(progress, {"calibrate", 2, 2, ""});
  return summary;
}

}  // namespace asbuilt
