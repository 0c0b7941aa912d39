#include "asbuilt/seg/metrics.h"

#include <cmath>

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// A 3-class case worked by hand (rows: label, columns: prediction):
//            pred0 pred1 pred2
//   label0     5     1     0
//   label1     2     3     1
//   label2     0     0     0      (class 2 never labelled, predicted once)
// class 0: I=5, pred=7, label=6, U=8 → IoU 5/8, P 5/7, R 5/6
// class 1: I=3, pred=4, label=6, U=7 → IoU 3/7, P 3/4, R 1/2
// class 2: I=0, pred=1, label=0, U=1 → IoU 0, P 0, R NaN, F NaN
TEST(ComputeMetrics, MatchesHandComputedConfusionMatrix) {
  ConfusionMatrix cm(3);
  cm.Add(0, 0, 5);
  cm.Add(0, 1, 1);
  cm.Add(1, 0, 2);
  cm.Add(1, 1, 3);
  cm.Add(1, 2, 1);
  SegmentationMetrics m = ComputeMetrics(cm, {"a", "b", "c"});
  ASSERT_EQ(m.classes.size(), 3u);
  EXPECT_DOUBLE_EQ(m.classes[0].iou, 5.0 / 8);
  EXPECT_DOUBLE_EQ(m.classes[0].precision, 5.0 / 7);
  EXPECT_DOUBLE_EQ(m.classes[0].recall, 5.0 / 6);
  EXPECT_DOUBLE_EQ(m.classes[0].fscore, 2 * (5.0 / 7) * (5.0 / 6) / (5.0 / 7 + 5.0 / 6));
  EXPECT_DOUBLE_EQ(m.classes[1].iou, 3.0 / 7);
  EXPECT_DOUBLE_EQ(m.classes[1].precision, 3.0 / 4);
  EXPECT_DOUBLE_EQ(m.classes[1].recall, 0.5);
  EXPECT_DOUBLE_EQ(m.classes[2].iou, 0.0);
  EXPECT_DOUBLE_EQ(m.classes[2].precision, 0.0);
  EXPECT_TRUE(std::isnan(m.classes[2].recall));
  EXPECT_TRUE(std::isnan(m.classes[2].fscore));
  // nanmean: IoU over 3 classes, recall and F-score over 2.
  EXPECT_DOUBLE_EQ(m.miou, (5.0 / 8 + 3.0 / 7 + 0.0) / 3);
  EXPECT_DOUBLE_EQ(m.mprecision, (5.0 / 7 + 3.0 / 4 + 0.0) / 3);
  EXPECT_DOUBLE_EQ(m.mrecall, (5.0 / 6 + 0.5) / 2);
  EXPECT_DOUBLE_EQ(m.mfscore, (m.classes[0].fscore + m.classes[1].fscore) / 2);
  EXPECT_DOUBLE_EQ(m.aacc, 8.0 / 12);
}

TEST(ComputeMetrics, ClassAbsentFromLabelsAndPredictionsIsExcluded) {
  ConfusionMatrix cm(4);
  cm.Add(0, 0, 10);
  cm.Add(1, 1, 10);
  SegmentationMetrics m = ComputeMetrics(cm);
  EXPECT_TRUE(std::isnan(m.classes[2].iou));
  EXPECT_TRUE(std::isnan(m.classes[3].iou));
  EXPECT_DOUBLE_EQ(m.miou, 1.0);
  EXPECT_DOUBLE_EQ(m.mfscore, 1.0);
  nlohmann::json j = m.ToJson();
  EXPECT_TRUE(j["classes"][2]["IoU"].is_null());
  EXPECT_NE(m.ToMarkdown().find("| door | nan |"), std::string::npos);
}

TEST(ConfusionMatrix, AddFromImagesSkipsIgnoreAndCounts) {
  cv::Mat label = (cv::Mat_<std::uint8_t>(2, 3) << 0, 1, 255, 2, 3, 3);
  cv::Mat pred = (cv::Mat_<std::uint8_t>(2, 3) << 0, 2, 1, 2, 3, 0);
  ConfusionMatrix cm(4);
  cm.Add(label, pred);
  EXPECT_EQ(cm.total(), 5);
  EXPECT_EQ(cm.ignored_pixels(), 1);
  EXPECT_EQ(cm.at(0, 0), 1);
  EXPECT_EQ(cm.at(1, 2), 1);
  EXPECT_EQ(cm.at(2, 2), 1);
  EXPECT_EQ(cm.at(3, 3), 1);
  EXPECT_EQ(cm.at(3, 0), 1);
  SegmentationMetrics m = ComputeMetrics(cm);
  EXPECT_DOUBLE_EQ(m.classes[3].iou, 0.5);  // I 1, pred 1, label 2.
  EXPECT_DOUBLE_EQ(m.classes[2].iou, 0.5);  // I 1, pred 2, label 1.
  EXPECT_DOUBLE_EQ(m.classes[1].iou, 0.0);
}

TEST(ConfusionMatrix, RejectsMismatchedSizes) {
  ConfusionMatrix cm(4);
  EXPECT_THROW(cm.Add(cv::Mat::zeros(2, 2, CV_8U), cv::Mat::zeros(3, 2, CV_8U)), InvalidArgument);
  EXPECT_THROW(cm.Add(cv::Mat::zeros(2, 2, CV_8U), cv::Mat(2, 2, CV_8U, cv::Scalar(7))), InvalidArgument);
}

TEST(SegmentationMetrics, BriefReportPrintsMeans) {
  ConfusionMatrix cm(4);
  cm.Add(1, 1, 4);
  SegmentationMetrics m = ComputeMetrics(cm);
  m.images = 1;
  EXPECT_EQ(m.BriefReport(), "mIoU 1.0000 mFscore 1.0000 mPrecision 1.0000 mRecall 1.0000 aAcc 1.0000 (1 image)");
}

}  // namespace
}  // namespace asbuilt
