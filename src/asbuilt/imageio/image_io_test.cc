#include "asbuilt/imageio/image_io.h"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

// A fresh folder per test, holding one file of each kind the readers meet.
fs::path ImageIoTestDir() {
  const fs::path dir =
      fs::temp_directory_path() /
      ("asbuilt_image_io_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  cv::imwrite((dir / "bgr.png").string(), cv::Mat(3, 4, CV_8UC3, cv::Scalar(10, 20, 30)));
  cv::imwrite((dir / "bgra.png").string(), cv::Mat(3, 4, CV_8UC4, cv::Scalar(10, 20, 30, 128)));
  cv::imwrite((dir / "grey.png").string(), cv::Mat(3, 4, CV_8UC1, cv::Scalar(77)));
  cv::imwrite((dir / "grey16.png").string(), cv::Mat(3, 4, CV_16UC1, cv::Scalar(1234)));
  cv::imwrite((dir / "bgr16.png").string(), cv::Mat(3, 4, CV_16UC3, cv::Scalar(100, 200, 300)));
  WriteFileAtomic(dir / "corrupt.png", "not a png");
  return dir;
}

// The message of the InputError that `read` throws, or "" when it throws none.
template <typename Read>
std::string ReadError(Read read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ReadColourImage, ReadsBgrGreyAndAlphaAsEightBitBgr) {
  const fs::path dir = ImageIoTestDir();
  const cv::Mat bgr = ReadColourImage(dir / "bgr.png");
  ASSERT_EQ(bgr.type(), CV_8UC3);
  EXPECT_EQ(bgr.size(), cv::Size(4, 3));
  EXPECT_EQ(bgr.at<cv::Vec3b>(2, 3), cv::Vec3b(10, 20, 30));
  EXPECT_EQ(ReadColourImage(dir / "grey.png").at<cv::Vec3b>(1, 1), cv::Vec3b(77, 77, 77));
  const cv::Mat alpha_dropped = ReadColourImage(dir / "bgra.png");
  ASSERT_EQ(alpha_dropped.type(), CV_8UC3);
  EXPECT_EQ(alpha_dropped.at<cv::Vec3b>(0, 0), cv::Vec3b(10, 20, 30));
}

TEST(ReadColourImage, NamesFileAndFieldOfEachFailure) {
  const fs::path dir = ImageIoTestDir();
  EXPECT_EQ(ReadError([&] { ReadColourImage(dir / "missing.png", "frames[3].left"); }),
            (dir / "missing.png").string() + ": frames[3].left: cannot read image: no such file");
  EXPECT_EQ(ReadError([&] { ReadColourImage(dir / "corrupt.png", "frames[3].left"); }),
            (dir / "corrupt.png").string() + ": frames[3].left: cannot decode image (not a PNG/JPEG/… or corrupt)");
  EXPECT_EQ(ReadError([&] { ReadColourImage(dir / "bgr16.png"); }),
            (dir / "bgr16.png").string() + ": expected an 8-bit colour image, got 16-bit");
}

TEST(ReadColourImage, ToneMapsALinearHdrPhoto) {
  const fs::path dir = ImageIoTestDir();
  // A linear gradient: the 98th percentile of the mean channel becomes white.
  cv::Mat linear(10, 100, CV_32FC3);
  for (int x = 0; x < 100; ++x) linear.col(x).setTo(cv::Scalar::all((x + 1) / 25.0));
  ASSERT_TRUE(cv::imwrite((dir / "room.hdr").string(), linear));
  const cv::Mat photo = ReadColourImage(dir / "room.hdr");
  ASSERT_EQ(photo.type(), CV_8UC3);
  EXPECT_EQ(photo.at<cv::Vec3b>(5, 99)[1], 255);  // Past the white point: clipped.
  EXPECT_EQ(photo.at<cv::Vec3b>(5, 97)[1], 255);  // The white point (98th of 100 levels).
  // Half of the white point is sRGB 0.5 → 188 (within the HDR format's rounding).
  EXPECT_NEAR(photo.at<cv::Vec3b>(5, 48)[1], 188, 2);
  EXPECT_LT(photo.at<cv::Vec3b>(5, 0)[1], photo.at<cv::Vec3b>(5, 10)[1]);
}

TEST(ReadColourImageAnyDepth, KeepsTheStoredDepth) {
  const fs::path dir = ImageIoTestDir();
  const cv::Mat deep = ReadColourImageAnyDepth(dir / "bgr16.png");
  ASSERT_EQ(deep.type(), CV_16UC3);
  EXPECT_EQ(deep.at<cv::Vec3w>(1, 2), cv::Vec3w(100, 200, 300));
  EXPECT_EQ(ReadColourImageAnyDepth(dir / "grey16.png").type(), CV_16UC3);
  EXPECT_EQ(ReadColourImageAnyDepth(dir / "bgr.png").type(), CV_8UC3);
  EXPECT_EQ(ReadError([&] { ReadColourImageAnyDepth(dir / "missing.hdr", "outside"); }),
            (dir / "missing.hdr").string() + ": outside: cannot read image: no such file");
  EXPECT_EQ(ReadError([&] { ReadColourImageAnyDepth(dir / "corrupt.png"); }),
            (dir / "corrupt.png").string() + ": cannot decode image (not a PNG/JPEG/… or corrupt)");
}

TEST(ReadGrayImage, ConvertsColourToGrey) {
  const fs::path dir = ImageIoTestDir();
  const cv::Mat grey = ReadGrayImage(dir / "bgr.png");
  ASSERT_EQ(grey.type(), CV_8UC1);
  EXPECT_NEAR(grey.at<std::uint8_t>(0, 0), 0.114 * 10 + 0.587 * 20 + 0.299 * 30, 1.0);
  EXPECT_EQ(ReadGrayImage(dir / "grey.png").at<std::uint8_t>(2, 3), 77);
  EXPECT_EQ(ReadError([&] { ReadGrayImage(dir / "missing.png", "left[0]"); }),
            (dir / "missing.png").string() + ": left[0]: cannot read image: no such file");
  EXPECT_EQ(ReadError([&] { ReadGrayImage(dir / "corrupt.png"); }),
            (dir / "corrupt.png").string() + ": cannot decode image (not a PNG/JPEG/… or corrupt)");
}

TEST(ReadLabelImage, ReadsSingleChannelIdsAndRefusesColour) {
  const fs::path dir = ImageIoTestDir();
  const cv::Mat labels = ReadLabelImage(dir / "grey.png");
  ASSERT_EQ(labels.type(), CV_8UC1);
  EXPECT_EQ(labels.at<std::uint8_t>(0, 0), 77);
  EXPECT_EQ(ReadError([&] { ReadLabelImage(dir / "bgr.png", "frames[0].labels"); }),
            (dir / "bgr.png").string() +
                ": frames[0].labels: expected a single-channel 8-bit label PNG, got 3 channels, 8-bit");
  EXPECT_EQ(ReadError([&] { ReadLabelImage(dir / "grey16.png"); }),
            (dir / "grey16.png").string() + ": expected a single-channel 8-bit label PNG, got 1 channel, 16-bit");
  EXPECT_EQ(ReadError([&] { ReadLabelImage(dir / "missing.png"); }),
            (dir / "missing.png").string() + ": cannot read image: no such file");
  EXPECT_EQ(ReadError([&] { ReadLabelImage(dir / "corrupt.png"); }),
            (dir / "corrupt.png").string() + ": cannot decode image (not a PNG/JPEG/… or corrupt)");
}

TEST(ReadDepthImage, ReadsSixteenBitMillimetresAndRefusesEightBit) {
  const fs::path dir = ImageIoTestDir();
  const cv::Mat depth = ReadDepthImage(dir / "grey16.png");
  ASSERT_EQ(depth.type(), CV_16UC1);
  EXPECT_EQ(depth.at<std::uint16_t>(2, 1), 1234);
  EXPECT_EQ(ReadError([&] { ReadDepthImage(dir / "grey.png", "frames[1].depth"); }),
            (dir / "grey.png").string() +
                ": frames[1].depth: expected a single-channel 16-bit (mm) or 32-bit float (m) depth image, got 1 "
                "channel, 8-bit");
  EXPECT_EQ(ReadError([&] { ReadDepthImage(dir / "missing.png"); }),
            (dir / "missing.png").string() + ": cannot read image: no such file");
  EXPECT_EQ(ReadError([&] { ReadDepthImage(dir / "corrupt.png"); }),
            (dir / "corrupt.png").string() + ": cannot decode image (not a PNG/JPEG/… or corrupt)");
}

TEST(ReadImageAsStored, KeepsDepthAndChannels) {
  const fs::path dir = ImageIoTestDir();
  EXPECT_EQ(ReadImageAsStored(dir / "bgra.png").type(), CV_8UC4);
  EXPECT_EQ(ReadImageAsStored(dir / "grey16.png").type(), CV_16UC1);
  EXPECT_EQ(ReadImageAsStored(dir / "bgr16.png").type(), CV_16UC3);
  EXPECT_EQ(ReadError([&] { ReadImageAsStored(dir / "missing.png", "--left"); }),
            (dir / "missing.png").string() + ": --left: cannot read image: no such file");
  EXPECT_EQ(ReadError([&] { ReadImageAsStored(dir / "corrupt.png"); }),
            (dir / "corrupt.png").string() + ": cannot decode image (not a PNG/JPEG/… or corrupt)");
}

TEST(CheckImageSize, NamesBothSizes) {
  const cv::Mat image(3, 4, CV_8UC1);
  EXPECT_NO_THROW(CheckImageSize(image, 4, 3, "a.png", "frames[0].labels", "the camera"));
  EXPECT_EQ(ReadError([&] { CheckImageSize(image, 8, 6, "a.png", "frames[0].labels", "the camera"); }),
            "a.png: frames[0].labels: image is 4x3, the camera is 8x6");
}

TEST(WriteImageAtomic, WritesLosslesslyIntoNewFoldersWithoutTempFiles) {
  const fs::path dir = ImageIoTestDir();
  cv::Mat depth(5, 7, CV_16UC1);
  for (int i = 0; i < 35; ++i) depth.at<std::uint16_t>(i / 7, i % 7) = static_cast<std::uint16_t>(i * 1000);
  WriteImageAtomic(dir / "new/sub/depth.png", depth);
  EXPECT_EQ(cv::countNonZero(ReadDepthImage(dir / "new/sub/depth.png") != depth), 0);
  for (const auto& e : fs::directory_iterator(dir / "new/sub")) EXPECT_FALSE(IsAtomicTempName(e.path()));
}

}  // namespace
}  // namespace asbuilt
