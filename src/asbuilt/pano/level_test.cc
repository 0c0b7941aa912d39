#include "asbuilt/pano/level.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/pano/pano_views.h"
#include "asbuilt/pano/perspective.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

// A 6.0 × 4.5 m room, 2.7 m high, the camera 1.5 m above the floor and off
// centre. Walls have panel seams, a skirting board and a dado rail, a door
// and a window with mullions; the floor is tiled.
constexpr double kX0 = -3.0, kX1 = 3.0, kY0 = -2.2, kY1 = 2.3, kCeiling = 2.7;
const Vec3 kCamera(0.5, -0.4, 1.5);

// The grey level a world ray from the camera sees.
double ShadeOfRay(const Vec3& ray) {
  double best = INFINITY;
  int surface = -1;  // 0..3 walls x0, x1, y0, y1; 4 floor; 5 ceiling.
  const double planes[6] = {kX0, kX1, kY0, kY1, 0.0, kCeiling};
  for (int i = 0; i < 6; ++i) {
    const int axis = i < 2 ? 0 : (i < 4 ? 1 : 2);
    if (std::abs(ray[axis]) < 1e-12) continue;
    const double t = (planes[i] - kCamera[axis]) / ray[axis];
    if (t > 0 && t < best) best = t, surface = i;
  }
  const Vec3 hit = kCamera + best * ray;
  if (surface == 4) return (static_cast<int>(std::floor(hit.x() / 0.6) + std::floor(hit.y() / 0.6)) & 1) ? 85 : 115;
  if (surface == 5) return 235;
  const double along = surface < 2 ? hit.y() : hit.x();  // Position along the wall.
  const double z = hit.z();
  const bool door = surface == 3 && along > -1.2 && along < -0.3 && z < 2.05;
  const bool door_frame = surface == 3 && along > -1.28 && along < -0.22 && z < 2.13;
  if (door) return 205;
  if (door_frame) return 60;
  if (surface == 1 && along > -1.0 && along < 1.0 && z > 0.9 && z < 2.0) {  // A window with two mullions.
    if (std::abs(along + 0.33) < 0.03 || std::abs(along - 0.33) < 0.03) return 70;
    return z > 1.45 ? 245 : 225;
  }
  if (z < 0.12) return 55;             // Skirting.
  if (z > 0.95 && z < 1.0) return 95;  // Dado rail.
  if (z > 2.55) return 215;            // Frieze.
  const double seam = along / 0.5 - std::floor(along / 0.5);
  if (seam < 0.05) return 75;  // Panel seams every 0.5 m, 2.5 cm wide.
  const double base[4] = {150, 175, 135, 190};
  return base[surface] + (z < 0.95 ? -20 : 0);
}

// The room seen by a panorama camera whose frame is turned by
// world_from_pano, 4 × 4 samples per pixel.
Image RenderRoom(const Mat3& world_from_pano, int width_px = 1024) {
  const int w = width_px, h = width_px / 2;
  cv::Mat image(h, w, CV_8UC3);
  constexpr int kSamples = 4;
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      double sum = 0;
      for (int sy = 0; sy < kSamples; ++sy) {
        for (int sx = 0; sx < kSamples; ++sx) {
          const Vec2 p(u - 0.5 + (sx + 0.5) / kSamples, v - 0.5 + (sy + 0.5) / kSamples);
          sum += ShadeOfRay(world_from_pano * DirectionFromEquirectPixel(p, w, h));
        }
      }
      const auto g = static_cast<unsigned char>(std::lround(sum / (kSamples * kSamples)));
      image.at<cv::Vec3b>(v, u) = cv::Vec3b(g, g, g);
    }
  }
  return AsImage(image);
}

// A camera tilted by tilt_deg about the horizontal axis at axis_yaw_deg.
Mat3 Tilted(double tilt_deg, double axis_yaw_deg) {
  return Eigen::AngleAxisd(DegToRad(tilt_deg), ForwardFromYaw(DegToRad(axis_yaw_deg))).toRotationMatrix();
}

double AngleDeg(const Vec3& a, const Vec3& b) { return RadToDeg(std::atan2(a.cross(b).norm(), a.dot(b))); }

TEST(LevelOptions, DefaultsAreValid) { EXPECT_NO_THROW(LevelOptions{}.Check()); }

TEST(LevelOptions, CheckNamesTheBadField) {
  EXPECT_THROW(LevelOptions{.max_tilt_deg = 0}.Check(), InvalidArgument);
  EXPECT_THROW(LevelOptions{.views = 2}.Check(), InvalidArgument);
  EXPECT_THROW(LevelOptions{.view_vertical_fov_deg = 180}.Check(), InvalidArgument);
  EXPECT_THROW(LevelOptions{.min_segment_deg = -1}.Check(), InvalidArgument);
  EXPECT_THROW(LevelOptions{.min_lines = 1}.Check(), InvalidArgument);
  try {
    LevelOptions{.bootstrap_samples = -3}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("LevelOptions.bootstrap_samples = -3"), std::string::npos) << e.what();
  }
}

TEST(EstimatePanoTilt, FindsALevelRoomLevel) {
  const PanoTilt tilt = EstimatePanoTilt(RenderRoom(Mat3::Identity()));
  std::printf("level room: %s\n", tilt.BriefReport().c_str());
  ASSERT_TRUE(tilt.found) << tilt.BriefReport();
  EXPECT_LT(tilt.tilt_deg, 0.1) << tilt.BriefReport();
  EXPECT_GE(tilt.vertical_lines, 50) << tilt.BriefReport();
  EXPECT_LT(tilt.sigma_deg, 0.1) << tilt.BriefReport();
}

TEST(EstimatePanoTilt, RecoversAKnownTiltAndLevellingRemovesIt) {
  struct Case {
    double tilt_deg, axis_yaw_deg;
  };
  for (const Case c : {Case{1.0, 30.0}, Case{1.0, 250.0}, Case{2.0, 120.0}, Case{2.0, 315.0}}) {
    SCOPED_TRACE(::testing::Message() << c.tilt_deg << "° about the axis at yaw " << c.axis_yaw_deg << "°");
    const Mat3 world_from_pano = Tilted(c.tilt_deg, c.axis_yaw_deg);
    const Vec3 truth_up = world_from_pano.transpose() * Vec3::UnitZ();
    const Image tilted = RenderRoom(world_from_pano);
    const PanoTilt tilt = EstimatePanoTilt(tilted);
    ASSERT_TRUE(tilt.found) << tilt.BriefReport();
    const double error_deg = AngleDeg(tilt.up_in_pano, truth_up);
    EXPECT_LT(error_deg, 0.1) << tilt.BriefReport();
    EXPECT_NEAR(tilt.tilt_deg, c.tilt_deg, 0.1) << tilt.BriefReport();
    // The up leans toward the yaw 90° counter-clockwise of the axis it turned about.
    EXPECT_NEAR(std::remainder(tilt.toward_yaw_deg - (c.axis_yaw_deg + 90), 360.0), 0.0, 5.0) << tilt.BriefReport();
    const PanoTilt after = EstimatePanoTilt(LevelPanorama(tilted, tilt));
    ASSERT_TRUE(after.found) << after.BriefReport();
    EXPECT_LT(after.tilt_deg, 0.1) << after.BriefReport();
    std::printf("%.1f° toward yaw %.0f°: error %.3f°, %s; levelled: %.3f°\n", c.tilt_deg,
                std::fmod(c.axis_yaw_deg + 90, 360.0), error_deg, tilt.BriefReport().c_str(), after.tilt_deg);
  }
}

TEST(EstimatePanoTilt, VerticalLinesAloneRecoverAKnownTiltToo) {
  const Mat3 world_from_pano = Tilted(1.5, 200.0);
  const PanoTilt tilt = EstimatePanoTilt(RenderRoom(world_from_pano), {.use_horizontal_lines = false});
  ASSERT_TRUE(tilt.found) << tilt.BriefReport();
  EXPECT_LT(AngleDeg(tilt.up_in_pano, world_from_pano.transpose() * Vec3::UnitZ()), 0.1) << tilt.BriefReport();
  EXPECT_EQ(tilt.lines_used, tilt.vertical_lines);
}

// A tripod whose axis leans: eight 640×480 views turned 45° apart, each
// said to be level, all tilted alike. Their lines give the lean, and each
// view resampled level gives none.
TEST(EstimateViewsTilt, RecoversATurningRigsLeanAndLevelViewRemovesIt) {
  const Mat3 world_from_rig = Tilted(1.5, 70.0);
  const Vec3 truth_up = world_from_rig.transpose() * Vec3::UnitZ();
  const Image pano = RenderRoom(world_from_rig, 2048);
  const std::vector<PanoView> geometry = TurnInPlaceViews({.views = 8, .yaw_step_deg = 45.0});
  std::vector<Image> views, levelled;
  for (const PanoView& g : geometry) views.push_back(RenderPanoView(pano, g));
  const PanoTilt tilt = EstimateViewsTilt(views, geometry);
  ASSERT_TRUE(tilt.found) << tilt.BriefReport();
  EXPECT_LT(AngleDeg(tilt.up_in_pano, truth_up), 0.1) << tilt.BriefReport();
  for (std::size_t i = 0; i < views.size(); ++i) levelled.push_back(LevelView(views[i], geometry[i], tilt));
  const PanoTilt after = EstimateViewsTilt(levelled, geometry);
  ASSERT_TRUE(after.found) << after.BriefReport();
  EXPECT_LT(after.tilt_deg, 0.1) << after.BriefReport();
  EXPECT_THROW(EstimateViewsTilt(views, {geometry.front()}), InvalidArgument);
  EXPECT_THROW(LevelView(views.front(), PanoView{.camera = {.width_px = 320}}, tilt), InvalidArgument);
}

TEST(LevelPanorama, UndoesAKnownTiltWithoutTurningTheYaw) {
  const Mat3 world_from_pano = Tilted(2.0, 60.0);
  const PanoTilt truth{.up_in_pano = world_from_pano.transpose() * Vec3::UnitZ(), .found = true};
  const cv::Mat levelled = AsMat(LevelPanorama(RenderRoom(world_from_pano), truth));
  const cv::Mat level = AsMat(RenderRoom(Mat3::Identity()));
  ASSERT_EQ(levelled.size(), level.size());
  ASSERT_EQ(levelled.type(), level.type());
  // Away from the poles (where the bilinear resampling smears the most) the
  // levelled image is the level one up to resampling blur.
  const cv::Rect band(0, 40, level.cols, level.rows - 80);
  EXPECT_LT(cv::mean(cv::abs(levelled(band) - level(band)))[0], 2.0);
  const cv::Mat still_tilted = AsMat(RenderRoom(world_from_pano));
  EXPECT_GT(cv::mean(cv::abs(still_tilted(band) - level(band)))[0], 4.0);
}

TEST(LevelPanorama, LeavesAPanoramaWithNoTiltFoundAsItIs) {
  const Image grey = AsImage(cv::Mat(64, 128, CV_8UC3, cv::Scalar(10, 20, 30)));
  const Image out = LevelPanorama(grey, PanoTilt{});
  EXPECT_TRUE(out.SamePixels(grey));
  EXPECT_NE(out.pixels(), grey.pixels());
}

TEST(EstimatePanoTilt, SaysSoWhenThereAreTooFewVerticalLines) {
  const PanoTilt tilt = EstimatePanoTilt(AsImage(cv::Mat(256, 512, CV_8UC3, cv::Scalar(128, 128, 128))));
  EXPECT_FALSE(tilt.found);
  EXPECT_LT(tilt.vertical_lines, LevelOptions{}.min_lines);
  EXPECT_TRUE(std::isnan(tilt.sigma_deg));
  EXPECT_EQ(tilt.up_in_pano, Vec3::UnitZ());
  EXPECT_EQ(tilt.BriefReport(), "no tilt estimate: 0 vertical lines, too few");
}

TEST(EstimatePanoTilt, RefusesBadImagesNamingWhatIsWrong) {
  const auto message = [](const Image& image) -> std::string {
    try {
      EstimatePanoTilt(image);
    } catch (const InvalidArgument& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(message(Image()).find("the panorama is empty"), std::string::npos);
  EXPECT_NE(message(Image(300, 100, 3, PixelType::kU8)).find("twice as wide as high, got 300x100"), std::string::npos);
  EXPECT_NE(message(Image(200, 100, 3, PixelType::kU16)).find("8-bit grey or BGR, got 3 channels, 16-bit"),
            std::string::npos);
  EXPECT_NE(message(Image(200, 100, 4, PixelType::kU8)).find("got 4 channels"), std::string::npos);
  EXPECT_THROW(LevelPanorama(Image(), PanoTilt{}), InvalidArgument);
  EXPECT_THROW(LevelPanorama(Image(200, 100, 3, PixelType::kU8), PanoTilt{.up_in_pano = Vec3(0, 0, 2)}),
               InvalidArgument);
}

TEST(PanoTilt, BriefReportSaysHowMuchWhichWayAndOnWhat) {
  const PanoTilt tilt{.up_in_pano = Vec3::UnitZ(),
                      .tilt_deg = 0.8,
                      .toward_yaw_deg = 327.6,
                      .lines_used = 412,
                      .vertical_lines = 130,
                      .sigma_deg = 0.031,
                      .found = true};
  EXPECT_EQ(tilt.BriefReport(), "tilted 0.80° toward yaw 328° ± 0.03°, 412 lines (130 vertical)");
  EXPECT_EQ(tilt.BriefReport(1024),
            "tilted 0.80° toward yaw 328° (column 92 of 1024) ± 0.03°, 412 lines (130 vertical)");
}

// The CC0 photos of ../shared/data (skipped without them): the tilts a
// person measured on their floor junctions and edges (annotated/README.md).
const fs::path kAnnotated = fs::path(ASBUILT_SHARED_DATA_DIR) / "cc0-panoramas/annotated";

TEST(EstimatePanoTilt, MeasuresThePineAtticPhotosTilt) {
  const fs::path photo = kAnnotated / "pine_attic/pano.jpg";
  if (!fs::exists(photo)) GTEST_SKIP() << "shared data not present: " << photo;
  const Image pano = ReadEquirect(photo);
  const auto start = std::chrono::steady_clock::now();
  const PanoTilt tilt = EstimatePanoTilt(pano);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("pine_attic: %s in %.2f s\n", tilt.BriefReport(pano.width()).c_str(), seconds);
  ASSERT_TRUE(tilt.found);
  EXPECT_NEAR(tilt.tilt_deg, 0.80, 0.1) << tilt.BriefReport();
  // Measured by hand: the world's up leans toward column ~92 (yaw −32°).
  EXPECT_NEAR(std::remainder(tilt.toward_yaw_deg + 32.3, 360.0), 0.0, 15.0) << tilt.BriefReport();
  const PanoTilt levelled = EstimatePanoTilt(ReadEquirect(kAnnotated / "pine_attic/pano_leveled.jpg"));
  std::printf("pine_attic pano_leveled: %s\n", levelled.BriefReport(pano.width()).c_str());
  EXPECT_LT(levelled.tilt_deg, 0.15) << levelled.BriefReport();
}

TEST(EstimatePanoTilt, MeasuresTheComfyCafePhotosTilt) {
  const fs::path photo = kAnnotated / "comfy_cafe/pano.jpg";
  if (!fs::exists(photo)) GTEST_SKIP() << "shared data not present: " << photo;
  const Image pano = ReadEquirect(photo);
  const PanoTilt tilt = EstimatePanoTilt(pano);
  std::printf("comfy_cafe: %s\n", tilt.BriefReport(pano.width()).c_str());
  ASSERT_TRUE(tilt.found);
  // By hand: 0.42 ± 0.1° about the axis at column ~224, so the up leans
  // toward yaw 11° (column ~992).
  EXPECT_NEAR(tilt.tilt_deg, 0.42, 0.15) << tilt.BriefReport();
  EXPECT_NEAR(std::remainder(tilt.toward_yaw_deg - 11.0, 360.0), 0.0, 25.0) << tilt.BriefReport();
}

}  // namespace
}  // namespace asbuilt
