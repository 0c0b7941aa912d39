#include "asbuilt/labels/import.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/labels/label_io.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

const fs::path kData = ASBUILT_SHARED_DATA_DIR;

fs::path ImportTestDir() {
  fs::path dir = fs::temp_directory_path() /
                 ("asbuilt_import_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(dir);
  return dir;
}

struct Counts {
  int background, wall, door, window, ignore;
};
Counts Count(const cv::Mat& l) {
  return {cv::countNonZero(l == 0), cv::countNonZero(l == 1), cv::countNonZero(l == 2), cv::countNonZero(l == 3),
          cv::countNonZero(l == 255)};
}

// Expected counts below are the hand-checked raw histograms of the sample
// masks, computed independently of OpenCV with a pure-Python PNG decoder
// (zlib + PNG row filters; run once by hand):
//   ADE_val_00001519.png (768x512): 0: 6998, 1 wall: 76461, 15 door: 31868,
//     no 9 (windowpane) and no 59 (screen door); the rest is other classes.
//     Matches the README's fractions (wall 19.4 %, door 8.1 %, unlabelled 1.8 %).
//   ADE_val_00000001.png (683x512): 0: 3613, 1 wall: 14538, no door/window.
//   nyuv2 semantic40_ids.png (682x512): 0: 37350, 1 wall: 117397, 8 door:
//     104747, no 9 (window); also the README's decoded counts.
// background = width·height − wall − door − window − ignore.
TEST(ImportAde20k, LivingRoomSampleMapsToFourClasses) {
  fs::path mask = kData / "ade20k_sceneparsing_samples/annotations/ADE_val_00001519.png";
  if (!fs::exists(mask)) GTEST_SKIP() << "shared data not present";
  cv::Mat l = ImportAnnotation(mask, {.format = AnnotationFormat::kAde20k});
  ASSERT_EQ(l.size(), cv::Size(768, 512));
  Counts c = Count(l);
  EXPECT_EQ(c.wall, 76461);
  EXPECT_EQ(c.door, 31868);
  EXPECT_EQ(c.window, 0);
  EXPECT_EQ(c.ignore, 6998);
  EXPECT_EQ(c.background, 768 * 512 - 76461 - 31868 - 6998);
  // Unlabelled as background instead of ignore.
  cv::Mat b = ImportAnnotation(mask, {.format = AnnotationFormat::kAde20k, .unlabeled_to_ignore = false});
  EXPECT_EQ(Count(b).background, 768 * 512 - 76461 - 31868);
}

TEST(ImportAde20k, OutdoorSampleHasWallOnly) {
  fs::path mask = kData / "ade20k_sceneparsing_samples/annotations/ADE_val_00000001.png";
  if (!fs::exists(mask)) GTEST_SKIP() << "shared data not present";
  Counts c = Count(ImportAnnotation(mask, {.format = AnnotationFormat::kAde20k}));
  EXPECT_EQ(c.wall, 14538);
  EXPECT_EQ(c.door + c.window, 0);
  EXPECT_EQ(c.ignore, 3613);
}

TEST(ImportAde20k, MapsDoorsWindowsAndScreenDoors) {
  auto t = Ade20kMapping(true);
  EXPECT_EQ(t[1], 1);
  EXPECT_EQ(t[9], 3);
  EXPECT_EQ(t[15], 2);  // door;double;door
  EXPECT_EQ(t[59], 2);  // screen;door;screen
  EXPECT_EQ(t[64], 0);  // blind;screen is not a door
  EXPECT_EQ(t[0], 255);
  EXPECT_EQ(Ade20kMapping(false)[0], 0);
}

TEST(ImportNyu40, OfficeSampleMapsWallAndDoors) {
  fs::path mask = kData / "nyuv2_sample/semantic40_ids.png";
  if (!fs::exists(mask)) GTEST_SKIP() << "shared data not present";
  cv::Mat l = ImportAnnotation(mask, {.format = AnnotationFormat::kNyu40});
  ASSERT_EQ(l.size(), cv::Size(682, 512));
  Counts c = Count(l);
  EXPECT_EQ(c.wall, 117397);
  EXPECT_EQ(c.door, 104747);
  EXPECT_EQ(c.window, 0);
  EXPECT_EQ(c.ignore, 37350);
  EXPECT_EQ(c.background, 682 * 512 - 117397 - 104747 - 37350);
}

TEST(ImportNyu40, OutOfRangeIdIsAnInputError) {
  fs::path dir = ImportTestDir();
  fs::create_directories(dir);
  cv::Mat raw(4, 4, CV_8UC1, cv::Scalar(1));
  raw.at<std::uint8_t>(2, 3) = 57;
  cv::imwrite((dir / "m.png").string(), raw);
  try {
    ImportAnnotation(dir / "m.png", {.format = AnnotationFormat::kNyu40});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir / "m.png").string() + ": pixel (3, 2) has value 57, not a NYUv2-40 class id (0..40)");
  }
}

TEST(ImportLabelMe, RasterisesShapesInOrder) {
  // 40x30 image: a wall polygon over everything, a door rectangle, a window
  // polygon, then a "Ignore" rectangle on top of part of the door.
  const std::string json = R"({"version": "5.2.1", "flags": {}, "imagePath": "x.jpg", "imageData": null,
    "imageWidth": 40, "imageHeight": 30,
    "shapes": [
      {"label": "wall", "points": [[-0.5, -0.5], [39.5, -0.5], [39.5, 29.5], [-0.5, 29.5]], "shape_type": "polygon"},
      {"label": "Door", "points": [[4.5, 9.5], [14.5, 29.5]], "shape_type": "rectangle"},
      {"label": "windowpane", "points": [[19.5, 4.5], [29.5, 4.5], [29.5, 14.5], [19.5, 14.5]]},
      {"label": "lamp", "points": [[34.5, 0.5], [36.5, 0.5], [36.5, 2.5]], "shape_type": "polygon"},
      {"label": "__ignore__", "points": [[4.5, 9.5], [6.5, 11.5]], "shape_type": "rectangle"},
      {"label": "wall", "points": [[1, 1], [2, 2]], "shape_type": "line"}]})";
  cv::Mat l = ImportLabelMeJson(json, "x.json", {.format = AnnotationFormat::kLabelMe});
  ASSERT_EQ(l.size(), cv::Size(40, 30));
  Counts c = Count(l);
  // Door: pixel centres 5..14 × 10..29 = 10 × 20, minus the 2×2 ignore patch.
  EXPECT_EQ(c.door, 200 - 4);
  EXPECT_EQ(c.ignore, 4);
  EXPECT_EQ(c.window, 10 * 10);
  // "lamp" → background: the triangle's pixel centres (35, 1), (36, 1), (36, 2).
  EXPECT_EQ(c.background, 3);
  EXPECT_EQ(l.at<std::uint8_t>(1, 35), 0);
  EXPECT_EQ(l.at<std::uint8_t>(2, 36), 0);
  EXPECT_EQ(c.wall, 1200 - 200 - 100 - 3);
}

TEST(ImportLabelMe, CirclesCoverPixelCentresWithinTheRadius) {
  const std::string json = R"({"imageWidth": 20, "imageHeight": 20,
    "shapes": [{"label": "window", "points": [[10, 10], [10, 12.5]], "shape_type": "circle"}]})";
  cv::Mat l = ImportLabelMeJson(json, "c.json", {.format = AnnotationFormat::kLabelMe});
  // Integer points (dx, dy) with dx² + dy² < 6.25: 21 of them.
  EXPECT_EQ(cv::countNonZero(l == 3), 21);
}

TEST(ImportLabelMe, BadShapesAreNamedByField) {
  const std::string json = R"({"imageWidth": 40, "imageHeight": 0,
    "shapes": [{"label": "wall", "points": [[0, 0], [1, 1]], "shape_type": "polygon"},
               {"label": "door", "points": [[0, 0], [1, "a"]], "shape_type": "rectangle"}]})";
  try {
    ImportLabelMeJson(json, "x.json", {.format = AnnotationFormat::kLabelMe});
    FAIL();
  } catch (const InputError& e) {
    ASSERT_EQ(e.problems().size(), 3u) << e.what();
    EXPECT_EQ(e.problems()[0].ToString(), "x.json: imageHeight: must be in 1..32768, got 0");
    EXPECT_EQ(e.problems()[1].ToString(), "x.json: shapes[0].points: a polygon needs at least 3 points, got 2");
    EXPECT_EQ(e.problems()[2].field_path, "shapes[1].points[1][1]");
  }
}

TEST(ImportLabelMe, NamesMapCaseInsensitivelyWithOverrides) {
  ImportOptions o{.format = AnnotationFormat::kLabelMe};
  EXPECT_EQ(LabelMeNameToId(" Double Door ", o), 2);
  EXPECT_EQ(LabelMeNameToId("WINDOWS", o), 3);
  EXPECT_EQ(LabelMeNameToId("sofa", o), 0);
  o.labelme_names["glazing"] = 3;
  EXPECT_EQ(LabelMeNameToId("Glazing", o), 3);
}

TEST(ImportPalette, ColourMasksMapThroughThePalette) {
  fs::path dir = ImportTestDir();
  fs::create_directories(dir);
  Palette p;
  p.colours = {{1, {128, 0, 0}, 0}, {2, {0, 128, 0}, 0}, {3, {0, 0, 128}, 0}};  // VOC-like colours.
  cv::Mat mask(10, 10, CV_8UC3, cv::Scalar(0, 0, 0));
  mask.rowRange(0, 5).setTo(cv::Scalar(0, 0, 128));  // wall (BGR).
  mask.rowRange(5, 7).setTo(cv::Scalar(2, 126, 1));  // door, JPEG-ish.
  mask.rowRange(7, 8).setTo(cv::Scalar(128, 0, 0));  // window.
  cv::imwrite((dir / "m.png").string(), mask);
  Counts c = Count(ImportAnnotation(dir / "m.png", {.format = AnnotationFormat::kPalette, .palette = p}));
  EXPECT_EQ(c.wall, 50);
  EXPECT_EQ(c.door, 20);
  EXPECT_EQ(c.window, 10);
  EXPECT_EQ(c.background, 20);  // Black is beyond the threshold from every colour.
  EXPECT_THROW((ImportOptions{.format = AnnotationFormat::kPalette}.Check()), InvalidArgument);
}

TEST(ImportAnnotations, BatchReportsBadFilesAndCountsClasses) {
  fs::path dir = ImportTestDir();
  fs::create_directories(dir / "in");
  cv::imwrite((dir / "in/a.png").string(), cv::Mat(4, 4, CV_8UC1, cv::Scalar(1)));
  cv::imwrite((dir / "in/b.png").string(), cv::Mat(4, 4, CV_8UC1, cv::Scalar(15)));
  WriteFileAtomic(dir / "in/c.png", "garbage");
  std::vector<fs::path> inputs = ListAnnotationFiles(dir / "in", AnnotationFormat::kAde20k);
  ASSERT_EQ(inputs.size(), 3u);
  ImportSummary s = ImportAnnotations({.format = AnnotationFormat::kAde20k}, inputs, dir / "out");
  EXPECT_EQ(s.imported, 2);
  ASSERT_EQ(s.failed.size(), 1u);
  EXPECT_EQ(s.failed[0].file, (dir / "in/c.png").string());
  EXPECT_EQ(s.class_pixels[1], 16);
  EXPECT_EQ(s.class_pixels[2], 16);
  EXPECT_EQ(Count(ReadLabelImage(dir / "out/b.png")).door, 16);
  EXPECT_NE(s.BriefReport().find("imported 2 ade20k annotations"), std::string::npos) << s.BriefReport();
}

TEST(AnnotationFormat, ParsesNames) {
  EXPECT_EQ(ParseAnnotationFormat("nyuv2"), AnnotationFormat::kNyu40);
  EXPECT_EQ(ParseAnnotationFormat("labelme"), AnnotationFormat::kLabelMe);
  EXPECT_FALSE(ParseAnnotationFormat("coco"));
}

}  // namespace
}  // namespace asbuilt
