#include "asbuilt/render/photo_textures.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

// Writes a GIMP pattern (version 1) of `channels` 8-bit channels whose
// pixel (x, y) has channel c = 10 * c + x + 3 * y.
void WritePattern(const fs::path& path, int width, int height, int channels, const std::string& magic = "GPAT") {
  fs::create_directories(path.parent_path());
  const std::string name = "test pattern";
  const std::uint32_t header_size = 24 + static_cast<std::uint32_t>(name.size()) + 1;
  std::vector<unsigned char> bytes;
  auto put32 = [&](std::uint32_t v) {
    for (int shift : {24, 16, 8, 0}) bytes.push_back(static_cast<unsigned char>(v >> shift));
  };
  put32(header_size);
  put32(1);
  put32(width);
  put32(height);
  put32(channels);
  bytes.insert(bytes.end(), magic.begin(), magic.end());
  bytes.insert(bytes.end(), name.begin(), name.end());
  bytes.push_back(0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < channels; ++c) bytes.push_back(static_cast<unsigned char>(10 * c + x + 3 * y));
    }
  }
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

fs::path TempDir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("asbuilt_photo_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(ReadGimpPattern, ReadsRgbAndGreyPixelsAsBgr) {
  fs::path dir = TempDir("read");
  WritePattern(dir / "rgb.pat", 4, 3, 3);
  WritePattern(dir / "grey.pat", 2, 2, 1);
  const cv::Mat rgb = AsMat(ReadGimpPattern(dir / "rgb.pat"));
  ASSERT_EQ(rgb.cols, 4);
  ASSERT_EQ(rgb.rows, 3);
  // Pixel (2, 1): R = 2 + 3 = 5, G = 15, B = 25; stored B, G, R.
  EXPECT_EQ(rgb.at<cv::Vec3b>(1, 2), cv::Vec3b(25, 15, 5));
  const cv::Mat grey = AsMat(ReadGimpPattern(dir / "grey.pat"));
  EXPECT_EQ(grey.at<cv::Vec3b>(1, 1), cv::Vec3b(4, 4, 4));
  fs::remove_all(dir);
}

TEST(ReadGimpPattern, RejectsAWrongMagicNamingTheField) {
  fs::path dir = TempDir("magic");
  WritePattern(dir / "bad.pat", 2, 2, 3, "GIMP");
  try {
    ReadGimpPattern(dir / "bad.pat");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("header.magic"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(ClassifyPhoto, SortsDebianCollectionsByUse) {
  EXPECT_EQ(ClassifyPhoto("/usr/share/gimp/2.0/patterns/Wood/parque1.pat"), PhotoKind::kWood);
  EXPECT_EQ(ClassifyPhoto("/usr/share/gimp/2.0/patterns/Wood/bark.pat"), std::nullopt);
  EXPECT_EQ(ClassifyPhoto("/usr/share/gimp/2.0/patterns/Wood/corkboard.pat"), std::nullopt);
  EXPECT_EQ(ClassifyPhoto("/usr/share/gimp/2.0/patterns/Stone/marble1.pat"), PhotoKind::kStone);
  EXPECT_EQ(ClassifyPhoto("/usr/share/gimp/2.0/patterns/Stone/Craters.pat"), std::nullopt);
  EXPECT_EQ(ClassifyPhoto("/usr/share/gimp/2.0/patterns/Paper/paper.pat"), PhotoKind::kPaper);
  EXPECT_EQ(ClassifyPhoto("/usr/share/gimp/2.0/patterns/Legacy/warning.pat"), std::nullopt);
  EXPECT_EQ(ClassifyPhoto("/usr/share/blender/datafiles/studiolights/world/city.exr"), PhotoKind::kEnvironment);
  EXPECT_EQ(ClassifyPhoto("/usr/share/blender/datafiles/studiolights/world/interior.exr"), std::nullopt);
  EXPECT_EQ(ClassifyPhoto("/usr/share/blender/datafiles/studiolights/matcap/pearl.exr"), std::nullopt);
  EXPECT_EQ(ClassifyPhoto("/usr/share/backgrounds/lake.jpg"), PhotoKind::kView);
  EXPECT_EQ(ClassifyPhoto("/data/oak_floor.png"), PhotoKind::kWood);
  EXPECT_EQ(ClassifyPhoto("/data/readme.txt"), std::nullopt);
}

TEST(LoadPhotoLibrary, ReadsClassifiedFilesAndSkipsMissingFolders) {
  fs::path dir = TempDir("library");
  WritePattern(dir / "Wood" / "tiny.pat", 8, 8, 3);
  WritePattern(dir / "Legacy" / "skipped.pat", 8, 8, 3);
  fs::create_directories(dir / "backgrounds");
  cv::imwrite((dir / "backgrounds" / "view.png").string(), cv::Mat(6, 12, CV_8UC3, cv::Scalar(200, 150, 100)));
  PhotoLibrary library = LoadPhotoLibrary({.dirs = {dir / "absent", dir}});
  ASSERT_EQ(library.photos.size(), 2u) << library.ToString();
  EXPECT_EQ(library.OfKind(PhotoKind::kWood).size(), 1u);
  ASSERT_EQ(library.OfKind(PhotoKind::kView).size(), 1u);
  EXPECT_EQ(library.ToString(), "PhotoLibrary(1 wood, 0 stone, 0 fabric, 0 paper, 0 environment, 1 view)");
  // The view is stored linear RGB: sRGB 100 (red) → 0.127, 200 (blue) → 0.578.
  const Photo& view = *library.OfKind(PhotoKind::kView)[0];
  EXPECT_NEAR(view.mean.x(), 0.127, 0.002);
  EXPECT_NEAR(view.mean.z(), 0.578, 0.002);
  EXPECT_TRUE(LoadPhotoLibrary({.dirs = {dir / "absent"}}).empty());
  fs::remove_all(dir);
}

TEST(Photo, EquirectangularOutsideLooksUpAtTheTopRowAndDownAtTheBottom) {
  Photo p;
  p.kind = PhotoKind::kEnvironment;
  cv::Mat linear_rgb(8, 16, CV_32FC3, cv::Scalar(0.5, 0.5, 0.5));
  linear_rgb.row(0).setTo(cv::Scalar(1, 0, 0));
  linear_rgb.row(7).setTo(cv::Scalar(0, 0, 1));
  p.linear_rgb = AsImage(linear_rgb);
  EXPECT_NEAR(p.Outside(Vec3f(0, 0, 1), 0).x(), 1.0, 1e-5);
  EXPECT_NEAR(p.Outside(Vec3f(0, 0, -1), 0).z(), 1.0, 1e-5);
  EXPECT_NEAR(p.Outside(Vec3f(1, 0, 0), 0).y(), 0.5, 1e-5);
}

}  // namespace
}  // namespace asbuilt
