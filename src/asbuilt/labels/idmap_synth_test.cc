#include "asbuilt/labels/idmap_synth.h"

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

TEST(SyntheticRoomLabels, HasEveryClassAndIsSeeded) {
  cv::Mat a = SyntheticRoomLabels(320, 240, 3);
  cv::Mat b = SyntheticRoomLabels(320, 240, 3);
  cv::Mat c = SyntheticRoomLabels(320, 240, 4);
  EXPECT_EQ(cv::countNonZero(a != b), 0);
  EXPECT_GT(cv::countNonZero(a != c), 0);
  for (int id : {0, 1, 2}) EXPECT_GT(cv::countNonZero(a == id), 100) << id;
}

TEST(SynthesizeIdMap, DriftsAroundTheNominalColoursDeterministically) {
  cv::Mat labels = SyntheticRoomLabels(320, 240, 1);
  Palette nominal = Palette::Nominal();
  IdMapDriftOptions options{.seed = 5};
  cv::Mat a = SynthesizeIdMap(labels, nominal, options);
  cv::Mat b = SynthesizeIdMap(labels, nominal, options);
  ASSERT_EQ(a.type(), CV_8UC3);
  EXPECT_EQ(cv::countNonZero(cv::Mat(a != b).reshape(1)), 0);
  // Wall pixels: reddish, drifted (not all equal to the nominal colour), and
  // darker on average than nominal (brightness factors mostly < 1).
  cv::Scalar mean = cv::mean(a, labels == 1);
  EXPECT_GT(mean[2], 2 * mean[1]);  // R dominates G.
  EXPECT_LT(mean[2], 220);
  EXPECT_GT(mean[2], 100);
  cv::Mat wall_r;
  cv::extractChannel(a, wall_r, 2);
  double lo, hi;
  cv::minMaxLoc(wall_r, &lo, &hi, nullptr, nullptr, labels == 1);
  EXPECT_GT(hi - lo, 40);
}

TEST(IdMapDriftOptions, DefaultsAreValidAndBadOnesNamed) {
  EXPECT_NO_THROW(IdMapDriftOptions{}.Check());
  try {
    IdMapDriftOptions{.brightness_min = 0}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("IdMapDriftOptions.brightness_min = 0"), std::string::npos);
  }
}

}  // namespace
}  // namespace asbuilt
