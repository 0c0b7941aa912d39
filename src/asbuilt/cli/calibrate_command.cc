// `asbuilt calibrate --left 'L*.jpg' --right 'R*.jpg' --board 9x6 --square-m S
// -o calibration.yml` — stereo calibration from chessboard pairs
// (stereo/calibrate.h).

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/stereo/calibrate.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {

int RunCalibrateCommand(int argc, char** argv) {
  CLI::App app(
      "Calibrate a stereo camera from chessboard photographs: corners with sub-pixel refinement,\n"
      "mono then stereo calibration, outlying views rejected with reasons. Writes OpenCV YAML\n"
      "(K1 D1 K2 D2 R T, image_width/image_height, rms) for `asbuilt rectify` and capture.json.",
      "asbuilt calibrate");
  AddCommonFlags(app);
  std::vector<std::string> left_args, right_args;
  std::string board = "9x6", out;
  CalibrateOptions options;
  app.add_option("--left", left_args, "left images (files or a quoted glob such as 'L*.jpg')")->required();
  app.add_option("--right", right_args, "right images, paired with --left by sorted name")->required();
  app.add_option("--board", board, "inner corners, COLSxROWS")->capture_default_str();
  app.add_option("--square-m", options.square_m, "chessboard square side in metres")->capture_default_str();
  app.add_option("-o,--out", out, "calibration file to write (.yml)")->required();
  app.add_option("--max-view-error-px", options.max_view_error_px,
                 "reject views above max(this, factor x median) reprojection error")
      ->capture_default_str();
  app.add_flag("--rational", options.rational_model, "rational distortion model (k4-k6)");
  Parse(app, argc, argv);

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
