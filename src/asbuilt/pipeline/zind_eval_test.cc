#include "asbuilt/pipeline/zind_eval.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "asbuilt/pano/layout_labels.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

const fs::path kSampleTour = fs::path(ASBUILT_SHARED_DATA_DIR) / "zind_sample_tour";

// Calls every pixel wall.
class AllWall : public Segmenter {
 public:
  cv::Mat Segment(const cv::Mat& bgr) override { return cv::Mat(bgr.size(), CV_8U, cv::Scalar(1)); }
  using Segmenter::SegmentBatch;
  std::vector<cv::Mat> SegmentBatch(const std::vector<cv::Mat>& bgr, std::vector<double>* confidence) override {
    if (confidence) confidence->assign(bgr.size(), 1.0);
    std::vector<cv::Mat> out;
    for (const cv::Mat& m : bgr) out.push_back(Segment(m));
    return out;
  }
  std::vector<cv::Mat> Probabilities(const cv::Mat&) override { return {}; }
  const SegmenterInfo& info() const override { return info_; }

 private:
  SegmenterInfo info_;
};

TEST(EvaluateOnZind, ScoresWholeViewsAndTheUpperHalfAndWritesAReport) {
  if (!fs::exists(kSampleTour / "zind_data.json")) GTEST_SKIP() << "shared data not present: " << kSampleTour;
  const ZindTour tour = ReadZindTour(kSampleTour);
  const fs::path out = fs::temp_directory_path() / "asbuilt_zind_eval_test";
  fs::remove_all(out);
  AllWall segmenter;
  const ZindEvalOptions options{.turn = {.width_px = 160, .height_px = 120, .fx = 100, .views = 4, .yaw_step_deg = 90},
                                .max_panoramas = 2};
  const ZindEvalSummary s = EvaluateOnZind(segmenter, tour, out, options);
  EXPECT_EQ(s.panoramas, 2);
  EXPECT_EQ(s.images, 8);
  ASSERT_EQ(s.per_panorama.size(), 2u);
  EXPECT_EQ(s.per_panorama[0].name, tour.BenchmarkPanoramas()[0]->Name());

  // All-wall predictions: wall recall 1, wall precision = the wall share of
  // the scored pixels, other classes never predicted.
  const ClassMetrics& wall = s.whole.classes[1];
  EXPECT_DOUBLE_EQ(wall.recall, 1.0);
  EXPECT_EQ(wall.pred_pixels, s.whole.confusion.total());
  EXPECT_DOUBLE_EQ(wall.precision, static_cast<double>(wall.label_pixels) / s.whole.confusion.total());
  EXPECT_EQ(s.whole.classes[2].pred_pixels, 0);
  // The upper half is the rows above the horizon: at most half the pixels
  // (fewer where passages are ignored), a subset of each class.
  EXPECT_EQ(s.upper.confusion.total() + s.upper.confusion.ignored_pixels(), 8 * 160 * 120);
  EXPECT_LE(s.upper.confusion.total(), 8 * 160 * 60);
  EXPECT_GT(s.upper.confusion.total(), 0.3 * s.whole.confusion.total());
  for (int c = 0; c < 4; ++c) EXPECT_LE(s.upper.classes[c].label_pixels, s.whole.classes[c].label_pixels);
  // Per-panorama matrices add up to the pooled one.
  EXPECT_EQ(s.per_panorama[0].whole.confusion.total() + s.per_panorama[1].whole.confusion.total(),
            s.whole.confusion.total());

  EXPECT_NE(s.ToMarkdown().find(kZindNotice), std::string::npos);
  EXPECT_NE(s.BriefReport().find("ZInD 2 panoramas, 8 views: mIoU"), std::string::npos) << s.BriefReport();
  EXPECT_EQ(nlohmann::json::parse(ReadFile(out / "metrics.json"))["notice"], kZindNotice);
  EXPECT_NE(ReadFile(out / "report.html").find(kZindNotice), std::string::npos);
  EXPECT_TRUE(fs::exists(out / s.per_panorama[1].sheet));
}

TEST(ZindEvalOptions, DefaultsAreIssue21sViews) {
  const ZindEvalOptions o;
  EXPECT_NO_THROW(o.Check());
  EXPECT_EQ(o.turn.views, 12);
  EXPECT_EQ(o.turn.width_px, 640);
  EXPECT_EQ(o.turn.height_px, 480);
  EXPECT_DOUBLE_EQ(o.turn.fx, 400);
  EXPECT_DOUBLE_EQ(o.turn.yaw_step_deg, 30);
  EXPECT_THROW(ZindEvalOptions{.batch_size = 0}.Check(), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
