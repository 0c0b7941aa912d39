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

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <unistd.h>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/seg/model_io.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/seg/tflite_segmenter.h"
#include "asbuilt/seg/toy_rooms.h"
#include "asbuilt/seg/train.h"
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
  torch::Tensor pred = net->forward(RgbTensor({square}))[0].argmax(0).to(torch::kUInt8).contiguous();
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

// A 4:3 image read in one pass with the global pool over 480² squares
// (set_pool_window) labels its pixels as reading the two squares one by one
// and averaging their logits does, and closer than a plain pass.
TEST(TfliteNet, AWideImageWithItsPoolOverSquaresReadsAsItsSquaresDo) {
  SKIP_WITHOUT_TEACHERS();
  TfliteNet net(ReadTflite(kDeeplab), TfliteNetOptions{.stop_before_final_resize = false});
  net->eval();
  torch::NoGradGuard no_grad;
  cv::Mat bgr = cv::imread((kAdeSamples / "images/ADE_val_00001519.png").string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(bgr.empty());
  cv::resize(bgr, bgr, {640, 480}, 0, 0, cv::INTER_LINEAR);
  const torch::Tensor x = RgbTensor({bgr});
  torch::Tensor squares = torch::zeros({1, net->num_classes(), 480, 640});
  torch::Tensor count = torch::zeros({1, 1, 1, 640});
  for (int64_t start : {0, 160}) {
    squares.narrow(3, start, 480).add_(net->forward(x.narrow(3, start, 480)));
    count.narrow(3, start, 480).add_(1);
  }
  const torch::Tensor by_squares = (squares / count).argmax(1);
  const torch::Tensor plain = net->forward(x).argmax(1);
  net->set_pool_window(480);
  const torch::Tensor windowed = net->forward(x).argmax(1);
  net->set_pool_window(0);
  const double agree = windowed.eq(by_squares).to(torch::kFloat).mean().item<double>();
  const double agree_plain = plain.eq(by_squares).to(torch::kFloat).mean().item<double>();
  std::printf("agreement with the squares' reading: pool over squares %.4f, plain pass %.4f\n", agree, agree_plain);
  EXPECT_GE(agree, 0.95);
  EXPECT_GT(agree, agree_plain);
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
  torch::manual_seed(7);  // The input and target; unseeded, three steps sometimes missed (CPU load).
  // Resize targets and the global pool follow the input: 240×320 → logits at 1/4.
  torch::Tensor x = torch::rand({2, 3, 240, 320}) * 255;
  {
    torch::NoGradGuard no_grad;
    EXPECT_EQ(net->forward(x).sizes(), (std::vector<int64_t>{2, 32, 60, 80}));
  }
  // The float network is trainable: steps on a fixed target lower the loss.
  torch::optim::Adam sgd(net->parameters(), torch::optim::AdamOptions(1e-4));
  torch::Tensor target = torch::randint(0, 32, {2, 60, 80}, torch::kInt64);
  double first = 0, best = INFINITY;
  for (int step = 0; step < 5; ++step) {
    sgd.zero_grad();
    torch::Tensor loss = torch::nn::functional::cross_entropy(net->forward(x), target);
    loss.backward();
    sgd.step();
    if (step == 0)
      first = loss.item<double>();
    else
      best = std::min(best, loss.item<double>());
  }
  EXPECT_LT(best, first);
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
  // Its confidence is the mean probability of the classes it chose.
  std::vector<double> confidence;
  EXPECT_EQ(seg->SegmentBatch({bgr}, &confidence).size(), 1u);
  ASSERT_EQ(confidence.size(), 1u);
  cv::Mat top = p[0].clone();
  for (const cv::Mat& c : p) cv::max(top, c, top);
  EXPECT_NEAR(confidence[0], cv::mean(top)[0], 1e-4);
}

TEST(TfliteSegmenter, RefusesAFileThatIsNotAModel) {
  const fs::path bad = fs::temp_directory_path() / "asbuilt_not_a_model.tflite";
  WriteFileAtomic(bad, "this is not a flatbuffer");
  EXPECT_THROW(LoadSegmenter(bad), InputError);
  fs::remove(bad);
}

TEST(TfliteSegmenter, GroupsSumTheSoftmaxOfTheirMembers) {
  torch::manual_seed(5);
  torch::Tensor logits = torch::randn({2, 32, 3, 4});
  torch::Tensor grouped = torch::exp(GroupedLogProbabilities(logits));
  ASSERT_EQ(grouped.sizes(), (std::vector<int64_t>{2, 4, 3, 4}));
  torch::Tensor p = torch::softmax(logits, 1);
  EXPECT_NEAR(grouped[0][1][2][3].item<double>(), p[0][1][2][3].item<double>(), 1e-5);   // wall: class 1 alone
  EXPECT_NEAR(grouped[1][2][0][0].item<double>(), p[1][15][0][0].item<double>(), 1e-5);  // door: class 15
  EXPECT_NEAR(grouped.sum(1).min().item<double>(), 1.0, 1e-5);
  EXPECT_NEAR(grouped.sum(1).max().item<double>(), 1.0, 1e-5);
}

// A fine-tuned network is saved without the file it came from: its graph in
// the metadata, its weights as parameters; reloaded it computes the same.
TEST(TfliteSegmenter, ACheckpointRebuildsTheNetworkExactly) {
  SKIP_WITHOUT_TEACHERS();
  TfliteNet net(ReadTflite(kDeeplab), TfliteNetOptions{});
  {
    torch::NoGradGuard no_grad;
    for (auto& p : net->parameters()) p.add_(0.01);  // Not the file's weights any more.
  }
  const fs::path path = fs::temp_directory_path() / fmt::format("asbuilt_tflite_ckpt_{}.pt", ::getpid());
  nlohmann::json meta = {{"format", kTfliteCheckpointFormat},
                         {"config", TfliteCheckpointConfig(net)},
                         {"scale", {320, 240}},
                         {"crop", {256, 256}},
                         {"epoch", 1},
                         {"parameters", CountParameters(*net)}};
  SaveCheckpoint(path, *net, nullptr, meta);
  TfliteNet loaded = LoadTfliteNet(path);
  torch::NoGradGuard no_grad;
  torch::Tensor x = torch::rand({1, 3, 96, 128}) * 255;
  EXPECT_LT((loaded->forward(x) - net->forward(x)).abs().max().item<double>(), 1e-5);
  // It reads as a segmenter of its own kind.
  const SegmenterInfo info = ReadSegmenterInfo(path);
  EXPECT_EQ(info.config.arch, "tflite");
  EXPECT_EQ(info.scale_width_px, 320);
  EXPECT_NE(info.ToString().find("fine-tuned"), std::string::npos) << info.ToString();
  auto seg = LoadSegmenter(path);
  cv::Mat bgr(48, 64, CV_8UC3, cv::Scalar(200, 180, 160));
  EXPECT_EQ(seg->Segment(bgr).size(), bgr.size());
  fs::remove(path);
}

TEST(TfliteSegmenter, TrainsThroughTheClassGroupsAndResumes) {
  SKIP_WITHOUT_TEACHERS();
  const fs::path dir = fs::temp_directory_path() / fmt::format("asbuilt_tflite_train_{}", ::getpid());
  WriteToyRoomSet(dir / "data", 6, {.width_px = 64, .height_px = 48, .seed = 3});
  TrainOptions o;
  o.images_dir = dir / "data";
  o.out_dir = dir / "run";
  o.arch = "tflite";
  o.init = kDeeplab;
  o.epochs = 2;
  o.steps_per_epoch = 2;
  o.batch_size = 2;
  o.val_fraction = 0.34;
  o.augment = {.scale_width_px = 64, .scale_height_px = 48, .crop_width_px = 64, .crop_height_px = 48};
  o.threads = 1;
  o.stop_after_epoch = 1;
  TrainSummary first = TrainSegmenter(o);
  EXPECT_EQ(first.epochs_done, 1);
  o.stop_after_epoch = 0;
  TrainSummary second = TrainSegmenter(o);
  EXPECT_EQ(second.resumed_from_epoch, 1);
  EXPECT_EQ(second.epochs_done, 2);
  EXPECT_TRUE(std::isfinite(second.last_loss));
  EXPECT_EQ(ReadCheckpointMeta(o.out_dir / "best.pt").at("format"), kTfliteCheckpointFormat);
  EXPECT_EQ(LoadSegmenter(o.out_dir / "best.pt")->info().config.arch, "tflite");
  // Asking another architecture of the same folder is refused, not overwritten.
  o.arch = "tiny";
  EXPECT_THROW(TrainSegmenter(o), InvalidArgument);
  // A TFLite fine-tune needs the network to start from.
  o.arch = "tflite";
  o.init.clear();
  EXPECT_THROW(o.Check(), InvalidArgument);
  fs::remove_all(dir);
}

TEST(TfliteSegmenter, RefusesASegformerCheckpointAsATfliteNetwork) {
  const fs::path path = fs::temp_directory_path() / fmt::format("asbuilt_not_tflite_{}.pt", ::getpid());
  SegformerConfig config = SegformerConfigFor("tiny", 4);
  Segformer model(config);
  SaveCheckpoint(
      path, *model, nullptr,
      {{"format", kCheckpointFormat}, {"config", ConfigToJson(config)}, {"scale", {64, 48}}, {"crop", {64, 48}}});
  try {
    LoadTfliteNet(path);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a TFLite network"), std::string::npos) << e.what();
  }
  fs::remove(path);
}

}  // namespace
}  // namespace asbuilt
