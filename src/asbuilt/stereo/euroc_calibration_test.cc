#include "asbuilt/stereo/euroc_calibration.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>

#include "asbuilt/imageio/image_io.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

const fs::path kEuroc = fs::path(ASBUILT_SHARED_DATA_DIR) / "euroc_v1_01_vicon_room_stereo";

#define SKIP_WITHOUT_EUROC() \
  if (!fs::exists(kEuroc / "cam0" / "sensor.yaml")) GTEST_SKIP() << kEuroc << " absent"

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Row offsets v_right − v_left and disparities of SIFT matches (sub-pixel
// keypoints; Lowe's ratio test 0.75) with a plausible disparity (0–120 px),
// in the given (rectified or raw) pair.
struct RowCheck {
  std::vector<double> dv, disparity;
};
RowCheck MatchRows(const cv::Mat& left, const cv::Mat& right) {
  cv::Ptr<cv::SIFT> sift = cv::SIFT::create(2000);
  std::vector<cv::KeyPoint> kl, kr;
  cv::Mat dl, dr;
  sift->detectAndCompute(left, cv::noArray(), kl, dl);
  sift->detectAndCompute(right, cv::noArray(), kr, dr);
  cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> knn;
  matcher.knnMatch(dl, dr, knn, 2);
  RowCheck out;
  for (const std::vector<cv::DMatch>& m : knn) {
    if (m.size() < 2 || m[0].distance > 0.75f * m[1].distance) continue;
    const cv::Point2f pl = kl[m[0].queryIdx].pt, pr = kr[m[0].trainIdx].pt;
    const double d = pl.x - pr.x, dv = pr.y - pl.y;
    // A geometric gate loose enough to keep a badly rectified pair's matches
    // (|Δv| up to 20 px) but drop mismatches across the image.
    if (d < 0 || d > 120 || std::abs(dv) > 20) continue;
    out.dv.push_back(dv);
    out.disparity.push_back(d);
  }
  return out;
}

TEST(CalibrationFromEuroc, MatchesTheDatasetReadmeReferenceNumbers) {
  SKIP_WITHOUT_EUROC();
  const StereoCalibration c = CalibrationFromEuroc(kEuroc / "cam0" / "sensor.yaml", kEuroc / "cam1" / "sensor.yaml");
  EXPECT_EQ(c.image_size, cv::Size(752, 480));
  EXPECT_DOUBLE_EQ(c.K1.at<double>(0, 0), 458.654);
  EXPECT_DOUBLE_EQ(c.K2.at<double>(1, 2), 255.238);
  EXPECT_DOUBLE_EQ(c.D1.at<double>(0), -0.28340811);
  EXPECT_EQ(c.D2.total(), 4u);
  // README: t = (-0.110074, 0.000399, -0.000854) m, R[1,2] = 0.01409.
  EXPECT_NEAR(c.T.at<double>(0), -0.110074, 2e-6);
  EXPECT_NEAR(c.T.at<double>(1), 0.000399, 2e-6);
  EXPECT_NEAR(c.T.at<double>(2), -0.000854, 2e-6);
  EXPECT_NEAR(c.R.at<double>(1, 2), 0.01409, 1e-5);
  EXPECT_TRUE(std::isnan(c.rms_px));
  // README: stereoRectify gives f = 436.2346 px, c = (364.4412, 256.9517), P2[0,3] = -48.0198.
  const StereoRectifier r = MakeStereoRectifier(c, {});
  EXPECT_NEAR(r.camera.fx, 436.2346, 1e-3);
  EXPECT_NEAR(r.camera.cx, 364.4412, 1e-3);
  EXPECT_NEAR(r.camera.cy, 256.9517, 1e-3);
  EXPECT_NEAR(r.baseline_m, 48.0198 / 436.2346, 1e-5);
}

TEST(CalibrationFromEuroc, RoundTripsThroughTheCalibrationFile) {
  SKIP_WITHOUT_EUROC();
  const StereoCalibration c = CalibrationFromEuroc(kEuroc / "cam0" / "sensor.yaml", kEuroc / "cam1" / "sensor.yaml");
  const fs::path path = fs::temp_directory_path() / fmt::format("asbuilt_euroc_{}.yml", ::getpid());
  WriteCalibration(c, path);
  EXPECT_TRUE(CheckCalibrationFile(path).errors.empty());
  const StereoCalibration back = LoadCalibration(path);
  EXPECT_EQ(back.image_size, c.image_size);
  EXPECT_LT(cv::norm(back.R, c.R, cv::NORM_INF), 1e-12);
  EXPECT_LT(cv::norm(back.T, c.T, cv::NORM_INF), 1e-12);
  EXPECT_LT(cv::norm(back.D2, c.D2, cv::NORM_INF), 1e-12);
  fs::remove(path);
}

// Issue 9: rectification with the converted calibration row-aligns the real
// pair: median |Δv| of SIFT matches < 1 px (raw images: ~13 px).
TEST(CalibrationFromEuroc, RectifiedRealPairsHaveAlignedRows) {
  SKIP_WITHOUT_EUROC();
  const StereoRectifier r =
      MakeStereoRectifier(CalibrationFromEuroc(kEuroc / "cam0" / "sensor.yaml", kEuroc / "cam1" / "sensor.yaml"), {});
  for (const char* stamp : {"1403715273262142976", "1403715277962142976"}) {
    const std::string name = std::string(stamp) + ".png";
    const cv::Mat left = ReadGrayImage(kEuroc / "cam0" / name);
    const cv::Mat right = ReadGrayImage(kEuroc / "cam1" / name);
    const RowCheck raw = MatchRows(left, right);
    const RowCheck rect = MatchRows(RectifyImage(r, StereoEye::kLeft, left), RectifyImage(r, StereoEye::kRight, right));
    ASSERT_GE(rect.dv.size(), 200u) << name;
    std::vector<double> abs_dv;
    for (double dv : rect.dv) abs_dv.push_back(std::abs(dv));
    std::vector<double> raw_abs_dv;
    for (double dv : raw.dv) raw_abs_dv.push_back(std::abs(dv));
    const double median_abs_dv = Median(abs_dv), raw_median_abs_dv = Median(raw_abs_dv);
    std::sort(abs_dv.begin(), abs_dv.end());
    const double p90_abs_dv = abs_dv[abs_dv.size() * 9 / 10];
    std::printf(
        "%s: %zu rectified matches, |dv| median %.3f px, p90 %.3f px (raw pair: median %.3f px over %zu), "
        "median disparity %.2f px\n",
        stamp, rect.dv.size(), median_abs_dv, p90_abs_dv, raw_median_abs_dv, raw.dv.size(), Median(rect.disparity));
    EXPECT_LT(median_abs_dv, 1.0) << name;
    EXPECT_LT(p90_abs_dv, 2.0) << name;
    EXPECT_LT(std::abs(Median(rect.dv)), 0.5) << name << ": rows are shifted, not just noisy";
    EXPECT_GT(raw_median_abs_dv, 2 * median_abs_dv) << name << ": the raw pair should be visibly worse";
    // README: median disparity ≈ 25 px (the mats ~1.9 m in front of the MAV).
    EXPECT_NEAR(Median(rect.disparity), 25.0, 3.0) << name;
  }
}

TEST(CalibrationFromEuroc, SwappedCamerasNameTheFileAndSayWhatToDo) {
  SKIP_WITHOUT_EUROC();
  try {
    CalibrationFromEuroc(kEuroc / "cam1" / "sensor.yaml", kEuroc / "cam0" / "sensor.yaml");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cam0/sensor.yaml: T_BS"), std::string::npos) << what;
    EXPECT_NE(what.find("left camera (cam0) first"), std::string::npos) << what;
  }
}

TEST(CalibrationFromEuroc, FisheyeAndMissingKeysAreInputErrors) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("asbuilt_euroc_bad_{}", ::getpid());
  fs::create_directories(dir);
  const std::string good =
      "%YAML:1.0\ncamera_model: pinhole\nresolution: [752, 480]\nintrinsics: [458.6, 457.3, 367.2, 248.4]\n"
      "distortion_coefficients: [-0.28, 0.07, 0.0, 0.0]\n"
      "T_BS:\n  cols: 4\n  rows: 4\n  data: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]\n";
  WriteFileAtomic(dir / "fisheye.yaml", good + "distortion_model: equidistant\n");
  WriteFileAtomic(dir / "no_tbs.yaml", good.substr(0, good.find("T_BS")) + "distortion_model: radial-tangential\n");
  WriteFileAtomic(dir / "ok.yaml", good + "distortion_model: radial-tangential\n");
  auto message = [&](const fs::path& a) -> std::string {
    try {
      CalibrationFromEuroc(a, dir / "ok.yaml");
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(message(dir / "fisheye.yaml").find("fisheye.yaml: distortion_model: 'equidistant' is not supported"),
            std::string::npos)
      << message(dir / "fisheye.yaml");
  EXPECT_NE(message(dir / "no_tbs.yaml").find("no_tbs.yaml: T_BS: missing"), std::string::npos)
      << message(dir / "no_tbs.yaml");
  EXPECT_NE(message(dir / "absent.yaml").find("absent.yaml"), std::string::npos) << message(dir / "absent.yaml");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace asbuilt
