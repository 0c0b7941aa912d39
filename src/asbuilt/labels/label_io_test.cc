#include "asbuilt/labels/label_io.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

fs::path LabelIoTestDir() {
  fs::path dir = fs::temp_directory_path() /
                 ("asbuilt_label_io_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(dir);
  return dir;
}

TEST(LabelIo, WritesAndReadsBackExactly) {
  fs::path dir = LabelIoTestDir();
  cv::Mat labels(7, 9, CV_8UC1);
  for (int i = 0; i < 63; ++i) labels.data[i] = static_cast<std::uint8_t>(i % 4);
  labels.at<std::uint8_t>(3, 3) = 255;
  WriteLabelImage(dir / "sub/a.png", labels);
  cv::Mat back = ReadLabelImage(dir / "sub/a.png");
  EXPECT_EQ(cv::countNonZero(back != labels), 0);
  for (const auto& e : fs::directory_iterator(dir / "sub")) EXPECT_FALSE(IsAtomicTempName(e.path()));
}

TEST(LabelIo, ColourLabelImageIsRejectedNamingTheFile) {
  fs::path dir = LabelIoTestDir();
  fs::create_directories(dir);
  cv::imwrite((dir / "rgb.png").string(), cv::Mat(4, 4, CV_8UC3, cv::Scalar(1, 2, 3)));
  try {
    ReadLabelImage(dir / "rgb.png");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir / "rgb.png").string() + ": expected a single-channel 8-bit label PNG, got 3 channels, 8-bit");
  }
}

TEST(LabelIo, CorruptFileIsAnInputError) {
  fs::path dir = LabelIoTestDir();
  WriteFileAtomic(dir / "bad.png", "not a png");
  EXPECT_THROW(ReadLabelImage(dir / "bad.png"), InputError);
  EXPECT_THROW(ReadColourImage(dir / "bad.png"), InputError);
  EXPECT_THROW(ReadColourImage(dir / "missing.png"), InputError);
}

TEST(LabelIo, GreyImageReadsAsColour) {
  fs::path dir = LabelIoTestDir();
  fs::create_directories(dir);
  cv::imwrite((dir / "g.png").string(), cv::Mat(4, 4, CV_8UC1, cv::Scalar(77)));
  cv::Mat c = ReadColourImage(dir / "g.png");
  EXPECT_EQ(c.type(), CV_8UC3);
  EXPECT_EQ(c.at<cv::Vec3b>(1, 1), cv::Vec3b(77, 77, 77));
}

}  // namespace
}  // namespace asbuilt
