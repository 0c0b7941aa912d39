// `asbuilt rectify --calibration calibration.yml --left L.png --right R.png
// -o DIR` — rectifies stereo pairs with maps computed once (stereo/rectify.h).

#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/stereo/rectify.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt::cli {
namespace fs = std::filesystem;

int RunRectifyCommand(int argc, char** argv) {
  CLI::App app(
      "Rectify stereo pairs with a calibration (maps computed once, reused for every pair).\n"
      "Writes DIR/left/NAME and DIR/right/NAME and prints the rectified camera for capture.json.",
      "asbuilt rectify");
  AddCommonFlags(app);
  std::string calibration, out_dir;
  std::vector<std::string> left_args, right_args;
  RectifyOptions options;
  app.add_option("--calibration", calibration, "OpenCV YAML from `asbuilt calibrate`")->required();
  app.add_option("--left", left_args, "left images (files or quoted globs)")->required();
  app.add_option("--right", right_args, "right images, paired by sorted name")->required();
  app.add_option("-o,--out", out_dir, "output folder")->required();
  app.add_option("--alpha", options.alpha, "0 crops to valid pixels, 1 keeps all")->capture_default_str();
  Parse(app, argc, argv);
  const auto left = ExpandFileArgs(left_args, "--left"), right = ExpandFileArgs(right_args, "--right");
  if (left.size() != right.size()) {
    throw CLI::ValidationError("--right", fmt::format("{} left images but {} right images", left.size(), right.size()));
  }
  options.Check();
  const StereoCalibration calib = LoadCalibration(calibration);
  const StereoRectifier rectifier = MakeStereoRectifier(calib, options);
  // Both images of a pair are read and checked before either is written, so
  // a bad pair leaves no half of itself behind.
  auto read = [&](const fs::path& path) {
    cv::Mat image = ReadImageAsStored(path);
    CheckImageSize(image, calib.image_size.width, calib.image_size.height, path, "",
                   fmt::format("the calibration {}", calibration));
    return image;
  };
  for (std::size_t i = 0; i < left.size(); ++i) {
    const cv::Mat images[2] = {read(left[i]), read(right[i])};
    for (auto [eye, path, sub, image] : {std::tuple{StereoEye::kLeft, left[i], "left", images[0]},
                                         std::tuple{StereoEye::kRight, right[i], "right", images[1]}}) {
      WriteImageAtomic(fs::path(out_dir) / sub / path.filename(), RectifyImage(rectifier, eye, image));
    }
  }
  const PinholeCamera& c = rectifier.camera;
  fmt::print(
      "{} pairs rectified → {}; camera for capture.json: {{\"width\": {}, \"height\": {}, \"fx\": {:.4f}, "
      "\"fy\": {:.4f}, \"cx\": {:.4f}, \"cy\": {:.4f}, \"baseline_m\": {:.6f}}}\n",
      left.size(), out_dir, c.width_px, c.height_px, c.fx, c.fy, c.cx, c.cy, rectifier.baseline_m);
  return 0;
}

}  // namespace asbuilt::cli
