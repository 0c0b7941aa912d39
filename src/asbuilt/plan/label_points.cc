#include "asbuilt/plan/label_points.h"

#include <fmt/format.h>
#include <opencv2/core.hpp>

#include "asbuilt/imageio/image_io.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace fs = std::filesystem;

void LabelPointsOptions::Check() const {
  CheckArgument(stride_px >= 1, fmt::format("LabelPointsOptions.stride_px = {}, must be >= 1", stride_px));
  CheckArgument(max_depth_m > 0, fmt::format("LabelPointsOptions.max_depth_m = {}, must be > 0", max_depth_m));
  CheckArgument(sigma_m >= 0, fmt::format("LabelPointsOptions.sigma_m = {}, must be >= 0", sigma_m));
}

std::vector<ClassPoint> PointsFromLabelledDepth(const Capture& capture, const LabelPointsOptions& options) {
  options.Check();
  const std::string file = (capture.base_dir / "capture.json").string();
  const PinholeCamera camera = capture.camera.Pinhole();
  std::vector<ClassPoint> points;
  for (size_t f = 0; f < capture.frames.size(); ++f) {
    const CaptureFrame& frame = capture.frames[f];
    const std::string field = fmt::format("frames[{}]", f);
    if (!frame.labels || !frame.depth) {
      throw InputError(file, field, "needs both `labels` and `depth` for exact class points");
    }
    const fs::path labels_path = capture.Resolve(*frame.labels), depth_path = capture.Resolve(*frame.depth);
    const cv::Mat labels = ReadLabelImage(labels_path, field + ".labels");
    CheckImageSize(labels, camera.width_px, camera.height_px, labels_path, field + ".labels", "the camera");
    const cv::Mat depth = ReadDepthImage(depth_path, field + ".depth");
    CheckImageSize(depth, camera.width_px, camera.height_px, depth_path, field + ".depth", "the camera");
    if (depth.type() != CV_16UC1) {
      throw InputError(depth_path.string(), field + ".depth", "expected a 16-bit (mm) depth image, got 32-bit float");
    }
    const Eigen::Isometry3d world_from_cam = WorldFromCamera(frame.Pose(), capture.camera.baseline_m, StereoEye::kLeft);
    for (int v = 0; v < labels.rows; v += options.stride_px) {
      const std::uint8_t* lrow = labels.ptr<std::uint8_t>(v);
      const std::uint16_t* drow = depth.ptr<std::uint16_t>(v);
      for (int u = 0; u < labels.cols; u += options.stride_px) {
        std::uint8_t label = lrow[u];
        if (label < 1 || label > 3 || drow[u] == 0) continue;
        double z = drow[u] * 0.001;
        if (z > options.max_depth_m) continue;
        Vec3 p = world_from_cam * UnprojectToCamera(camera, Vec2(u, v), z);
        points.push_back({static_cast<LabelClass>(label), p, options.sigma_m, PointSource::kDense, frame.index});
      }
    }
  }
  return points;
}

}  // namespace asbuilt
