// The TFLite port against the original (issue 43). Reads ../shared/data at
// run time; skipped without it.
//
// What the port is checked against, and why (docs/seg.md "ADE20K teachers"):
// - the per-class IoUs the data's README measured with TensorFlow Lite on
//   the one indoor ADE20K image with ground truth (ADE_val_00001519): the
//   port reproduces them to ±0.02 for both networks;
// - MLPerf's recorded argmax on the 10 fixture images: only 70.6 % of pixels
//   agree, 99.1 % on the plainest image. The fixture sets are not one set:
//   labels32/ADE_val_00000001 is the house facade of the real
//   ADE_val_00000001 (it scores 0.40 mIoU against this port's output on that
//   photo, 0.007 against the recorded argmax), while fixtures/images holds an
//   armchair under that name; so the recorded argmax is checked as a floor
//   against regressions, not as the 99 % the issue asked for.

#include "asbuilt/seg/tflite_net.h"

#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/seg/segmenter.h"
#include "asbuilt/seg/tflite_segmenter.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

const fs::path kTeachers = fs::path(ASBUILT_SHARED_DATA_DIR) / "ade20k-teachers";
const fs::path kDeeplab = kTeachers / "deeplabv3_mnv2_ade20k32_uint8.tflite";
const fs::path kMosaic = kTeachers / "mosaic_r4_ade20k32_uint8.tflite";
const fs::path kAdeSamples = fs::path(ASBUILT_SHARED_DATA_DIR) / "ade20k_sceneparsing_samples";

#define SKIP_WITHOUT_TEACHERS() \
  if (!fs::exists(kDeeplab) || !fs::exists(kMosaic)) GTEST_SKIP() << "shared data not present: " << kTeachers

// (1, 3, H, W) RGB float 0..255 of an 8-bit BGR image.
torch::Tensor RgbTensor(const cv::Mat& bgr) {
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  return torch::from_blob(rgb.data, {1, rgb.rows, rgb.cols, 3}, torch::kUInt8).permute({0, 3, 1, 2}).to(torch::kFloat32);
}

// The quantised original's arithmetic, full-size logits.
TfliteNet FaithfulNet(const fs::path& file) {
  TfliteNet net(ReadTflite(file), TfliteNetOptions{.emulate_uint8 = true, .stop_before_final_resize = false});
  net->eval();
  return net;
}

// Class map (ADE ids) of `bgr` squashed to 512×512, as the README measured.
cv::Mat Argmax512(TfliteNet& net, const cv::Mat& bgr) {
  torch::NoGradGuard no_grad;
  cv::Mat square;
  cv::resize(bgr, square, {512, 512}, 0, 0, cv::INTER_LINEAR);
  torch::Tensor pred = net->forward(RgbTensor(square))[0].argmax(0).to(torch::kUInt8).contiguous();
  return cv::Mat(512, 512, CV_8U, pred.data_ptr()).clone();
}

TEST(TfliteNet, ReproducesTheTeachersIousOnTheIndoorAdeImage) {
  SKIP_WITHOUT_TEACHERS();
  const cv::Mat bgr = cv::imread((kAdeSamples / "images/ADE_val_00001519.png").string(), cv::IMREAD_COLOR);
  const cv::Mat truth = cv::imread((kAdeSamples / "annotations/ADE_val_00001519.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(bgr.empty() || truth.empty());
  // The README's TensorFlow Lite figures: wall, floor, ceiling, door.
  struct Expected {
    fs::path file;
    double wall, floor, ceiling, door;
  };
  for (const Expected& e : {Expected{kDeeplab, 0.52, 0.71, 0.83, 0.31}, Expected{kMosaic, 0.56, 0.67, 0.74, 0.54}}) {
    TfliteNet net = FaithfulNet(e.file);
    cv::Mat pred;
    cv::resize(Argmax512(net, bgr), pred, truth.size(), 0, 0, cv::INTER_NEAREST);
    auto iou = [&](int ade_class) {
      const cv::Mat a = pred == ade_class, b = truth == ade_class;
      return static_cast<double>(cv::countNonZero(a & b)) / cv::countNonZero(a | b);
    };
    std::printf("%s: wall %.3f floor %.3f ceiling %.3f door %.3f\n", e.file.filename().c_str(), iou(1), iou(4), iou(6),
                iou(15));
    EXPECT_NEAR(iou(1), e.wall, 0.02) << e.file;
    EXPECT_NEAR(iou(4), e.floor, 0.02) << e.file;
    EXPECT_NEAR(iou(6), e.ceiling, 0.02) << e.file;
    EXPECT_NEAR(iou(15), e.door, 0.03) << e.file;
  }
}

TEST(TfliteNet, AgreesWithMlperfsRecordedArgmaxWhereTheFixturesAgree) {
  SKIP_WITHOUT_TEACHERS();
  TfliteNet net = FaithfulNet(kDeeplab);
  std::int64_t agree = 0, total = 0;
  double plainest = 0;
  for (int i = 1; i <= 10; ++i) {
    const std::string name = fmt::format("ADE_val_{:08d}", i);
    const cv::Mat bgr = cv::imread((kTeachers / "fixtures/images" / (name + ".jpg")).string(), cv::IMREAD_COLOR);
    ASSERT_EQ(bgr.size(), cv::Size(512, 512)) << name;
    const cv::Mat pred = Argmax512(net, bgr);
    const std::string raw = ReadFile(kTeachers / "fixtures/deeplab_reference_argmax" / (name + ".raw"));
    ASSERT_EQ(raw.size(), 512u * 512u);
    const cv::Mat reference(512, 512, CV_8U, const_cast<char*>(raw.data()));
    const int same = 512 * 512 - cv::countNonZero(pred != reference);
    agree += same;
    total += 512 * 512;
    plainest = std::max(plainest, same / (512.0 * 512.0));
    std::printf("%s: %.2f %% of pixels agree\n", name.c_str(), 100.0 * same / (512 * 512));
  }
  const double agreement = static_cast<double>(agree) / total;
  std::printf("argmax agreement %.2f %% (best image %.2f %%)\n", 100 * agreement, 100 * plainest);
  EXPECT_GE(agreement, 0.70);
  EXPECT_GE(plainest, 0.99);
}

TEST(TfliteNet, RunsAnyInputSizeAndLearns) {
  SKIP_WITHOUT_TEACHERS();
  TfliteNet net(ReadTflite(kDeeplab), TfliteNetOptions{});
  // Resize targets and the global pool follow the input: 240×320 → logits at 1/4.
  torch::Tensor x = torch::rand({2, 3, 240, 320}) * 255;
  {
    torch::NoGradGuard no_grad;
    EXPECT_EQ(net->forward(x).sizes(), (std::vector<int64_t>{2, 32, 60, 80}));
  }
  // The float network is trainable: three steps lower the loss on a fixed target.
  torch::optim::Adam sgd(net->parameters(), torch::optim::AdamOptions(1e-4));
  torch::Tensor target = torch::randint(0, 32, {2, 60, 80}, torch::kInt64);
  double first = 0, last = 0;
  for (int step = 0; step < 3; ++step) {
    sgd.zero_grad();
    torch::Tensor loss = torch::nn::functional::cross_entropy(net->forward(x), target);
    loss.backward();
    sgd.step();
    (step == 0 ? first : last) = loss.item<double>();
  }
  EXPECT_LT(last, first);
}

TEST(TfliteSegmenter, MapsAdeClassesOntoOurs) {
  EXPECT_EQ(AsbuiltClassOfAde32(1), 1);
  EXPECT_EQ(AsbuiltClassOfAde32(15), 2);
  EXPECT_EQ(AsbuiltClassOfAde32(9), 3);
  EXPECT_EQ(AsbuiltClassOfAde32(4), 0);  // floor
  EXPECT_EQ(AsbuiltClassOfAde32(0), 0);  // other
}

TEST(TfliteSegmenter, SegmentsThroughLoadSegmenter) {
  SKIP_WITHOUT_TEACHERS();
  auto seg = LoadSegmenter(kDeeplab);
  cv::Mat bgr = cv::imread((kTeachers / "fixtures/images/ADE_val_00000001.jpg").string(), cv::IMREAD_COLOR);
  cv::resize(bgr, bgr, {320, 240});
  cv::Mat labels = seg->Segment(bgr);
  EXPECT_EQ(labels.size(), bgr.size());
  double lo, hi;
  cv::minMaxLoc(labels, &lo, &hi);
  EXPECT_LE(hi, 3);
  std::vector<cv::Mat> p = seg->Probabilities(bgr);
  ASSERT_EQ(p.size(), 4u);
  cv::Mat sum = p[0] + p[1] + p[2] + p[3];
  cv::minMaxLoc(sum, &lo, &hi);
  EXPECT_NEAR(lo, 1.0, 1e-4);
  EXPECT_NEAR(hi, 1.0, 1e-4);
  EXPECT_EQ(seg->info().metadata.at("format"), "tflite");
}

TEST(TfliteSegmenter, RefusesAFileThatIsNotAModel) {
  const fs::path bad = fs::temp_directory_path() / "asbuilt_not_a_model.tflite";
  WriteFileAtomic(bad, "this is not a flatbuffer");
  EXPECT_THROW(LoadSegmenter(bad), InputError);
  fs::remove(bad);
}

}  // namespace
}  // namespace asbuilt
