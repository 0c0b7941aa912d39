// `asbuilt disparity LEFT RIGHT -o disparity.pfm` — dense disparity of a
// rectified pair (stereo/disparity.h): float PFM + a colour picture.

#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/cli/command.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/stereo/disparity.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt::cli {

int RunDisparityCommand(int argc, char** argv) {
  CLI::App app(
      "Dense disparity of a rectified pair (SGBM or BM, left-right check, optional WLS and\n"
      "multi-scale). Writes float disparity as PFM (+inf = none) and a colour picture.",
      "asbuilt disparity");
  AddCommonFlags(app);
  std::string left_path, right_path, out, color, matcher = "sgbm";
  DisparityOptions options;
  bool no_lr = false;
  app.add_option("left", left_path, "rectified left image")->required();
  app.add_option("right", right_path, "rectified right image")->required();
  app.add_option("-o,--out", out, "float disparity file (.pfm)")->required();
  app.add_option("--color", color, "colour picture (default: OUT with .png)");
  app.add_option("--matcher", matcher, "sgbm or bm")->capture_default_str();
  app.add_option("--min-disparity", options.min_disparity_px, "smallest disparity (px)")->capture_default_str();
  app.add_option("--num-disparities", options.num_disparities_px, "range width, multiple of 16")->capture_default_str();
  app.add_option("--block", options.block_size_px, "matching window side (odd)")->capture_default_str();
  app.add_flag("--full-dp", options.full_dp, "SGBM with eight paths (slower)");
  app.add_flag("--wls", options.wls_filter, "edge-aware WLS filtering (fills holes)");
  app.add_flag("--multi-scale", options.multi_scale, "coarse pass narrows the range");
  app.add_flag("--no-lr", no_lr, "skip the left-right consistency check");
  Parse(app, argc, argv);
  if (matcher == "sgbm") {
    options.matcher = DisparityMatcher::kSgbm;
  } else if (matcher == "bm") {
    options.matcher = DisparityMatcher::kBm;
  } else {
    throw CLI::ValidationError("--matcher", fmt::format("'{}': expected sgbm or bm", matcher));
  }
  options.left_right_check = !no_lr;
  options.Check();
  if (std::filesystem::path(out).extension() != ".pfm") {
    throw CLI::ValidationError("--out", fmt::format("'{}': the float disparity is written as .pfm", out));
  }
  const cv::Mat left = ReadColourImage(left_path), right = ReadColourImage(right_path);
  CheckImageSize(right, left.cols, left.rows, right_path, "", "the left image");
  const DisparityResult r = ComputeDisparity(left, right, options);
  if (color.empty()) color = std::filesystem::path(out).replace_extension(".png").string();
  {
    AtomicFile picture(color);
    if (!cv::imwrite(picture.temp_path().string(), ColorizeDisparity(r.disparity_px))) {
      throw Error(fmt::format("{}: cannot write", color));
    }
    WritePfm(r.disparity_px, out);
    picture.Commit();
  }
  fmt::print("{} ({}) → {}, {}\n", r.ToString(), options.ToString(), out, color);
  return 0;
}

}  // namespace asbuilt::cli
