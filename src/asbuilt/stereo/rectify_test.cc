#include "asbuilt/stereo/rectify.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

StereoCalibration IdealRig() {
  StereoCalibration c;
  c.image_size = cv::Size(640, 480);
  c.K1 = (cv::Mat_<double>(3, 3) << 400, 0, 319.5, 0, 400, 239.5, 0, 0, 1);
  c.K2 = c.K1.clone();
  c.D1 = cv::Mat::zeros(1, 5, CV_64F);
  c.D2 = cv::Mat::zeros(1, 5, CV_64F);
  c.R = cv::Mat::eye(3, 3, CV_64F);
  c.T = (cv::Mat_<double>(3, 1) << -0.12, 0, 0);
  c.rms_px = 0.25;
  return c;
}

TEST(StereoRectifier, IdealRigKeepsIntrinsicsAndBaseline) {
  const StereoRectifier r = MakeStereoRectifier(IdealRig(), {});
  EXPECT_NEAR(r.camera.fx, 400, 1.0);
  EXPECT_NEAR(r.baseline_m, 0.12, 1e-9);
  // An ideal rig's maps are (nearly) the identity.
  EXPECT_NEAR(r.left_map_x.at<float>(100, 200), 200, 1.0);
  EXPECT_NEAR(r.left_map_y.at<float>(100, 200), 100, 1.0);
  cv::Mat image(480, 640, CV_8UC1, cv::Scalar(7));
  EXPECT_EQ(RectifyImage(r, StereoEye::kRight, image, Interpolation::kNearest).size(), image.size());
  EXPECT_THROW(RectifyImage(r, StereoEye::kLeft, cv::Mat(10, 10, CV_8UC1)), InvalidArgument);
}

TEST(LoadCalibration, ReadsWhatWriteCalibrationWrote) {
  const fs::path path = fs::temp_directory_path() / "asbuilt_stereo_rectify_test.yml";
  WriteCalibration(IdealRig(), path);
  const StereoCalibration c = LoadCalibration(path);
  EXPECT_EQ(c.image_size, cv::Size(640, 480));
  EXPECT_DOUBLE_EQ(c.K1.at<double>(0, 0), 400);
  EXPECT_DOUBLE_EQ(c.T.at<double>(0), -0.12);
  EXPECT_DOUBLE_EQ(c.rms_px, 0.25);
  // And OpenCV itself reads the keys by name.
  cv::FileStorage fs(path.string(), cv::FileStorage::READ);
  EXPECT_DOUBLE_EQ(static_cast<double>(fs["rms"]), 0.25);
  fs::remove(path);
}

TEST(LoadCalibration, MissingKeyNamesFileAndKey) {
  const fs::path path = fs::temp_directory_path() / "asbuilt_stereo_bad_calibration.yml";
  WriteFileAtomic(path, "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\n");
  try {
    LoadCalibration(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("K1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("asbuilt_stereo_bad_calibration.yml"), std::string::npos);
  }
  fs::remove(path);
}

}  // namespace
}  // namespace asbuilt
