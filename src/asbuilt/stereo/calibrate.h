#ifndef ASBUILT_STEREO_CALIBRATE_H_
#define ASBUILT_STEREO_CALIBRATE_H_

// Stereo calibration from chessboard photographs (PAPER.md §7, real capture):
// corner detection with sub-pixel refinement, mono calibration of each
// camera, then stereo calibration starting from them; views with no board or
// an outlying reprojection error are rejected with a reason, never a crash.

#include <filesystem>
#include <string>
#include <vector>

#include "asbuilt/stereo/rectify.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

struct CalibrateOptions {
  // Inner corners of the chessboard (9x6 for OpenCV's sample board).
  int board_cols = 9;
  int board_rows = 6;
  // Side of one square; sets the unit of T (metres when given in metres).
  double square_m = 0.025;
  // cornerSubPix window (2r+1)².
  int subpix_radius_px = 5;
  // A view is rejected when its reprojection RMS in either image exceeds
  // max(max_view_error_px, view_error_factor × the median view RMS); the
  // calibration is then rerun without it.
  double max_view_error_px = 1.0;
  double view_error_factor = 3.0;
  // Rational distortion model (k4–k6): wide lenses; needs many views.
  bool rational_model = false;
  int min_views = 3;

  void Check() const;
};

struct ViewReport {
  std::string left, right;  // File names as given.
  bool used = false;
  std::string reason;          // Why it was rejected; empty when used.
  double left_error_px = NAN;  // Per-view RMS reprojection error (stereo).
  double right_error_px = NAN;

  std::string ToString() const;
};

struct CalibrationSummary {
  StereoCalibration calibration;  // rms_px and epipolar_error_px filled.
  std::vector<ViewReport> views;
  int views_used = 0;
  double left_rms_px = NAN;  // Mono calibrations.
  double right_rms_px = NAN;

  // "13/13 views, RMS 0.42 px, epipolar 0.38 px, baseline 0.0836 m".
  std::string BriefReport() const;
};

// Calibrates from pairs left[i]/right[i]. Throws InvalidArgument for bad
// options or unequal list lengths; InputError when fewer than min_views
// pairs show the board (listing each view's reason).
CalibrationSummary CalibrateStereo(const std::vector<std::filesystem::path>& left,
                                   const std::vector<std::filesystem::path>& right, const CalibrateOptions& options,
                                   const ProgressCallback& progress = {});

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_CALIBRATE_H_
