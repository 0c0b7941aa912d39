#include "asbuilt/seg/tflite_segmenter.h"

#include <cstring>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "asbuilt/formats/tflite.h"
#include "asbuilt/seg/model_io.h"
#include "asbuilt/seg/seg_data.h"
#include "asbuilt/seg/segformer.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace F = torch::nn::functional;

constexpr const char* kClassMap = "ADE20K-Top31: 1 wall, 15 door, 9 windowpane; the rest background";

class TfliteSegmenter : public Segmenter {
 public:
  TfliteSegmenter(TfliteNet net, SegmenterInfo info, SegmentOptions options)
      : net_(std::move(net)), info_(std::move(info)), options_(std::move(options)) {
    options_.Check();
    CheckArgument(options_.mode == "whole", "SegmentOptions.mode: TFLite segmenters run whole images only");
    if (options_.scale_width_px == 0) {
      options_.scale_width_px = info_.scale_width_px;
      options_.scale_height_px = info_.scale_height_px;
    }
  }

  cv::Mat Segment(const cv::Mat& bgr) override { return SegmentBatch({bgr}, nullptr).at(0); }

  using Segmenter::SegmentBatch;
  std::vector<cv::Mat> SegmentBatch(const std::vector<cv::Mat>& images, std::vector<double>* confidence) override {
    std::vector<cv::Mat> out;
    if (confidence) confidence->clear();
    for (const cv::Mat& im : images) {
      torch::Tensor p = GroupProbabilities(im);
      if (confidence) confidence->push_back(std::get<0>(p.max(0)).mean().item<double>());
      torch::Tensor pred = p.argmax(0).to(torch::kUInt8).contiguous();
      cv::Mat m(im.rows, im.cols, CV_8UC1);
      std::memcpy(m.data, pred.data_ptr(), m.total());
      out.push_back(m);
    }
    return out;
  }

  std::vector<cv::Mat> Probabilities(const cv::Mat& bgr) override { return ClassMaps(GroupProbabilities(bgr)); }

  const SegmenterInfo& info() const override { return info_; }

 private:
  // (4, H, W) probabilities of asbuilt's classes at the image's size.
  torch::Tensor GroupProbabilities(const cv::Mat& bgr) {
    CheckArgument(bgr.type() == CV_8UC3, "Segmenter: images must be 8-bit BGR (CV_8UC3)");
    UseAllCores();
    torch::NoGradGuard no_grad;
    const bool was_training = net_->is_training();
    net_->eval();
    cv::Size scaled = FitSize(bgr.size(), options_.scale_width_px, options_.scale_height_px);
    cv::Mat resized;
    cv::resize(bgr, resized, scaled, 0, 0, cv::INTER_LINEAR);
    torch::Tensor logits = Tiled(RgbTensor({resized}));
    net_->train(was_training);
    logits = F::interpolate(logits, F::InterpolateFuncOptions()
                                        .size(std::vector<int64_t>{bgr.rows, bgr.cols})
                                        .mode(torch::kBilinear)
                                        .align_corners(false));
    return torch::exp(GroupedLogProbabilities(logits))[0];
  }

  // The network's logits for (1, 3, H, W), upsampled to H × W. These networks
  // were trained on square crops; averaged over a whole tall or wide image
  // their global pools read it badly (the floor at the bottom of a tall
  // panorama view comes out as wall). An image whose sides differ by more
  // than a quarter is read as squares of its shorter side, 2/3 of a side
  // apart, their logits averaged. Up to 3:2 (a 4:3 view: two squares that
  // overlap by two thirds) one pass with those pools taken over the squares,
  // each row or column the mean of the squares over it
  // (TfliteNetImpl::set_pool_window), reads it as the squares do in two
  // thirds of the time. Beyond (a panorama's 1:2 views, three squares) the
  // pass sees across the squares' borders what each square alone does not,
  // and reads real rooms worse: the squares are read one by one.
  torch::Tensor Tiled(const torch::Tensor& x) {
    const int64_t H = x.size(2), W = x.size(3), side = std::min(H, W), length = std::max(H, W);
    if (length > side * 3 / 2) return Squares(x);
    struct Whole {  // The pools over the whole map again after this pass, however it ends.
      TfliteNet& net;
      ~Whole() { net->set_pool_window(0); }
    } whole{net_};
    if (length > side * 5 / 4) net_->set_pool_window(static_cast<int>(side));
    return Logits(x);
  }

  // The squares of the shorter side, 2/3 of a side apart, read one by one,
  // their logits averaged.
  torch::Tensor Squares(const torch::Tensor& x) {
    const int64_t H = x.size(2), W = x.size(3), side = std::min(H, W), length = std::max(H, W);
    const int64_t stride = std::max<int64_t>(1, side * 2 / 3);
    const int dim = H > W ? 2 : 3;
    torch::Tensor sum, count = torch::zeros({length});
    for (int64_t start = 0;; start += stride) {
      const int64_t s = std::min(start, length - side);
      torch::Tensor tile = Logits(x.narrow(dim, s, side));
      if (!sum.defined()) sum = torch::zeros({1, tile.size(1), H, W});
      sum.narrow(dim, s, side).add_(tile);
      count.narrow(0, s, side).add_(1);
      if (s + side >= length) break;
    }
    return sum / (dim == 2 ? count.view({1, 1, length, 1}) : count.view({1, 1, 1, length}));
  }

  // One pass, upsampled to the input's size.
  torch::Tensor Logits(const torch::Tensor& x) {
    return F::interpolate(net_->forward(x), F::InterpolateFuncOptions()
                                                .size(std::vector<int64_t>{x.size(2), x.size(3)})
                                                .mode(torch::kBilinear)
                                                .align_corners(false));
  }

  TfliteNet net_;
  SegmenterInfo info_;
  SegmentOptions options_;
};

// The info of a .tflite file read as it is (its declared input size).
SegmenterInfo InfoOfFile(const TfliteModel& model, const TfliteNet& net, const std::filesystem::path& path) {
  SegmenterInfo info;
  info.config.arch = "tflite";
  info.config.num_classes = 4;
  info.scale_width_px = net->input_width_px();
  info.scale_height_px = net->input_height_px();
  info.crop_width_px = info.scale_width_px;
  info.crop_height_px = info.scale_height_px;
  info.parameters = CountParameters(*net);
  info.metadata = {{"format", "tflite"},
                   {"file", path.filename().string()},
                   {"description", model.description},
                   {"source_classes", net->num_classes()},
                   {"class_map", kClassMap}};
  return info;
}

}  // namespace

bool IsTfliteFile(const std::filesystem::path& path) { return path.extension() == ".tflite"; }

int AsbuiltClassOfAde32(int ade_class) {
  switch (ade_class) {
    case 1:
      return 1;  // wall
    case 15:
      return 2;  // door; double door
    case 9:
      return 3;  // windowpane
    default:
      return 0;
  }
}

torch::Tensor RgbTensor(const std::vector<cv::Mat>& images) {
  std::vector<torch::Tensor> batch;
  for (const cv::Mat& bgr : images) {
    CheckArgument(bgr.type() == CV_8UC3, "RgbTensor: images must be 8-bit BGR (CV_8UC3)");
    cv::Mat rgb;
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    batch.push_back(
        torch::from_blob(rgb.data, {rgb.rows, rgb.cols, 3}, torch::kUInt8).permute({2, 0, 1}).to(torch::kFloat32));
  }
  return torch::stack(batch);
}

torch::Tensor GroupedLogProbabilities(const torch::Tensor& logits) {
  const torch::Tensor log_p = torch::log_softmax(logits, 1);
  std::vector<std::vector<int64_t>> members(4);
  for (int c = 0; c < logits.size(1); ++c) members[AsbuiltClassOfAde32(c)].push_back(c);
  std::vector<torch::Tensor> groups;
  for (auto& m : members) {
    torch::Tensor index = torch::from_blob(m.data(), {static_cast<int64_t>(m.size())}, torch::kInt64).clone();
    groups.push_back(torch::logsumexp(log_p.index_select(1, index), 1, /*keepdim=*/true));
  }
  return torch::cat(groups, 1);
}

TfliteNet LoadTfliteNet(const std::filesystem::path& path) {
  if (IsTfliteFile(path)) return TfliteNet(ReadTflite(path), TfliteNetOptions{});
  const nlohmann::json meta = ReadCheckpointMeta(path);
  if (meta.value("format", "") != kTfliteCheckpointFormat) {
    throw InputError(
        path.string(), "asbuilt_meta.format",
        fmt::format("a {} checkpoint, not a TFLite network fine-tuned by asbuilt", meta.value("format", "")));
  }
  if (!meta.contains("config") || !meta["config"].contains("graph")) {
    throw InputError(path.string(), "asbuilt_meta.config.graph", "missing: the network's graph");
  }
  TfliteNet net(TfliteGraphFromJson(meta["config"]["graph"], path.string()), TfliteNetOptions{});
  LoadWeights(path, *net, nullptr, /*strict=*/true);
  return net;
}

std::unique_ptr<Segmenter> MakeTfliteSegmenter(TfliteNet net, SegmenterInfo info, const SegmentOptions& options) {
  return std::make_unique<TfliteSegmenter>(std::move(net), std::move(info), options);
}

std::unique_ptr<Segmenter> LoadTfliteSegmenter(const std::filesystem::path& path, const SegmentOptions& options) {
  options.Check();
  TfliteModel model = ReadTflite(path);
  TfliteNet net(model, TfliteNetOptions{});
  SegmenterInfo info = InfoOfFile(model, net, path);
  return MakeTfliteSegmenter(net, std::move(info), options);
}

SegmenterInfo ReadTfliteSegmenterInfo(const std::filesystem::path& path) {
  TfliteModel model = ReadTflite(path);
  TfliteNet net(model, TfliteNetOptions{});
  return InfoOfFile(model, net, path);
}

nlohmann::json TfliteCheckpointConfig(const TfliteNet& net) {
  return {{"arch", "tflite"},
          {"num_classes", 4},
          {"source_classes", net->num_classes()},
          {"class_map", kClassMap},
          {"graph", TfliteGraphToJson(net->graph())}};
}

}  // namespace asbuilt
