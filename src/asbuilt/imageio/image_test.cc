#include "asbuilt/imageio/image.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

TEST(Image, NewImageIsZeroAndRowsArePacked) {
  Image image(5, 3, 3, PixelType::kU16);
  EXPECT_EQ(image.width(), 5);
  EXPECT_EQ(image.height(), 3);
  EXPECT_EQ(image.channels(), 3);
  EXPECT_EQ(image.row_bytes(), 30u);
  EXPECT_EQ(image.row_stride_bytes(), 30u);
  for (int y = 0; y < 3; ++y) {
    for (int i = 0; i < 15; ++i) EXPECT_EQ(image.Row<std::uint16_t>(y)[i], 0);
  }
  EXPECT_TRUE(Image().empty());
  EXPECT_TRUE(Image(0, 4, 1, PixelType::kU8).empty());
}

TEST(Image, CopiesSharePixelsAndClonesDoNot) {
  Image a(4, 2, 1, PixelType::kU8);
  Image shared = a;
  Image clone = a.Clone();
  a.Row<std::uint8_t>(1)[3] = 9;
  EXPECT_EQ(shared.Row<std::uint8_t>(1)[3], 9);
  EXPECT_EQ(clone.Row<std::uint8_t>(1)[3], 0);
  EXPECT_TRUE(a.SamePixels(shared));
  EXPECT_FALSE(a.SamePixels(clone));
  EXPECT_FALSE(a.SamePixels(Image(4, 2, 1, PixelType::kU16)));
}

TEST(Image, RejectsBadSizesAndChannelCounts) {
  EXPECT_THROW(Image(-1, 4, 1, PixelType::kU8), InvalidArgument);
  EXPECT_THROW(Image(4, 4, 0, PixelType::kU8), InvalidArgument);
  EXPECT_THROW(Image(4, 4, 5, PixelType::kF32), InvalidArgument);
  EXPECT_THROW(Image(4, 4, 1, PixelType::kU8, nullptr, 4), InvalidArgument);
}

TEST(Image, PrintsSizeChannelsAndType) {
  EXPECT_EQ(Image(640, 480, 3, PixelType::kU8).ToString(), "Image(640x480, 3 × 8-bit)");
  EXPECT_EQ(Image(2, 1, 1, PixelType::kF32).ToString(), "Image(2x1, 1 × 32-bit float)");
  EXPECT_EQ(Image().ToString(), "Image(empty)");
}

TEST(AsImage, SharesAMatsPixelsAndKeepsThemAlive) {
  Image image;
  {
    cv::Mat mat(3, 4, CV_16UC1, cv::Scalar(7));
    image = AsImage(mat);
    mat.at<std::uint16_t>(2, 1) = 1234;
  }  // The Mat header is gone; its buffer lives on in `image`.
  EXPECT_EQ(image.type(), PixelType::kU16);
  EXPECT_EQ(image.width(), 4);
  EXPECT_EQ(image.Row<std::uint16_t>(2)[1], 1234);
  EXPECT_EQ(image.Row<std::uint16_t>(0)[0], 7);
  EXPECT_TRUE(AsImage(cv::Mat()).empty());
  EXPECT_THROW(AsImage(cv::Mat(2, 2, CV_64F)), InvalidArgument);
}

TEST(AsImage, KeepsTheStrideOfARegionOfInterest) {
  cv::Mat big(6, 8, CV_8UC3, cv::Scalar(0, 0, 0));
  big.at<cv::Vec3b>(3, 4) = cv::Vec3b(1, 2, 3);
  const Image roi = AsImage(big(cv::Rect(2, 1, 4, 4)));
  EXPECT_EQ(roi.row_stride_bytes(), 24u);
  EXPECT_EQ(roi.Row<std::uint8_t>(2)[3 * 2 + 2], 3);  // (x 4, y 3) of `big`, BGR channel 2.
}

TEST(AsMat, ViewsTheSamePixelsBothWays) {
  Image image(3, 2, 3, PixelType::kF32);
  cv::Mat mat = AsMat(image);
  ASSERT_EQ(mat.type(), CV_32FC3);
  EXPECT_EQ(mat.size(), cv::Size(3, 2));
  mat.at<cv::Vec3f>(1, 2) = cv::Vec3f(0.5f, 1.5f, 2.5f);
  EXPECT_EQ(image.Row<float>(1)[2 * 3 + 1], 1.5f);
  image.Row<float>(0)[0] = 4.0f;
  EXPECT_EQ(mat.at<cv::Vec3f>(0, 0)[0], 4.0f);
  EXPECT_EQ(AsImage(mat).pixels().get(), image.pixels().get());
  EXPECT_TRUE(AsMat(Image()).empty());
}

TEST(AsMat, KeepsThePixelsAliveAfterTheImageIsGone) {
  cv::Mat mat;
  {
    Image image(4, 3, 1, PixelType::kU8);
    image.Row<std::uint8_t>(2)[3] = 42;
    mat = AsMat(image);
  }
  EXPECT_EQ(mat.at<std::uint8_t>(2, 3), 42);
  cv::Mat copy = mat;
  mat.release();
  EXPECT_EQ(copy.at<std::uint8_t>(2, 3), 42);
  copy.create(8, 8, CV_16UC1);  // A new buffer of another size comes from OpenCV's own allocator.
  copy.setTo(7);
  EXPECT_EQ(copy.at<std::uint16_t>(7, 7), 7);
}

}  // namespace
}  // namespace asbuilt
