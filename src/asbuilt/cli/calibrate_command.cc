// `asbuilt calibrate --left 'L*.jpg' --right 'R*.jpg' --board 9x6 --square-m S
// -o calibration.yml` — stereo calibration from chessboard pairs
// (stereo/calibrate.h), or `asbuilt calibrate --from-euroc cam0/sensor.yaml
// cam1/sensor.yaml -o calibration.yml` — a rig calibrated elsewhere, imported
// from EuRoC sensor.yaml files (stereo/euroc_calibration.h).

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/stereo/calibrate.h"
#include "asbuilt/stereo/euroc_calibration.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {

int RunCalibrateCommand(int argc, char** argv) {
  CLI::App app(
      "Calibrate a stereo camera from chessboard photographs: corners with sub-pixel refinement,\n"
      "mono then stereo calibration, outlying views rejected with reasons. Writes OpenCV YAML\n"
      "(K1 D1 K2 D2 R T, image_width/image_height, rms) for `asbuilt rectify` and capture.json.\n"
      "With --from-euroc LEFT.yaml RIGHT.yaml, converts an existing calibration instead (EuRoC\n"
      "sensor.yaml per camera: intrinsics, radial-tangential distortion, T_BS camera-to-body).",
      "asbuilt calibrate");
  AddCommonFlags(app);
  std::vector<std::string> left_args, right_args, euroc;
  std::string board = "9x6", out;
  CalibrateOptions options;
  auto* left_opt = app.add_option("--left", left_args, "left images (files or a quoted glob such as 'L*.jpg')");
  auto* right_opt = app.add_option("--right", right_args, "right images, paired with --left by sorted name");
  auto* euroc_opt =
      app.add_option("--from-euroc", euroc, "convert EuRoC sensor.yaml files instead: LEFT (cam0) then RIGHT (cam1)")
          ->expected(2)
          ->check(CLI::ExistingFile);
  euroc_opt->excludes(left_opt)->excludes(right_opt);
  app.add_option("--board", board, "inner corners, COLSxROWS")->capture_default_str();
  app.add_option("--square-m", options.square_m, "chessboard square side in metres")->capture_default_str();
  app.add_option("-o,--out", out, "calibration file to write (.yml)")->required();
  app.add_option("--max-view-error-px", options.max_view_error_px,
                 "reject views above max(this, factor x median) reprojection error")
      ->capture_default_str();
  app.add_flag("--rational", options.rational_model, "rational distortion model (k4-k6)");
  Parse(app, argc, argv);

  if (!euroc.empty()) {
    const StereoCalibration calibration = CalibrationFromEuroc(euroc[0], euroc[1]);
    WriteCalibration(calibration, out);
    // The rectified camera, so a capture.json can be written without a rectify run.
    const StereoRectifier rectifier = MakeStereoRectifier(calibration, {});
    const PinholeCamera& c = rectifier.camera;
    fmt::print(
        "{} → {}; rectified camera for capture.json: {{\"width\": {}, \"height\": {}, \"fx\": {:.4f}, "
        "\"fy\": {:.4f}, \"cx\": {:.4f}, \"cy\": {:.4f}, \"baseline_m\": {:.6f}}}\n",
        calibration.ToString(), out, c.width_px, c.height_px, c.fx, c.fy, c.cx, c.cy, rectifier.baseline_m);
    return 0;
  }
  if (left_args.empty() || right_args.empty()) {
    throw CLI::RequiredError("--left and --right (or --from-euroc LEFT.yaml RIGHT.yaml)");
  }
  if (std::sscanf(board.c_str(), "%dx%d", &options.board_cols, &options.board_rows) != 2) {
    throw CLI::ValidationError("--board", fmt::format("'{}' is not COLSxROWS (e.g. 9x6)", board));
  }
  const auto left = ExpandFileArgs(left_args, "--left"), right = ExpandFileArgs(right_args, "--right");
  if (left.size() != right.size()) {
    throw CLI::ValidationError("--right", fmt::format("{} left images but {} right images", left.size(), right.size()));
  }
  options.Check();
  ProgressPrinter printer;
  CalibrationSummary summary = CalibrateStereo(left, right, options, printer.Callback());
  printer.Finish();
  for (const ViewReport& v : summary.views) fmt::print(stderr, "  {}\n", v.ToString());
  WriteCalibration(summary.calibration, out);
  fmt::print("{} → {}\n", summary.BriefReport(), out);
  return 0;
}

}  // namespace asbuilt::cli
