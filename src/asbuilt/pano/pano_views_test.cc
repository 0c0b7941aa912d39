#include "asbuilt/pano/pano_views.h"

#include <cstdlib>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/pano/layout_labels.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("asbuilt_pano_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A panorama whose colour tells the direction: blue rises with the column, red with the row.
fs::path WriteGradientPanorama(const fs::path& dir) {
  cv::Mat pano(256, 512, CV_8UC3);
  for (int v = 0; v < pano.rows; ++v)
    for (int u = 0; u < pano.cols; ++u) pano.at<cv::Vec3b>(v, u) = cv::Vec3b(u / 2, 60, v);
  const fs::path path = dir / "pano.png";
  cv::imwrite(path.string(), pano);
  return path;
}

ZindPanorama Room(const fs::path& image) {
  ZindPanorama p;
  p.floor_id = "floor_01";
  p.complete_room_id = "complete_room_01";
  p.partial_room_id = "partial_room_01";
  p.pano_id = "pano_1";
  p.label = "test room";
  p.image = image;
  p.camera_height_m = 1.4;
  p.ceiling_height_m = 2.4;
  p.layout_raw.vertices_m = {{-2, -2}, {2, -2}, {2, 2}, {-2, 2}};
  p.layout_raw.openings = {
      {.kind = ZindOpeningKind::kDoor, .start_m = {-0.5, 2}, .end_m = {0.5, 2}, .bottom_m = 0, .top_m = 2, .wall = 2}};
  return p;
}

TEST(WritePanoViews, WritesViewsAndAMonoCapture) {
  const fs::path dir = FreshDir("views");
  const fs::path pano = WriteGradientPanorama(dir);
  const PanoViewsSummary s = WritePanoViews(
      pano, dir / "out", {.turn = {.width_px = 160, .height_px = 120, .fx = 100, .views = 4, .yaw_step_deg = 90}});
  EXPECT_EQ(s.views, 4);
  EXPECT_FALSE(s.labels);
  EXPECT_EQ(s.BriefReport(), "4 views → " + (dir / "out/capture.json").string());
  const nlohmann::json j = nlohmann::json::parse(ReadFile(dir / "out/capture.json"));
  EXPECT_EQ(j["kind"], "mono");
  EXPECT_FALSE(j.contains("provisional"));
  EXPECT_EQ(j["camera"]["width"], 160);
  EXPECT_EQ(j["camera"]["cx"], 79.5);
  ASSERT_EQ(j["frames"].size(), 4u);
  EXPECT_EQ(j["frames"][3]["yaw_deg"], 270.0);
  EXPECT_EQ(j["frames"][3]["image"], "images/003.png");
  EXPECT_FALSE(j["frames"][0].contains("position_m"));  // No camera height given.
  EXPECT_FALSE(j.contains("notice"));
  const cv::Mat view = ReadColourImage(dir / "out/images/001.png");
  ASSERT_EQ(view.size(), cv::Size(160, 120));
  // View 1 looks at yaw 90° (−X): three quarters across the panorama.
  EXPECT_NEAR(view.at<cv::Vec3b>(60, 80)[0], 384 / 2, 2);
  EXPECT_NEAR(view.at<cv::Vec3b>(60, 80)[2], 128, 2);
  EXPECT_FALSE(fs::exists(dir / "out/labels"));
}

TEST(WritePanoViews, WritesLabelsOverlaysAndTruthForAnAnnotatedPanorama) {
  const fs::path dir = FreshDir("zind");
  const fs::path pano = WriteGradientPanorama(dir);
  const ZindPanorama room = Room(pano);
  const PanoViewsSummary s =
      WritePanoViews(pano, dir / "out", {.turn = {.views = 2, .yaw_step_deg = 180}, .overlays = true}, &room);
  EXPECT_TRUE(s.labels);
  const nlohmann::json j = nlohmann::json::parse(ReadFile(dir / "out/capture.json"));
  EXPECT_EQ(j["notice"], kZindNotice);
  EXPECT_EQ(j["source"]["zind"]["pano"], "floor_01/complete_room_01/partial_room_01/pano_1");
  EXPECT_EQ(j["frames"][1]["position_m"], nlohmann::json({0.0, 0.0, 1.4}));
  EXPECT_EQ(j["frames"][1]["labels"], "labels/001.png");
  const cv::Mat labels = ReadLabelImage(dir / "out/labels/000.png");
  EXPECT_EQ(labels.at<std::uint8_t>(240, 320), 2);  // View 0 looks at the door.
  EXPECT_TRUE(fs::exists(dir / "out/overlays/001.png"));
  const Plan truth = ReadPlan(dir / "out/truth.json");
  EXPECT_EQ(truth.walls.size(), 4u);
  EXPECT_EQ(truth.openings.size(), 1u);
  EXPECT_DOUBLE_EQ(truth.rooms[0].area_m2, 16.0);
}

// A label panorama (a PNG of ids, or Blender's object-index EXR) is cut into
// the same views as the photo, nearest pixel.
TEST(WritePanoViews, CutsALabelPanoramaIntoTheViews) {
  const fs::path dir = FreshDir("label_pano");
  const fs::path pano = WriteGradientPanorama(dir);
  cv::Mat ids(256, 512, CV_8UC1, cv::Scalar(1));
  ids(cv::Rect(0, 0, 512, 64)).setTo(0);     // Ceiling band.
  ids(cv::Rect(240, 100, 32, 80)).setTo(2);  // A door facing yaw 180° (the middle column).
  cv::imwrite((dir / "ids.png").string(), ids);
  const PanoViewsOptions options{.turn = {.views = 2, .yaw_step_deg = 180}, .label_panorama = dir / "ids.png"};
  const PanoViewsSummary s = WritePanoViews(pano, dir / "out", options);
  EXPECT_TRUE(s.labels);
  EXPECT_FALSE(s.truth);
  EXPECT_EQ(s.BriefReport(), "2 views + labels → " + (dir / "out/capture.json").string());
  const nlohmann::json j = nlohmann::json::parse(ReadFile(dir / "out/capture.json"));
  EXPECT_EQ(j["frames"][1]["labels"], "labels/001.png");
  EXPECT_EQ(ReadLabelImage(dir / "out/labels/001.png").at<std::uint8_t>(240, 320), 2);  // View 1 looks at yaw 180°.
  EXPECT_EQ(ReadLabelImage(dir / "out/labels/000.png").at<std::uint8_t>(240, 320), 1);

  // The same ids as Blender writes them: floats in an OpenEXR.
  setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 0);
  cv::Mat floats;
  ids.convertTo(floats, CV_32F);
  cv::Mat rgb;
  cv::merge(std::vector<cv::Mat>{floats, floats, floats}, rgb);
  ASSERT_TRUE(cv::imwrite((dir / "index.exr").string(), rgb));
  const cv::Mat read = AsMat(ReadLabelEquirect(dir / "index.exr"));
  EXPECT_EQ(cv::countNonZero(read != ids), 0);
  // A value that is no label id is named with its pixel; so is a bad shape.
  rgb.at<cv::Vec3f>(7, 9) = cv::Vec3f(1.5f, 1.5f, 1.5f);
  ASSERT_TRUE(cv::imwrite((dir / "bad.exr").string(), rgb));
  try {
    ReadLabelEquirect(dir / "bad.exr");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pixel (9, 7) holds 1.5"), std::string::npos) << e.what();
  }
  cv::imwrite((dir / "square.png").string(), cv::Mat(64, 64, CV_8UC1, cv::Scalar(1)));
  EXPECT_THROW(ReadLabelEquirect(dir / "square.png"), InputError);
}

TEST(WritePanoViews, NamesAPanoramaThatIsNotOne) {
  const fs::path dir = FreshDir("bad");
  cv::imwrite((dir / "square.png").string(), cv::Mat(100, 100, CV_8UC3, cv::Scalar(1, 2, 3)));
  WriteFileAtomic(dir / "broken.jpg", "not a jpeg");
  try {
    WritePanoViews(dir / "square.png", dir / "out", {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems()[0].ToString(),
              (dir / "square.png").string() + ": 100x100 is not an equirectangular panorama (twice as wide as high)");
  }
  EXPECT_THROW(WritePanoViews(dir / "broken.jpg", dir / "out", {}), InputError);
  try {
    WritePanoViews(dir / "missing.jpg", dir / "out", {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "missing.jpg").string() + ": cannot read image: no such file");
  }
  EXPECT_THROW(WritePanoViews(dir / "square.png", dir / "out", {.camera_height_m = -1}), InvalidArgument);
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace asbuilt
