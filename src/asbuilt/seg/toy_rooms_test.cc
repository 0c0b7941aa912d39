#include "asbuilt/seg/toy_rooms.h"

#include <set>

#include <gtest/gtest.h>

namespace asbuilt {
namespace {

TEST(ToyRooms, ViewsAreDeterministicAndLabelled) {
  ToyRoomOptions o{.width_px = 64, .height_px = 48, .seed = 3};
  ToyView a = RenderToyRoom(o, 5), b = RenderToyRoom(o, 5), c = RenderToyRoom(o, 6);
  ASSERT_EQ(a.bgr.size(), cv::Size(64, 48));
  ASSERT_EQ(a.label.type(), CV_8UC1);
  EXPECT_EQ(cv::norm(a.bgr, b.bgr, cv::NORM_L1), 0);
  EXPECT_EQ(cv::norm(a.label, b.label, cv::NORM_L1), 0);
  EXPECT_GT(cv::norm(a.bgr, c.bgr, cv::NORM_L1), 0);
  std::set<int> seen;
  for (int i = 0; i < 20; ++i) {
    ToyView v = RenderToyRoom(o, i);
    for (int r = 0; r < v.label.rows; ++r)
      for (int col = 0; col < v.label.cols; ++col) seen.insert(v.label.at<std::uint8_t>(r, col));
  }
  EXPECT_EQ(seen, (std::set<int>{0, 1, 2, 3}));
}

TEST(ToyRoomOptions, RejectsTinySize) {
  EXPECT_THROW(RenderToyRoom({.width_px = 4, .height_px = 48}, 0), std::exception);
}

}  // namespace
}  // namespace asbuilt
