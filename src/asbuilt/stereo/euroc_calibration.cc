#include "asbuilt/stereo/euroc_calibration.h"

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <opencv2/core.hpp>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {

struct EurocCamera {
  cv::Size resolution;
  cv::Mat K, D;           // 3×3, 1×4 (CV_64F).
  cv::Mat body_from_cam;  // 4×4 (CV_64F).
};

std::vector<double> ReadNumbers(const cv::FileNode& node, const std::string& file, const std::string& key,
                                std::size_t count) {
  if (node.empty()) throw InputError(file, key, "missing");
  if (!node.isSeq()) throw InputError(file, key, fmt::format("expected a list of {} numbers", count));
  std::vector<double> values;
  for (const cv::FileNode& v : node) {
    if (!v.isReal() && !v.isInt()) throw InputError(file, key, "expected numbers");
    values.push_back(static_cast<double>(v));
  }
  if (values.size() != count) {
    throw InputError(file, key, fmt::format("expected {} numbers, got {}", count, values.size()));
  }
  for (double v : values) {
    if (!std::isfinite(v)) throw InputError(file, key, "non-finite value");
  }
  return values;
}

std::string ReadString(const cv::FileNode& node) {
  return node.isString() ? static_cast<std::string>(node) : std::string();
}

EurocCamera ReadEurocCamera(const std::filesystem::path& path) {
  const std::string file = path.string();
  // Parse from memory so a missing file gets our message, not OpenCV's.
  const std::string text = ReadFile(path);
  cv::FileStorage fs;
  try {
    fs.open(text, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  } catch (const cv::Exception&) {
    throw InputError(file, "", "not a YAML file OpenCV can read (EuRoC sensor.yaml expected)");
  }
  if (!fs.isOpened()) throw InputError(file, "", "not a YAML file OpenCV can read (EuRoC sensor.yaml expected)");

  if (const std::string model = ReadString(fs["camera_model"]); !model.empty() && model != "pinhole") {
    throw InputError(file, "camera_model", fmt::format("'{}' is not supported (pinhole only)", model));
  }
  const std::string distortion = ReadString(fs["distortion_model"]);
  if (distortion != "radial-tangential" && distortion != "radtan" && distortion != "plumb_bob") {
    throw InputError(file, "distortion_model",
                     distortion.empty() ? std::string("missing (radial-tangential expected)")
                                        : fmt::format("'{}' is not supported (radial-tangential only; equidistant "
                                                      "needs OpenCV's fisheye model)",
                                                      distortion));
  }
  EurocCamera cam;
  const std::vector<double> res = ReadNumbers(fs["resolution"], file, "resolution", 2);
  if (res[0] < 1 || res[1] < 1) throw InputError(file, "resolution", "must be positive");
  cam.resolution = cv::Size(static_cast<int>(res[0]), static_cast<int>(res[1]));
  const std::vector<double> k = ReadNumbers(fs["intrinsics"], file, "intrinsics", 4);
  if (k[0] <= 0 || k[1] <= 0) throw InputError(file, "intrinsics", "focal lengths fu, fv must be > 0");
  cam.K = (cv::Mat_<double>(3, 3) << k[0], 0, k[2], 0, k[1], k[3], 0, 0, 1);
  const std::vector<double> d = ReadNumbers(fs["distortion_coefficients"], file, "distortion_coefficients", 4);
  cam.D = cv::Mat(d, true).reshape(1, 1);

  const cv::FileNode t_bs = fs["T_BS"];
  if (t_bs.empty()) throw InputError(file, "T_BS", "missing");
  const std::vector<double> m = ReadNumbers(t_bs["data"], file, "T_BS.data", 16);
  cam.body_from_cam = cv::Mat(m, true).reshape(1, 4);
  // The rotation block must be a rotation (det +1, orthonormal to ~1e-6 as printed).
  const cv::Mat rot = cam.body_from_cam(cv::Rect(0, 0, 3, 3));
  const double orthogonality = cv::norm(rot * rot.t() - cv::Mat::eye(3, 3, CV_64F), cv::NORM_INF);
  if (orthogonality > 1e-4 || std::abs(cv::determinant(rot) - 1) > 1e-4) {
    throw InputError(file, "T_BS.data", "the upper-left 3x3 block is not a rotation");
  }
  return cam;
}

}  // namespace

StereoCalibration CalibrationFromEuroc(const std::filesystem::path& left_sensor_yaml,
                                       const std::filesystem::path& right_sensor_yaml) {
  const EurocCamera left = ReadEurocCamera(left_sensor_yaml);
  const EurocCamera right = ReadEurocCamera(right_sensor_yaml);
  if (left.resolution != right.resolution) {
    throw InputError(right_sensor_yaml.string(), "resolution",
                     fmt::format("{}x{}, but the left camera is {}x{}", right.resolution.width, right.resolution.height,
                                 left.resolution.width, left.resolution.height));
  }
  StereoCalibration c;
  c.image_size = left.resolution;
  c.K1 = left.K;
  c.D1 = left.D;
  c.K2 = right.K;
  c.D2 = right.D;
  // x_B = T_BS_L·x_L = T_BS_R·x_R  ⇒  x_R = T_BS_R⁻¹·T_BS_L·x_L.
  const cv::Mat right_from_left = right.body_from_cam.inv(cv::DECOMP_SVD) * left.body_from_cam;
  c.R = right_from_left(cv::Rect(0, 0, 3, 3)).clone();
  c.T = right_from_left(cv::Rect(3, 0, 1, 3)).clone();
  // The left camera's centre seen from the right camera is T; in a rig with
  // the right camera to the right, that is to the right camera's left (x < 0).
  const double baseline_m = cv::norm(c.T);
  if (!(baseline_m > 0) || c.T.at<double>(0) > -0.5 * baseline_m) {
    throw InputError(right_sensor_yaml.string(), "T_BS",
                     fmt::format("this camera is not to the right of {} (T = [{:.4f}, {:.4f}, {:.4f}] m): give "
                                 "the left camera (cam0) first",
                                 left_sensor_yaml.string(), c.T.at<double>(0), c.T.at<double>(1), c.T.at<double>(2)));
  }
  return c;
}

}  // namespace asbuilt
