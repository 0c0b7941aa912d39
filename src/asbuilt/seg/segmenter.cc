#include "asbuilt/seg/segmenter.h"

#include <algorithm>
#include <map>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "asbuilt/seg/model_io.h"
#include "asbuilt/seg/seg_data.h"
#include "asbuilt/seg/tflite_segmenter.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace F = torch::nn::functional;

torch::Tensor Resize(const torch::Tensor& logits, int64_t h, int64_t w) {
  return F::interpolate(
      logits, F::InterpolateFuncOptions().size(std::vector<int64_t>{h, w}).mode(torch::kBilinear).align_corners(false));
}

class TorchSegmenter : public Segmenter {
 public:
  TorchSegmenter(Segformer model, SegmenterInfo info, SegmentOptions options)
      : model_(std::move(model)), info_(std::move(info)), options_(std::move(options)) {
    options_.Check();
    if (options_.scale_width_px == 0) options_.scale_width_px = info_.scale_width_px;
    if (options_.scale_height_px == 0) options_.scale_height_px = info_.scale_height_px;
  }

  cv::Mat Segment(const cv::Mat& bgr) override { return SegmentBatch({bgr}, nullptr).at(0); }

  using Segmenter::SegmentBatch;
  std::vector<cv::Mat> SegmentBatch(const std::vector<cv::Mat>& images, std::vector<double>* confidence) override {
    std::vector<cv::Mat> out(images.size());
    if (confidence) confidence->assign(images.size(), 0.0);
    // Group images by size so that each group is one batched pass.
    std::map<std::pair<int, int>, std::vector<size_t>> groups;
    for (size_t i = 0; i < images.size(); ++i) {
      CheckArgument(images[i].type() == CV_8UC3, "Segmenter: images must be 8-bit BGR (CV_8UC3)");
      groups[{images[i].rows, images[i].cols}].push_back(i);
    }
    for (const auto& [size, idx] : groups) {
      for (size_t start = 0; start < idx.size(); start += options_.batch_size) {
        std::vector<cv::Mat> batch;
        for (size_t k = start; k < std::min(idx.size(), start + options_.batch_size); ++k)
          batch.push_back(images[idx[k]]);
        torch::Tensor logits = Logits(batch);  // (B, C, H, W) at image size.
        torch::Tensor pred = logits.argmax(1).to(torch::kUInt8).contiguous();
        torch::Tensor sure;
        if (confidence) sure = std::get<0>(torch::softmax(logits, 1).max(1)).mean({1, 2});
        for (size_t k = 0; k < batch.size(); ++k) {
          if (confidence) (*confidence)[idx[start + k]] = sure[static_cast<int64_t>(k)].item<double>();
          cv::Mat m(size.first, size.second, CV_8UC1);
          std::memcpy(m.data, pred[static_cast<int64_t>(k)].data_ptr(), m.total());
          out[idx[start + k]] = m;
        }
      }
    }
    return out;
  }

  std::vector<cv::Mat> Probabilities(const cv::Mat& bgr) override {
    return ClassMaps(torch::softmax(Logits({bgr}), 1)[0]);
  }

  const SegmenterInfo& info() const override { return info_; }

 private:
  // Logits at the images' own size for same-size images.
  torch::Tensor Logits(const std::vector<cv::Mat>& images) {
    UseAllCores();
    torch::NoGradGuard no_grad;
    bool was_training = model_->is_training();
    model_->eval();
    const int h = images[0].rows, w = images[0].cols;
    cv::Size scaled = FitSize(images[0].size(), options_.scale_width_px, options_.scale_height_px);
    std::vector<cv::Mat> resized;
    for (const cv::Mat& im : images) {
      cv::Mat r;
      cv::resize(im, r, scaled, 0, 0, cv::INTER_LINEAR);
      resized.push_back(r);
    }
    torch::Tensor logits;
    if (options_.mode == "slide") {
      logits = Slide(resized);
    } else {
      torch::Tensor x = ImagesToTensor(resized);
      logits = Resize(model_->forward(x), scaled.height, scaled.width);
    }
    logits = Resize(logits, h, w);
    if (was_training) model_->train();
    return logits;
  }

  // mmseg slide inference: windows of the crop size, stride 2/3 crop.
  torch::Tensor Slide(const std::vector<cv::Mat>& images) {
    const int H = images[0].rows, W = images[0].cols;
    const int cw = std::min(W, info_.crop_width_px > 0 ? info_.crop_width_px : W);
    const int ch = std::min(H, info_.crop_height_px > 0 ? info_.crop_height_px : H);
    const int sw = std::max(1, cw * 2 / 3), sh = std::max(1, ch * 2 / 3);
    torch::Tensor x = ImagesToTensor(images);
    const int64_t B = x.size(0), C = info_.config.num_classes;
    torch::Tensor sum = torch::zeros({B, C, H, W}), count = torch::zeros({1, 1, H, W});
    std::vector<cv::Rect> windows;
    for (int y = 0;; y += sh) {
      int y0 = std::min(y, H - ch);
      for (int xw = 0;; xw += sw) {
        int x0 = std::min(xw, W - cw);
        windows.emplace_back(x0, y0, cw, ch);
        if (x0 + cw >= W) break;
      }
      if (y0 + ch >= H) break;
    }
    // Batch windows (all images × a few windows per pass).
    const size_t per_pass = std::max<size_t>(1, options_.batch_size / std::max<int64_t>(1, B));
    for (size_t start = 0; start < windows.size(); start += per_pass) {
      std::vector<torch::Tensor> crops;
      size_t end = std::min(windows.size(), start + per_pass);
      for (size_t k = start; k < end; ++k) {
        const cv::Rect& r = windows[k];
        crops.push_back(
            x.index({torch::indexing::Slice(), torch::indexing::Slice(), torch::indexing::Slice(r.y, r.y + r.height),
                     torch::indexing::Slice(r.x, r.x + r.width)}));
      }
      torch::Tensor out = Resize(model_->forward(torch::cat(crops, 0)), ch, cw);
      for (size_t k = start; k < end; ++k) {
        const cv::Rect& r = windows[k];
        std::vector<torch::indexing::TensorIndex> idx = {torch::indexing::Slice(), torch::indexing::Slice(),
                                                         torch::indexing::Slice(r.y, r.y + r.height),
                                                         torch::indexing::Slice(r.x, r.x + r.width)};
        sum.index(idx) += out.slice(0, static_cast<int64_t>(k - start) * B, static_cast<int64_t>(k - start + 1) * B);
        count.index(idx) += 1;
      }
    }
    return sum / count;
  }

  Segformer model_;
  SegmenterInfo info_;
  SegmentOptions options_;
};

}  // namespace

SegmenterInfo InfoFromMeta(const nlohmann::json& meta, const std::string& file) {
  SegmenterInfo info;
  if (meta.value("format", "") == kTfliteCheckpointFormat) {
    info.config.arch = "tflite";
    info.config.num_classes = 4;
  } else {
    info.config = ConfigFromMeta(meta, file);
  }
  try {
    info.scale_width_px = meta.at("scale").at(0).get<int>();
    info.scale_height_px = meta.at("scale").at(1).get<int>();
    info.crop_width_px = meta.at("crop").at(0).get<int>();
    info.crop_height_px = meta.at("crop").at(1).get<int>();
    info.epoch = meta.value("epoch", 0);
    info.parameters = meta.value("parameters", int64_t{0});
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "asbuilt_meta", e.what());
  }
  if (info.scale_width_px <= 0 || info.scale_height_px <= 0) {
    throw InputError(file, "asbuilt_meta.scale", "must be two positive sizes");
  }
  info.metadata = meta;
  return info;
}

SegmenterInfo ReadSegmenterInfo(const std::filesystem::path& path) {
  if (IsTfliteFile(path)) return ReadTfliteSegmenterInfo(path);
  return InfoFromMeta(ReadCheckpointMeta(path), path.string());
}

std::unique_ptr<Segmenter> MakeSegmenter(Segformer model, SegmenterInfo info, const SegmentOptions& options) {
  return std::make_unique<TorchSegmenter>(std::move(model), std::move(info), options);
}

std::unique_ptr<Segmenter> LoadSegmenter(const std::filesystem::path& path, const SegmentOptions& options) {
  options.Check();
  if (IsTfliteFile(path)) return LoadTfliteSegmenter(path, options);
  SegmenterInfo info = ReadSegmenterInfo(path);
  // A fine-tuned TFLite graph's checkpoint.
  if (info.config.arch == "tflite") return MakeTfliteSegmenter(LoadTfliteNet(path), std::move(info), options);
  Segformer model(info.config);
  LoadWeights(path, *model, nullptr, /*strict=*/true);
  info.parameters = CountParameters(*model);
  return MakeSegmenter(model, info, options);
}

bool SegmenterAvailable() { return true; }

}  // namespace asbuilt
