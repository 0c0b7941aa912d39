#include "asbuilt/formats/capture.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

class CaptureFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("asbuilt_capture_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    for (const char* f : {"left/000.png", "right/000.png", "left/001.png", "right/001.png"}) {
      WriteFileAtomic(dir_ / f, "png");
    }
  }
  // Writes `text` as capture.json and returns every error message.
  std::vector<std::string> Errors(const std::string& text) {
    WriteFileAtomic(dir_ / "capture.json", text);
    std::vector<std::string> out;
    for (const Problem& p : CheckCaptureFile(dir_ / "capture.json").errors) {
      out.push_back(p.field_path + ": " + p.message);
    }
    return out;
  }
  std::string Valid(const std::string& frame0_yaw = "0.0", const std::string& baseline = "0.12") {
    return R"({"version": 1,
      "camera": {"width": 640, "height": 480, "fx": 400.0, "fy": 400.0, "cx": 319.5, "cy": 239.5,
                 "baseline_m": )" +
           baseline + R"(},
      "rectified": true,
      "frames": [{"index": 0, "left": "left/000.png", "right": "right/000.png",
                  "yaw_deg": )" +
           frame0_yaw + R"(, "position_m": [0.0, 0.0, 1.5]},
                 {"index": 1, "left": "left/001.png", "right": "right/001.png",
                  "yaw_deg": 30, "position_m": [0.0, 0.0, 1.5]}]})";
  }
  fs::path dir_;
};

TEST_F(CaptureFileTest, ValidFileReadsAndRoundTrips) {
  EXPECT_TRUE(Errors(Valid()).empty());
  Capture c = ReadCapture(dir_ / "capture.json");
  EXPECT_EQ(c.frames.size(), 2u);
  EXPECT_DOUBLE_EQ(c.frames[1].yaw_deg, 30.0);
  EXPECT_EQ(c.Resolve(c.frames[0].left), dir_ / "left/000.png");
  WriteCapture(c, dir_ / "copy.json");
  Capture d = ReadCapture(dir_ / "copy.json");
  EXPECT_EQ(CaptureToJson(c), CaptureToJson(d));
}

TEST_F(CaptureFileTest, WrongTypeGivesFieldPath) {
  auto errors = Errors(Valid("\"abc\""));
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0], "frames[0].yaw_deg: expected a number, got \"abc\"");
}

TEST_F(CaptureFileTest, MessageNamesTheFile) {
  WriteFileAtomic(dir_ / "capture.json", Valid("\"abc\""));
  try {
    ReadCapture(dir_ / "capture.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir_ / "capture.json").string() + ": frames[0].yaw_deg: expected a number, got \"abc\"");
  }
}

TEST_F(CaptureFileTest, RejectsZeroBaseline) {
  auto errors = Errors(Valid("0", "0"));
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0], "camera.baseline_m: baseline is zero: a stereo rig needs two separated cameras");
}

TEST_F(CaptureFileTest, RejectsDuplicateIndicesAndMissingImages) {
  std::string text = Valid();
  text.replace(text.find("\"index\": 1"), 10, "\"index\": 0");
  text.replace(text.find("right/001.png"), 13, "right/009.png");
  auto errors = Errors(text);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0], "frames[1].index: duplicate frame index 0");
  EXPECT_EQ(errors[1].rfind("frames[1].right: image not found: ", 0), 0u) << errors[1];
}

TEST_F(CaptureFileTest, RejectsNegativeSizesAndAbsurdIntrinsics) {
  std::string text = Valid();
  text.replace(text.find("\"width\": 640"), 12, "\"width\": -640");
  text.replace(text.find("\"fx\": 400.0"), 11, "\"fx\": 1e12");
  auto errors = Errors(text);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0], "camera.width: must be in 1..32768, got -640");
  EXPECT_EQ(errors[1], "camera.fx: focal length 1000000000000 px is absurd");
}

TEST_F(CaptureFileTest, ReportsEveryProblemNotJustTheFirst) {
  std::string text = Valid("null");
  text.replace(text.find("\"fy\": 400.0"), 11, "\"fy\": 0");
  auto errors = Errors(text);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0], "camera.fy: must be > 0, got 0");
  EXPECT_EQ(errors[1], "frames[0].yaw_deg: expected a number, got null");
}

TEST_F(CaptureFileTest, UnrectifiedNeedsCalibration) {
  std::string text = Valid();
  text.replace(text.find("\"rectified\": true"), 17, "\"rectified\": false");
  auto errors = Errors(text);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].rfind("calibration: required when rectified is false", 0), 0u);
}

TEST_F(CaptureFileTest, UnknownKeysAreOnlyWarnings) {
  std::string text = Valid();
  text.insert(1, "\"comment\": \"kitchen\", ");
  WriteFileAtomic(dir_ / "capture.json", text);
  FileReport report = CheckCaptureFile(dir_ / "capture.json");
  EXPECT_TRUE(report.errors.empty());
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_EQ(report.warnings[0].field_path, "comment");
}

TEST_F(CaptureFileTest, TruncatedJsonIsASyntaxError) {
  auto errors = Errors(Valid().substr(0, 80));
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("invalid JSON at line"), std::string::npos);
}

// A PNG header of the given size (enough for the reader's shape check).
std::string PngHeader(int width, int height) {
  std::string h = "\x89PNG\r\n\x1a\n";
  h += std::string("\0\0\0\x0dIHDR", 8);
  for (int v : {width, height}) {
    for (int shift : {24, 16, 8, 0}) h += static_cast<char>((v >> shift) & 0xFF);
  }
  return h + std::string(13, '\0');
}

TEST_F(CaptureFileTest, MonoCaptureReadsAndRoundTrips) {
  WriteFileAtomic(dir_ / "views/000.png", "png");
  const std::string text = R"({"version": 1, "kind": "mono",
      "camera": {"width": 640, "height": 480, "fx": 400.0, "fy": 400.0, "cx": 319.5, "cy": 239.5},
      "frames": [{"index": 0, "image": "views/000.png", "yaw_deg": 30, "position_m": [0, 0, 1.435]}]})";
  EXPECT_TRUE(Errors(text).empty());
  Capture c = ReadCapture(dir_ / "capture.json");
  EXPECT_EQ(c.kind, CaptureKind::kMono);
  ASSERT_EQ(c.frames.size(), 1u);
  EXPECT_EQ(c.frames[0].left, "views/000.png");
  EXPECT_TRUE(c.frames[0].right.empty());
  EXPECT_DOUBLE_EQ(c.frames[0].position_m.z(), 1.435);
  WriteCapture(c, dir_ / "copy.json");
  EXPECT_EQ(CaptureToJson(ReadCapture(dir_ / "copy.json")), CaptureToJson(c));
  EXPECT_EQ(CaptureToJson(c)["frames"][0]["image"], "views/000.png");
}

TEST_F(CaptureFileTest, PanoramaCaptureReadsAndRoundTrips) {
  WriteFileAtomic(dir_ / "pano.png", PngHeader(2048, 1024));
  EXPECT_TRUE(Errors(R"({"version": 1, "kind": "panorama", "panorama": "pano.png",
                         "position_m": [0, 0, 1.435], "yaw_deg": 10})")
                  .empty());
  Capture c = ReadCapture(dir_ / "capture.json");
  EXPECT_EQ(c.kind, CaptureKind::kPanorama);
  ASSERT_TRUE(c.panorama);
  EXPECT_EQ(c.panorama->image, "pano.png");
  EXPECT_DOUBLE_EQ(c.panorama->yaw_deg, 10.0);
  EXPECT_TRUE(c.frames.empty());
  WriteCapture(c, dir_ / "copy.json");
  EXPECT_EQ(CaptureToJson(ReadCapture(dir_ / "copy.json")), CaptureToJson(c));
  EXPECT_EQ(c.ToString(), "Capture(panorama pano.png, camera at (0.000, 0.000, 1.435) m, yaw 10.0°)");
}

TEST_F(CaptureFileTest, PanoramaThatIsNotTwoToOneIsRefused) {
  WriteFileAtomic(dir_ / "pano.png", PngHeader(2048, 1536));
  auto errors = Errors(R"({"version": 1, "kind": "panorama", "panorama": "pano.png", "position_m": [0, 0, 1.4]})");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("panorama: "), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find("is 2048x1536: an equirectangular panorama is twice as wide as high"), std::string::npos)
      << errors[0];
}

TEST_F(CaptureFileTest, PanoramaWithoutCameraHeightIsRefused) {
  WriteFileAtomic(dir_ / "pano.png", PngHeader(2048, 1024));
  auto missing = Errors(R"({"version": 1, "kind": "panorama", "panorama": "pano.png"})");
  ASSERT_EQ(missing.size(), 1u);
  EXPECT_EQ(missing[0].rfind("position_m: ", 0), 0u) << missing[0];
  auto zero = Errors(R"({"version": 1, "kind": "panorama", "panorama": "pano.png", "position_m": [0, 0, 0]})");
  ASSERT_EQ(zero.size(), 1u);
  EXPECT_EQ(zero[0],
            "position_m: the camera's height above the floor (z) must be > 0, got 0: walls are placed from it");
}

TEST_F(CaptureFileTest, MonoFrameWithBadYawOrNoHeightIsRefused) {
  WriteFileAtomic(dir_ / "views/000.png", "png");
  auto errors = Errors(R"({"version": 1, "kind": "mono",
      "camera": {"width": 640, "height": 480, "fx": 400.0, "fy": 400.0, "cx": 319.5, "cy": 239.5},
      "frames": [{"index": 0, "image": "views/000.png", "yaw_deg": "NaN", "position_m": [0, 0, -1]}]})");
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0].rfind("frames[0].yaw_deg: ", 0), 0u) << errors[0];
  EXPECT_EQ(errors[1].rfind("frames[0].position_m: the camera's height", 0), 0u) << errors[1];
}

TEST_F(CaptureFileTest, UnknownKindIsRefused) {
  auto errors = Errors(R"({"version": 1, "kind": "fisheye"})");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0], "kind: unknown kind \"fisheye\", expected stereo, mono or panorama");
}

TEST(CaptureFile, ReadsTheBlenderRoomsCaptures) {
  fs::path p = fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public/p01_rect_1door_2win/capture.json";
  if (!fs::exists(p)) GTEST_SKIP() << "shared data not present: " << p;
  Capture c = ReadCapture(p);
  EXPECT_EQ(c.frames.size(), 12u);
  EXPECT_EQ(c.camera.width, 640);
  EXPECT_DOUBLE_EQ(c.camera.baseline_m, 0.12);
  EXPECT_TRUE(c.frames[0].labels.has_value());
}

}  // namespace
}  // namespace asbuilt
