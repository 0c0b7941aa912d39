#include "asbuilt/seg/tflite_net.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace F = torch::nn::functional;

torch::Tensor FromFloats(std::vector<float> values, const std::vector<int>& shape) {
  std::vector<int64_t> sizes(shape.begin(), shape.end());
  return torch::from_blob(values.data(), sizes, torch::kFloat32).clone();
}

torch::Tensor Activate(const torch::Tensor& x, int activation) {
  switch (activation) {
    case 1:
      return torch::relu(x);
    case 2:
      return torch::clamp(x, -1.0, 1.0);
    case 3:
      return torch::clamp(x, 0.0, 6.0);
    default:
      return x;
  }
}

// A filter or bias: dequantised from the file, or zeros of its shape when the
// graph came without its constants (a checkpoint's graph: the values follow
// as parameters).
torch::Tensor ConstantOrZeros(const TfliteModel& model, int tensor) {
  const TfliteTensor& t = model.tensors.at(tensor);
  if (t.data.empty()) return torch::zeros(std::vector<int64_t>(t.shape.begin(), t.shape.end()));
  return FromFloats(DequantizedData(model, tensor), t.shape);
}

// TensorFlow's SAME padding for one axis: (before, after).
std::pair<int64_t, int64_t> SamePadding(int64_t in, int64_t kernel, int64_t stride, int64_t dilation) {
  const int64_t effective = (kernel - 1) * dilation + 1;
  const int64_t out = (in + stride - 1) / stride;
  const int64_t total = std::max<int64_t>(0, (out - 1) * stride + effective - in);
  return {total / 2, total - total / 2};
}

// Bilinear resampling of axis `dim` to `out` samples with TensorFlow's
// coordinate rules (align_corners, half_pixel_centers, or the legacy
// src = dst · in/out); differentiable in `x`.
torch::Tensor ResizeAxis(const torch::Tensor& x, int64_t dim, int64_t out, bool align_corners, bool half_pixel) {
  const int64_t in = x.size(dim);
  if (in == out) return x;
  std::vector<int64_t> i0(out), i1(out);
  std::vector<float> w(out);
  for (int64_t d = 0; d < out; ++d) {
    double src;
    if (align_corners && out > 1) {
      src = static_cast<double>(d) * (in - 1) / (out - 1);
    } else if (half_pixel) {
      src = std::max(0.0, (d + 0.5) * in / out - 0.5);
    } else {
      src = static_cast<double>(d) * in / out;
    }
    const int64_t lo = std::min<int64_t>(static_cast<int64_t>(std::floor(src)), in - 1);
    i0[d] = lo;
    i1[d] = std::min<int64_t>(lo + 1, in - 1);
    w[d] = static_cast<float>(src - lo);
  }
  auto index = [](std::vector<int64_t>& v) {
    return torch::from_blob(v.data(), {static_cast<int64_t>(v.size())}, torch::kInt64).clone();
  };
  std::vector<int64_t> shape(x.dim(), 1);
  shape[dim] = out;
  torch::Tensor weight = torch::from_blob(w.data(), {out}, torch::kFloat32).clone().view(shape);
  torch::Tensor a = x.index_select(dim, index(i0));
  torch::Tensor b = x.index_select(dim, index(i1));
  return a + (b - a) * weight;
}

// NHWC axis of a 4-D TFLite tensor → NCHW axis.
int64_t TorchAxis(int axis, std::size_t rank) {
  if (axis < 0) axis += static_cast<int>(rank);
  if (rank != 4) return axis;
  static constexpr int64_t kMap[4] = {0, 2, 3, 1};
  return kMap[axis];
}

}  // namespace

TfliteNetImpl::TfliteNetImpl(const TfliteModel& model, TfliteNetOptions options) : graph_(model), options_(options) {
  auto fail = [&](const std::string& field, const std::string& message) {
    throw InputError(graph_.file, field, message);
  };
  if (graph_.inputs.size() != 1)
    fail("subgraphs[0].inputs", fmt::format("{} inputs; a segmenter has one image", graph_.inputs.size()));
  input_tensor_ = graph_.inputs[0];
  const auto& in_shape = graph_.tensors[input_tensor_].shape;
  if (in_shape.size() != 4 || in_shape[3] != 3) fail("subgraphs[0].inputs", "the input is not one NHWC RGB image");
  input_h_ = in_shape[1], input_w_ = in_shape[2];

  // Quantisation of every tensor (activations are per-tensor).
  for (const TfliteTensor& t : graph_.tensors) {
    Quant q;
    if (t.type == static_cast<int>(TfliteType::kUInt8) && t.quantization.scale.size() == 1) {
      q.uint8 = true;
      q.scale = t.quantization.scale[0];
      q.zero_point = t.quantization.zero_point.empty() ? 0.f : static_cast<float>(t.quantization.zero_point[0]);
    }
    quant_.push_back(q);
  }

  // The logits: the input of a final ARG_MAX, or the graph's output.
  if (graph_.operators.empty()) fail("subgraphs[0].operators", "the graph has no operators");
  last_op_ = static_cast<int>(graph_.operators.size());
  if (graph_.operators.back().builtin_code == static_cast<int>(TfliteOp::kArgMax)) {
    --last_op_;
    logits_tensor_ = graph_.operators.back().inputs.at(0);
  } else {
    logits_tensor_ = graph_.outputs.at(0);
  }
  if (options_.stop_before_final_resize && last_op_ > 0 &&
      graph_.operators[last_op_ - 1].builtin_code == static_cast<int>(TfliteOp::kResizeBilinear) &&
      graph_.operators[last_op_ - 1].outputs.at(0) == logits_tensor_) {
    --last_op_;
    logits_tensor_ = graph_.operators[last_op_].inputs.at(0);
  }
  const auto& logits_shape = graph_.tensors[logits_tensor_].shape;
  if (logits_shape.size() != 4) fail("subgraphs[0].outputs", "the logits are not an NHWC map");
  num_classes_ = logits_shape[3];

  // Weights: dequantised, in torch's layouts, registered as parameters.
  weights_.resize(last_op_);
  biases_.resize(last_op_);
  for (int k = 0; k < last_op_; ++k) {
    const TfliteOperator& op = graph_.operators[k];
    const std::string field = fmt::format("subgraphs[0].operators[{}] ({})", k, TfliteOpName(op.builtin_code));
    switch (static_cast<TfliteOp>(op.builtin_code)) {
      case TfliteOp::kConv2d:
      case TfliteOp::kDepthwiseConv2d: {
        if (op.inputs.size() < 2) fail(field, "needs an input and a filter");
        const auto& filter = graph_.tensors[op.inputs[1]];
        if (filter.shape.size() != 4) fail(field, "the filter is not 4-D");
        torch::Tensor w = ConstantOrZeros(graph_, op.inputs[1]);
        // CONV_2D filters are OHWI, DEPTHWISE_CONV_2D filters 1HWO; torch wants OIHW.
        w = op.builtin_code == static_cast<int>(TfliteOp::kConv2d) ? w.permute({0, 3, 1, 2}) : w.permute({3, 0, 1, 2});
        weights_[k] = register_parameter(fmt::format("op{}_weight", k), w.contiguous());
        if (op.inputs.size() > 2 && op.inputs[2] >= 0) {
          biases_[k] = register_parameter(fmt::format("op{}_bias", k), ConstantOrZeros(graph_, op.inputs[2]));
        }
        break;
      }
      case TfliteOp::kAdd:
      case TfliteOp::kMul:
      case TfliteOp::kAveragePool2d:
      case TfliteOp::kMaxPool2d:
      case TfliteOp::kConcatenation:
      case TfliteOp::kResizeBilinear:
      case TfliteOp::kSplit:
      case TfliteOp::kQuantize:
      case TfliteOp::kDequantize:
      case TfliteOp::kRelu:
      case TfliteOp::kRelu6:
        break;
      default:
        fail(field, "this operator is not supported by asbuilt's TFLite port");
    }
    if ((op.builtin_code == static_cast<int>(TfliteOp::kSplit) ||
         op.builtin_code == static_cast<int>(TfliteOp::kResizeBilinear)) &&
        (op.inputs.size() < 2 ||
         graph_.tensors[op.inputs[op.builtin_code == static_cast<int>(TfliteOp::kSplit) ? 0 : 1]].data.empty())) {
      fail(field, "needs a constant axis / size tensor");
    }
  }
  if (parameters().empty()) fail("subgraphs[0].operators", "no convolution: not a segmentation network");
  for (auto& t : graph_.tensors) {
    // Filters and biases now live in the parameters; keep only small constants.
    if (t.data.size() > kTfliteSmallConstantBytes) t.data.clear(), t.data.shrink_to_fit();
  }
}

std::vector<torch::Tensor> TfliteNetImpl::head_parameters() const {
  for (int k = last_op_ - 1; k >= 0; --k) {
    if (!weights_[k].defined()) continue;
    std::vector<torch::Tensor> out = {weights_[k]};
    if (biases_[k].defined()) out.push_back(biases_[k]);
    return out;
  }
  return {};
}

torch::Tensor TfliteNetImpl::Requantize(const torch::Tensor& x, int tensor) const {
  const Quant& q = quant_[tensor];
  if (!q.uint8) return x;
  if (options_.emulate_uint8) {
    torch::Tensor level = torch::clamp(torch::floor(x / q.scale + 0.5) + q.zero_point, 0.0, 255.0);
    return (level - q.zero_point) * q.scale;
  }
  if (tensor == logits_tensor_) return x;  // Logits being trained must not saturate.
  return torch::clamp(x, (0.f - q.zero_point) * q.scale, (255.f - q.zero_point) * q.scale);
}

namespace {

// The mean of x (B, C, H, W) over windows of `share` of its length along
// `dim`, 2/3 of a window apart (the last one flush with the end), and per
// row or column the average of the means of the windows that cover it:
// (B, C, 1, W) or (B, C, H, 1).
torch::Tensor WindowedMean(const torch::Tensor& x, int dim, double share) {
  const int64_t length = x.size(dim);
  const int64_t side = std::clamp<int64_t>(std::llround(share * length), 1, length);
  const int64_t stride = std::max<int64_t>(1, side * 2 / 3);
  std::vector<int64_t> shape = {x.size(0), x.size(1), 1, 1};
  shape[dim] = length;
  torch::Tensor sum = torch::zeros(shape, x.options()), count = torch::zeros({length}, x.options());
  for (int64_t start = 0;; start += stride) {
    const int64_t s = std::min(start, length - side);
    sum.narrow(dim, s, side).add_(x.narrow(dim, s, side).mean({2, 3}, true));
    count.narrow(0, s, side).add_(1);
    if (s + side >= length) break;
  }
  return sum / (dim == 2 ? count.view({1, 1, length, 1}) : count.view({1, 1, 1, length}));
}

}  // namespace

torch::Tensor TfliteNetImpl::forward(const torch::Tensor& rgb) {
  TORCH_CHECK(rgb.dim() == 4 && rgb.size(1) == 3, "TfliteNet: input must be (B, 3, H, W)");
  const double ratio_h = static_cast<double>(rgb.size(2)) / input_h_;
  const double ratio_w = static_cast<double>(rgb.size(3)) / input_w_;
  std::vector<torch::Tensor> values(graph_.tensors.size());
  const Quant& in_q = quant_[input_tensor_];
  values[input_tensor_] = in_q.uint8 ? (rgb - in_q.zero_point) * in_q.scale : rgb / 255.0;

  for (int k = 0; k < last_op_; ++k) {
    const TfliteOperator& op = graph_.operators[k];
    const TfliteOptions& o = op.options;
    auto input = [&](int i) -> const torch::Tensor& { return values.at(op.inputs.at(i)); };
    std::vector<torch::Tensor> out;
    switch (static_cast<TfliteOp>(op.builtin_code)) {
      case TfliteOp::kConv2d:
      case TfliteOp::kDepthwiseConv2d: {
        torch::Tensor x = input(0);
        const torch::Tensor& w = weights_[k];
        const bool depthwise = op.builtin_code == static_cast<int>(TfliteOp::kDepthwiseConv2d);
        if (o.padding_same) {
          auto [top, bottom] = SamePadding(x.size(2), w.size(2), o.stride_h, o.dilation_h);
          auto [left, right] = SamePadding(x.size(3), w.size(3), o.stride_w, o.dilation_w);
          if (top + bottom + left + right > 0) x = F::pad(x, F::PadFuncOptions({left, right, top, bottom}));
        }
        const std::vector<int64_t> stride = {o.stride_h, o.stride_w}, dilation = {o.dilation_h, o.dilation_w};
        torch::Tensor y =
            torch::conv2d(x, w, biases_[k], stride, std::vector<int64_t>{0, 0}, dilation, depthwise ? x.size(1) : 1);
        out.push_back(Activate(y, o.activation));
        break;
      }
      case TfliteOp::kAdd:
        out.push_back(Activate(input(0) + input(1), o.activation));
        break;
      case TfliteOp::kMul:
        out.push_back(Activate(input(0) * input(1), o.activation));
        break;
      case TfliteOp::kAveragePool2d:
      case TfliteOp::kMaxPool2d: {
        const torch::Tensor& x = input(0);
        const auto& declared = graph_.tensors[op.inputs[0]].shape;
        const bool avg = op.builtin_code == static_cast<int>(TfliteOp::kAveragePool2d);
        torch::Tensor y;
        if (o.filter_h == declared[1] && o.filter_w == declared[2]) {
          // A pool over the whole declared map is a global pool at any input size.
          const int64_t in_long = std::max(rgb.size(2), rgb.size(3)), in_short = std::min(rgb.size(2), rgb.size(3));
          if (avg && pool_window_px_ > 0 && in_long > in_short * 5 / 4 && pool_window_px_ < in_long) {
            y = WindowedMean(x, rgb.size(2) > rgb.size(3) ? 2 : 3, static_cast<double>(pool_window_px_) / in_long);
          } else {
            y = avg ? x.mean({2, 3}, true) : x.amax({2, 3}, true);
          }
        } else {
          torch::Tensor padded = x;
          if (o.padding_same) {
            auto [top, bottom] = SamePadding(x.size(2), o.filter_h, o.stride_h, 1);
            auto [left, right] = SamePadding(x.size(3), o.filter_w, o.stride_w, 1);
            if (top + bottom + left + right > 0) {
              // TensorFlow's pools ignore the padding: average the window's real pixels only.
              padded = F::pad(x, F::PadFuncOptions({left, right, top, bottom})
                                     .value(avg ? 0.0 : -std::numeric_limits<double>::infinity()));
              if (avg) {
                torch::Tensor ones =
                    F::pad(torch::ones({1, 1, x.size(2), x.size(3)}), F::PadFuncOptions({left, right, top, bottom}));
                torch::Tensor sum = F::avg_pool2d(
                    padded, F::AvgPool2dFuncOptions({o.filter_h, o.filter_w}).stride({o.stride_h, o.stride_w}));
                torch::Tensor count = F::avg_pool2d(
                    ones, F::AvgPool2dFuncOptions({o.filter_h, o.filter_w}).stride({o.stride_h, o.stride_w}));
                out.push_back(Activate(sum / count, o.activation));
                break;
              }
            }
          }
          y = avg ? F::avg_pool2d(padded,
                                  F::AvgPool2dFuncOptions({o.filter_h, o.filter_w}).stride({o.stride_h, o.stride_w}))
                  : F::max_pool2d(padded,
                                  F::MaxPool2dFuncOptions({o.filter_h, o.filter_w}).stride({o.stride_h, o.stride_w}));
        }
        out.push_back(Activate(y, o.activation));
        break;
      }
      case TfliteOp::kConcatenation: {
        std::vector<torch::Tensor> parts;
        for (std::size_t i = 0; i < op.inputs.size(); ++i) parts.push_back(input(static_cast<int>(i)));
        out.push_back(
            Activate(torch::cat(parts, TorchAxis(o.axis, graph_.tensors[op.outputs[0]].shape.size())), o.activation));
        break;
      }
      case TfliteOp::kResizeBilinear: {
        const auto& size = graph_.tensors[op.inputs[1]].data;
        std::int32_t hw[2];
        std::memcpy(hw, size.data(), sizeof(hw));
        // The file's targets are for its declared input: scale them with the actual one.
        const auto h = static_cast<int64_t>(std::ceil(hw[0] * ratio_h - 1e-6));
        const auto w = static_cast<int64_t>(std::ceil(hw[1] * ratio_w - 1e-6));
        torch::Tensor y = ResizeAxis(input(0), 2, h, o.align_corners, o.half_pixel_centers);
        out.push_back(ResizeAxis(y, 3, w, o.align_corners, o.half_pixel_centers));
        break;
      }
      case TfliteOp::kSplit: {
        std::int32_t axis;
        std::memcpy(&axis, graph_.tensors[op.inputs[0]].data.data(), 4);
        const torch::Tensor& x = input(1);
        out = x.chunk(static_cast<int64_t>(op.outputs.size()),
                      TorchAxis(axis, graph_.tensors[op.inputs[1]].shape.size()));
        break;
      }
      case TfliteOp::kRelu:
        out.push_back(torch::relu(input(0)));
        break;
      case TfliteOp::kRelu6:
        out.push_back(torch::clamp(input(0), 0.0, 6.0));
        break;
      default:  // QUANTIZE, DEQUANTIZE: a change of grid only.
        out.push_back(input(0));
    }
    for (std::size_t i = 0; i < op.outputs.size(); ++i) values[op.outputs[i]] = Requantize(out.at(i), op.outputs[i]);
  }
  return values[logits_tensor_];
}

}  // namespace asbuilt
