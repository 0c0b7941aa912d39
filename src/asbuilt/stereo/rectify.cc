#include "asbuilt/stereo/rectify.h"

#include <fmt/format.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {

cv::Mat ReadMatrix(const cv::FileStorage& fs, const std::string& file, const std::string& key, int rows, int cols_min,
                   int cols_max) {
  cv::FileNode node = fs[key];
  if (node.empty()) throw InputError(file, key, "missing");
  cv::Mat m;
  try {
    node >> m;
  } catch (const cv::Exception&) {
    throw InputError(file, key, "not a matrix");
  }
  if (m.empty()) throw InputError(file, key, "not a matrix");
  m.convertTo(m, CV_64F);
  if (key[0] == 'D' || key == "T") {
    m = m.reshape(1, static_cast<int>(m.total()));
    if (rows < 0) {
      if (static_cast<int>(m.total()) < cols_min || static_cast<int>(m.total()) > cols_max) {
        throw InputError(file, key, fmt::format("expected {} to {} values, got {}", cols_min, cols_max, m.total()));
      }
      return m.t();
    }
  }
  if (m.rows * m.cols != rows * cols_min) {
    throw InputError(file, key, fmt::format("expected a {}x{} matrix, got {}x{}", rows, cols_min, m.rows, m.cols));
  }
  m = m.reshape(1, rows);
  for (int i = 0; i < m.rows; ++i)
    for (int j = 0; j < m.cols; ++j)
      if (!std::isfinite(m.at<double>(i, j))) throw InputError(file, key, "non-finite value");
  return m;
}

}  // namespace

std::string StereoCalibration::ToString() const {
  const double baseline = T.empty() ? NAN : cv::norm(T);
  return fmt::format("stereo calibration {}x{}, fx {:.2f}/{:.2f}, baseline {:.4f}, rms {:.3f} px", image_size.width,
                     image_size.height, K1.empty() ? NAN : K1.at<double>(0, 0), K2.empty() ? NAN : K2.at<double>(0, 0),
                     baseline, rms_px);
}

StereoCalibration LoadCalibration(const std::filesystem::path& path) {
  const std::string file = path.string();
  // FileStorage parses from memory so a missing file gets our message.
  const std::string text = ReadFile(path);
  cv::FileStorage fs;
  try {
    fs.open(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  } catch (const cv::Exception& e) {
    throw InputError(file, "", "not an OpenCV YAML/XML file");
  }
  if (!fs.isOpened()) throw InputError(file, "", "not an OpenCV YAML/XML file");
  StereoCalibration c;
  std::vector<Problem> problems;
  auto matrix = [&](const std::string& key, int rows, int cmin, int cmax) {
    try {
      return ReadMatrix(fs, file, key, rows, cmin, cmax);
    } catch (const InputError& e) {
      problems.insert(problems.end(), e.problems().begin(), e.problems().end());
      return cv::Mat();
    }
  };
  c.K1 = matrix("K1", 3, 3, 3);
  c.D1 = matrix("D1", -1, 4, 14);
  c.K2 = matrix("K2", 3, 3, 3);
  c.D2 = matrix("D2", -1, 4, 14);
  c.R = matrix("R", 3, 3, 3);
  c.T = matrix("T", 3, 1, 1);
  int w = 0, h = 0;
  if (!fs["image_width"].empty()) {
    w = static_cast<int>(fs["image_width"]);
    h = static_cast<int>(fs["image_height"]);
  } else if (!fs["image_size"].empty()) {
    cv::FileNode s = fs["image_size"];
    if (s.isSeq() && s.size() == 2) {
      w = static_cast<int>(s[0]);
      h = static_cast<int>(s[1]);
    }
  }
  if (w <= 0 || h <= 0)
    problems.push_back({file, "image_width", "missing or not positive (need image_width, image_height)"});
  c.image_size = cv::Size(w, h);
  if (!fs["rms"].empty()) c.rms_px = static_cast<double>(fs["rms"]);
  if (!fs["mean_epipolar_error_px"].empty()) c.epipolar_error_px = static_cast<double>(fs["mean_epipolar_error_px"]);
  if (!problems.empty()) throw InputError(problems);
  return c;
}

FileReport CheckCalibrationFile(const std::filesystem::path& path) {
  FileReport report;
  try {
    LoadCalibration(path);
  } catch (const InputError& e) {
    report.errors = e.problems();
  }
  return report;
}

void WriteCalibration(const StereoCalibration& c, const std::filesystem::path& path) {
  AtomicFile out(path);
  {
    cv::FileStorage fs(out.temp_path().string(), cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
    if (!fs.isOpened()) throw Error(fmt::format("{}: cannot write", path.string()));
    fs << "image_width" << c.image_size.width << "image_height" << c.image_size.height;
    fs << "K1" << c.K1 << "D1" << c.D1 << "K2" << c.K2 << "D2" << c.D2 << "R" << c.R << "T" << c.T;
    fs << "rms" << c.rms_px;
    if (std::isfinite(c.epipolar_error_px)) fs << "mean_epipolar_error_px" << c.epipolar_error_px;
  }
  out.Commit();
}

void RectifyOptions::Check() const {
  CheckArgument((alpha >= 0 && alpha <= 1) || alpha == -1,
                fmt::format("RectifyOptions.alpha = {}, must be in [0, 1] (or -1 for OpenCV's default)", alpha));
}

std::string StereoRectifier::ToString() const {
  return fmt::format("rectifier {}, baseline {:.4f} m", camera.ToString(), baseline_m);
}

StereoRectifier MakeStereoRectifier(const StereoCalibration& c, const RectifyOptions& options) {
  options.Check();
  CheckArgument(c.image_size.width > 0 && c.image_size.height > 0 && !c.K1.empty() && !c.K2.empty() && !c.R.empty() &&
                    !c.T.empty(),
                "MakeStereoRectifier: calibration lacks image size or matrices");
  cv::Mat R1, R2, P1, P2, Q;
  // One stereoRectify per rig (STYLE.md 5).
  cv::stereoRectify(c.K1, c.D1, c.K2, c.D2, c.image_size, c.R, c.T, R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY,
                    options.alpha, c.image_size);
  StereoRectifier r;
  cv::initUndistortRectifyMap(c.K1, c.D1, R1, P1, c.image_size, CV_32FC1, r.left_map_x, r.left_map_y);
  cv::initUndistortRectifyMap(c.K2, c.D2, R2, P2, c.image_size, CV_32FC1, r.right_map_x, r.right_map_y);
  r.camera = {c.image_size.width,  c.image_size.height, P1.at<double>(0, 0),
              P1.at<double>(1, 1), P1.at<double>(0, 2), P1.at<double>(1, 2)};
  r.baseline_m = std::abs(P2.at<double>(0, 3) / P2.at<double>(0, 0));
  r.R1 = R1;
  return r;
}

cv::Mat RectifyImage(const StereoRectifier& rectifier, StereoEye eye, const cv::Mat& image,
                     Interpolation interpolation) {
  CheckArgument(image.size() == rectifier.left_map_x.size(),
                fmt::format("RectifyImage: image is {}x{}, calibration is for {}x{}", image.cols, image.rows,
                            rectifier.left_map_x.cols, rectifier.left_map_x.rows));
  cv::Mat out;
  const bool left = eye == StereoEye::kLeft;
  cv::remap(image, out, left ? rectifier.left_map_x : rectifier.right_map_x,
            left ? rectifier.left_map_y : rectifier.right_map_y,
            interpolation == Interpolation::kNearest ? cv::INTER_NEAREST : cv::INTER_LINEAR, cv::BORDER_CONSTANT,
            cv::Scalar::all(interpolation == Interpolation::kNearest ? 255 : 0));
  return out;
}

}  // namespace asbuilt
