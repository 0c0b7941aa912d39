#include "asbuilt/seg/segformer.h"

#include <malloc.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <string>
#include <thread>

#include "asbuilt/seg/communicator.h"
#include "asbuilt/seg/sync_batch_norm.h"

namespace asbuilt {
namespace {
namespace nn = torch::nn;
namespace F = torch::nn::functional;

// (B, N, C) ↔ (B, C, H, W).
torch::Tensor ToMap(const torch::Tensor& x, int64_t h, int64_t w) {
  return x.transpose(1, 2).reshape({x.size(0), x.size(2), h, w});
}
torch::Tensor ToSeq(const torch::Tensor& x) { return x.flatten(2).transpose(1, 2); }

nn::LayerNorm MakeLayerNorm(int dim) { return nn::LayerNorm(nn::LayerNormOptions({dim}).eps(1e-6)); }

// mmsegmentation's MiT initialisation: truncated normal (σ 0.02) for linear
// layers, He-style normal (fan-out) for convolutions, unit LayerNorm.
void InitWeights(nn::Module& module) {
  torch::NoGradGuard no_grad;
  for (auto& m : module.modules(/*include_self=*/false)) {
    if (auto* linear = m->as<nn::Linear>()) {
      linear->weight.normal_(0.0, 0.02).clamp_(-0.04, 0.04);
      if (linear->bias.defined()) linear->bias.zero_();
    } else if (auto* conv = m->as<nn::Conv2d>()) {
      const auto& o = conv->options;
      double fan_out = static_cast<double>(o.kernel_size()->at(0) * o.kernel_size()->at(1) * o.out_channels()) /
                       static_cast<double>(o.groups());
      conv->weight.normal_(0.0, std::sqrt(2.0 / fan_out));
      if (conv->bias.defined()) conv->bias.zero_();
    } else if (auto* ln = m->as<nn::LayerNorm>()) {
      ln->weight.fill_(1.0);
      ln->bias.zero_();
    }
  }
}

}  // namespace

torch::Tensor DropPathImpl::forward(torch::Tensor x) {
  if (!is_training() || p_ <= 0.0) return x;
  double keep = 1.0 - p_;
  std::vector<int64_t> shape(x.dim(), 1);
  shape[0] = x.size(0);
  if (!comm_) {
    torch::Tensor mask = torch::empty(shape, x.options()).bernoulli_(keep);
    return x * mask / keep;
  }
  shape[0] *= comm_->world_size();
  torch::Tensor mask =
      torch::empty(shape, x.options()).bernoulli_(keep).narrow(0, comm_->rank() * x.size(0), x.size(0));
  return x * mask / keep;
}

OverlapPatchEmbedImpl::OverlapPatchEmbedImpl(int in_ch, int dim, int patch, int stride) {
  proj = register_module("proj", nn::Conv2d(nn::Conv2dOptions(in_ch, dim, patch).stride(stride).padding(patch / 2)));
  norm = register_module("norm", MakeLayerNorm(dim));
}

torch::Tensor OverlapPatchEmbedImpl::forward(torch::Tensor x, int64_t& h, int64_t& w) {
  x = proj->forward(x);
  h = x.size(2);
  w = x.size(3);
  return norm->forward(ToSeq(x));
}

EfficientAttentionImpl::EfficientAttentionImpl(int dim, int heads, int sr_ratio)
    : heads_(heads), sr_ratio_(sr_ratio), scale_(1.0 / std::sqrt(static_cast<double>(dim / heads))) {
  q = register_module("q", nn::Linear(dim, dim));
  kv = register_module("kv", nn::Linear(dim, 2 * dim));
  proj = register_module("proj", nn::Linear(dim, dim));
  if (sr_ratio > 1) {
    sr = register_module("sr", nn::Conv2d(nn::Conv2dOptions(dim, dim, sr_ratio).stride(sr_ratio)));
    sr_norm = register_module("sr_norm", MakeLayerNorm(dim));
  }
}

torch::Tensor EfficientAttentionImpl::forward(torch::Tensor x, int64_t h, int64_t w) {
  const int64_t b = x.size(0), n = x.size(1), c = x.size(2), d = c / heads_;
  torch::Tensor qh = q->forward(x).reshape({b, n, heads_, d}).permute({0, 2, 1, 3});
  // Reduce the key/value sequence by sr_ratio² (paper Eq. 2).
  torch::Tensor kv_in = x;
  if (sr_ratio_ > 1) kv_in = sr_norm->forward(ToSeq(sr->forward(ToMap(x, h, w))));
  const int64_t m = kv_in.size(1);
  torch::Tensor kvh = kv->forward(kv_in).reshape({b, m, 2, heads_, d}).permute({2, 0, 3, 1, 4});
  torch::Tensor attn = torch::softmax(torch::matmul(qh, kvh[0].transpose(-2, -1)) * scale_, -1);
  torch::Tensor out = torch::matmul(attn, kvh[1]).transpose(1, 2).reshape({b, n, c});
  return proj->forward(out);
}

MixFfnImpl::MixFfnImpl(int dim, int hidden) {
  fc1 = register_module("fc1", nn::Conv2d(nn::Conv2dOptions(dim, hidden, 1)));
  dwconv = register_module("dwconv", nn::Conv2d(nn::Conv2dOptions(hidden, hidden, 3).padding(1).groups(hidden)));
  fc2 = register_module("fc2", nn::Conv2d(nn::Conv2dOptions(hidden, dim, 1)));
}

torch::Tensor MixFfnImpl::forward(torch::Tensor x, int64_t h, int64_t w) {
  torch::Tensor y = dwconv->forward(fc1->forward(ToMap(x, h, w)));
  return ToSeq(fc2->forward(torch::gelu(y)));
}

MitBlockImpl::MitBlockImpl(int dim, int heads, int mlp_ratio, int sr_ratio, double drop_path_p) {
  norm1 = register_module("norm1", MakeLayerNorm(dim));
  attn = register_module("attn", EfficientAttention(dim, heads, sr_ratio));
  norm2 = register_module("norm2", MakeLayerNorm(dim));
  ffn = register_module("ffn", MixFfn(dim, dim * mlp_ratio));
  drop_path = register_module("drop_path", DropPath(drop_path_p));
}

torch::Tensor MitBlockImpl::forward(torch::Tensor x, int64_t h, int64_t w) {
  x = x + drop_path->forward(attn->forward(norm1->forward(x), h, w));
  return x + drop_path->forward(ffn->forward(norm2->forward(x), h, w));
}

MixTransformerImpl::MixTransformerImpl(const SegformerConfig& config) {
  int total_depth = 0;
  for (int d : config.depths) total_depth += d;
  int block_index = 0;
  int in_ch = config.in_channels;
  for (int i = 0; i < 4; ++i) {
    const std::string s = std::to_string(i);
    patch_embeds_.push_back(register_module(
        "patch_embed" + s, OverlapPatchEmbed(in_ch, config.embed_dims[i], config.patch_sizes[i], config.strides[i])));
    blocks_.emplace_back();
    for (int j = 0; j < config.depths[i]; ++j, ++block_index) {
      // Stochastic depth grows linearly with block index (as in mmseg).
      double p = total_depth > 1 ? config.drop_path_rate * block_index / (total_depth - 1) : 0.0;
      blocks_.back().push_back(register_module(
          "block" + s + "_" + std::to_string(j),
          MitBlock(config.embed_dims[i], config.num_heads[i], config.mlp_ratio, config.sr_ratios[i], p)));
    }
    norms_.push_back(register_module("norm" + s, MakeLayerNorm(config.embed_dims[i])));
    in_ch = config.embed_dims[i];
  }
}

std::vector<torch::Tensor> MixTransformerImpl::forward(torch::Tensor x) {
  std::vector<torch::Tensor> outs;
  for (int i = 0; i < 4; ++i) {
    int64_t h = 0, w = 0;
    x = patch_embeds_[i]->forward(x, h, w);
    for (auto& block : blocks_[i]) x = block->forward(x, h, w);
    x = ToMap(norms_[i]->forward(x), h, w);
    outs.push_back(x);
  }
  return outs;
}

SegformerHeadImpl::SegformerHeadImpl(const SegformerConfig& config) {
  const int c = config.decoder_dim;
  for (int i = 0; i < 4; ++i) {
    linear_c_.push_back(
        register_module("linear_c" + std::to_string(i),
                        nn::Sequential(nn::Conv2d(nn::Conv2dOptions(config.embed_dims[i], c, 1).bias(false)),
                                       nn::BatchNorm2d(c), nn::ReLU(true))));
  }
  fuse = register_module("fuse", nn::Sequential(nn::Conv2d(nn::Conv2dOptions(4 * c, c, 1).bias(false)),
                                                nn::BatchNorm2d(c), nn::ReLU(true)));
  dropout = register_module("dropout", nn::Dropout(config.decoder_dropout));
  classifier = register_module("classifier", nn::Conv2d(nn::Conv2dOptions(c, config.num_classes, 1)));
}

torch::Tensor SegformerHeadImpl::forward(const std::vector<torch::Tensor>& features) {
  const std::vector<int64_t> size = {features[0].size(2), features[0].size(3)};
  std::vector<torch::Tensor> up;
  // mmseg order: deepest first in the concatenation.
  for (int i = 3; i >= 0; --i) {
    torch::Tensor y = ConvBnRelu(linear_c_[i], features[i]);
    if (i > 0) {
      y = F::interpolate(y, F::InterpolateFuncOptions().size(size).mode(torch::kBilinear).align_corners(false));
    }
    up.push_back(y);
  }
  torch::Tensor fused = ConvBnRelu(fuse, torch::cat(up, 1));
  return classifier->forward(Dropout(fused));
}

torch::Tensor SegformerHeadImpl::ConvBnRelu(nn::Sequential& layers, const torch::Tensor& x) {
  if (!comm_ || !is_training()) return layers->forward(x);
  torch::Tensor y = layers->ptr(0)->as<nn::Conv2d>()->forward(x);
  return torch::relu(SyncBatchNorm(*layers->ptr(1)->as<nn::BatchNorm2d>(), y, *comm_));
}

torch::Tensor SegformerHeadImpl::Dropout(const torch::Tensor& x) {
  const double p = dropout->options.p();
  if (!comm_ || !is_training() || p <= 0) return dropout->forward(x);
  // As ATen's dropout draws its mask (bernoulli_(1 − p), ÷ (1 − p)), for the global batch.
  std::vector<int64_t> shape = x.sizes().vec();
  shape[0] *= comm_->world_size();
  torch::Tensor noise = torch::empty(shape, x.options()).bernoulli_(1 - p);
  noise.div_(1 - p);
  return x * noise.narrow(0, comm_->rank() * x.size(0), x.size(0));
}

SegformerImpl::SegformerImpl(const SegformerConfig& config) : config_(config) {
  config.Check();
  encoder = register_module("encoder", MixTransformer(config));
  decoder = register_module("decoder", SegformerHead(config));
  InitWeights(*this);
  // mmseg decode head: the classifier starts near zero (σ 0.01), so the
  // initial loss is ≈ ln(classes).
  torch::NoGradGuard no_grad;
  decoder->classifier_weight().normal_(0.0, 0.01);
}

torch::Tensor SegformerImpl::forward(torch::Tensor x) { return decoder->forward(encoder->forward(x)); }

void SegformerImpl::SetDataParallel(const std::shared_ptr<Communicator>& comm) {
  for (const auto& m : modules(/*include_self=*/false)) {
    if (auto* drop_path = m->as<DropPathImpl>()) drop_path->set_data_parallel(comm);
  }
  decoder->set_data_parallel(comm);
}

int64_t CountParameters(const torch::nn::Module& module) {
  int64_t n = 0;
  for (const auto& p : module.parameters()) n += p.numel();
  return n;
}

namespace {
std::atomic<bool> g_threads_configured{false};

// LibTorch's CPU tensors come straight from malloc, and a forward pass
// allocates and frees hundreds of activations of 1–300 MB. glibc serves
// blocks that large with mmap and unmaps them on free, so each is
// page-faulted in afresh: at 640×480, 7.4 s of kernel time in 17.7 s of
// CPU for 12 images; kept in the heap for reuse, 1.4 s and the pass 2×
// faster. The process then keeps its peak heap (up to 1 GiB of it free).
void KeepFreedTensorMemory() {
  static std::once_flag once;
  std::call_once(once, [] {
#ifdef __GLIBC__
    mallopt(M_MMAP_MAX, 0);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
  });
}
}  // namespace

void UseAllCores() {
  KeepFreedTensorMemory();
  if (g_threads_configured.exchange(true)) return;
  torch::set_num_threads(static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
}

void SetTorchThreads(int threads) {
  if (threads <= 0) {
    UseAllCores();
    return;
  }
  KeepFreedTensorMemory();
  g_threads_configured = true;
  torch::set_num_threads(threads);
}

}  // namespace asbuilt
