#ifndef ASBUILT_SEG_SEGFORMER_H_
#define ASBUILT_SEG_SEGFORMER_H_

// SegFormer in LibTorch: the Mix Transformer encoder (MiT) and the all-MLP
// decoder. INTERNAL to seg/: it includes torch; other modules use
// segmenter.h / train.h, which do not.
//
// Layout follows mmsegmentation's MixVisionTransformer + SegformerHead:
//   stage i: OverlapPatchEmbed (conv k=patch, stride, pad k/2; LayerNorm)
//            → depth_i × [x + DropPath(Attn(LN(x))); x + DropPath(MixFFN(LN(x)))]
//            → LayerNorm → feature map (B, C_i, H/s_i, W/s_i)
//   Attn: efficient self-attention, K and V from a sequence reduced by a
//         conv of kernel = stride = sr_ratio (+ LayerNorm) (paper Eq. 2).
//   MixFFN: 1×1 conv → 3×3 depthwise conv → GELU → 1×1 conv (paper Eq. 3).
//   decoder: per stage 1×1 conv → BN → ReLU to C, upsample to H/4, concat,
//            1×1 conv (4C → C) → BN → ReLU, dropout, 1×1 conv → classes.
// Output logits are at 1/4 of the input resolution.

#include <torch/torch.h>

#include <memory>
#include <vector>

#include "asbuilt/seg/segformer_config.h"

namespace asbuilt {

class Communicator;

// Stochastic depth: in training, each sample's branch is dropped with
// probability p (and the kept ones scaled by 1/(1 − p)). In data-parallel
// training the mask is drawn for the global batch and this rank's rows are
// kept, so K ranks draw what one process does (SegformerImpl::SetDataParallel).
class DropPathImpl : public torch::nn::Module {
 public:
  explicit DropPathImpl(double p) : p_(p) {}
  torch::Tensor forward(torch::Tensor x);
  void set_data_parallel(std::shared_ptr<Communicator> comm) { comm_ = std::move(comm); }

 private:
  double p_;
  std::shared_ptr<Communicator> comm_;
};
TORCH_MODULE(DropPath);

class OverlapPatchEmbedImpl : public torch::nn::Module {
 public:
  OverlapPatchEmbedImpl(int in_ch, int dim, int patch, int stride);
  // (B, C, H, W) → (B, N, dim); writes the new H, W.
  torch::Tensor forward(torch::Tensor x, int64_t& h, int64_t& w);

 private:
  torch::nn::Conv2d proj{nullptr};
  torch::nn::LayerNorm norm{nullptr};
};
TORCH_MODULE(OverlapPatchEmbed);

class EfficientAttentionImpl : public torch::nn::Module {
 public:
  EfficientAttentionImpl(int dim, int heads, int sr_ratio);
  torch::Tensor forward(torch::Tensor x, int64_t h, int64_t w);

 private:
  int heads_, sr_ratio_;
  double scale_;
  torch::nn::Linear q{nullptr}, kv{nullptr}, proj{nullptr};
  torch::nn::Conv2d sr{nullptr};
  torch::nn::LayerNorm sr_norm{nullptr};
};
TORCH_MODULE(EfficientAttention);

class MixFfnImpl : public torch::nn::Module {
 public:
  MixFfnImpl(int dim, int hidden);
  torch::Tensor forward(torch::Tensor x, int64_t h, int64_t w);

 private:
  torch::nn::Conv2d fc1{nullptr}, dwconv{nullptr}, fc2{nullptr};
};
TORCH_MODULE(MixFfn);

class MitBlockImpl : public torch::nn::Module {
 public:
  MitBlockImpl(int dim, int heads, int mlp_ratio, int sr_ratio, double drop_path);
  torch::Tensor forward(torch::Tensor x, int64_t h, int64_t w);

 private:
  torch::nn::LayerNorm norm1{nullptr}, norm2{nullptr};
  EfficientAttention attn{nullptr};
  MixFfn ffn{nullptr};
  DropPath drop_path{nullptr};
};
TORCH_MODULE(MitBlock);

class MixTransformerImpl : public torch::nn::Module {
 public:
  explicit MixTransformerImpl(const SegformerConfig& config);
  // Four feature maps at strides 4, 8, 16, 32.
  std::vector<torch::Tensor> forward(torch::Tensor x);

 private:
  std::vector<OverlapPatchEmbed> patch_embeds_;
  std::vector<std::vector<MitBlock>> blocks_;
  std::vector<torch::nn::LayerNorm> norms_;
};
TORCH_MODULE(MixTransformer);

class SegformerHeadImpl : public torch::nn::Module {
 public:
  explicit SegformerHeadImpl(const SegformerConfig& config);
  torch::Tensor forward(const std::vector<torch::Tensor>& features);
  torch::Tensor& classifier_weight() { return classifier->weight; }
  void set_data_parallel(std::shared_ptr<Communicator> comm) { comm_ = std::move(comm); }

 private:
  // conv → BN → ReLU; in data-parallel training the BN is SyncBatchNorm.
  torch::Tensor ConvBnRelu(torch::nn::Sequential& layers, const torch::Tensor& x);
  // Dropout; in data-parallel training the mask is the global batch's rows of this rank.
  torch::Tensor Dropout(const torch::Tensor& x);

  std::shared_ptr<Communicator> comm_;
  std::vector<torch::nn::Sequential> linear_c_;
  torch::nn::Sequential fuse{nullptr};
  torch::nn::Dropout dropout{nullptr};
  torch::nn::Conv2d classifier{nullptr};
};
TORCH_MODULE(SegformerHead);

class SegformerImpl : public torch::nn::Module {
 public:
  explicit SegformerImpl(const SegformerConfig& config);
  // (B, 3, H, W) normalised RGB → (B, classes, ceil(H/4), ceil(W/4)) logits.
  torch::Tensor forward(torch::Tensor x);
  const SegformerConfig& config() const { return config_; }
  // Data-parallel training: this process is rank r of comm's K and its
  // batches are the r-th of K equal shares of a global batch. In training
  // mode, DropPath and dropout masks are drawn for the global batch (with
  // the same seed every rank's generator stays in step) and the decoder's
  // batch norms take the global batch's statistics, so the ranks together
  // compute what one process computes on the global batch. Null: one process
  // (the default; then nothing changes). Evaluation mode needs no other rank.
  void SetDataParallel(const std::shared_ptr<Communicator>& comm);
  MixTransformer encoder{nullptr};
  SegformerHead decoder{nullptr};

 private:
  SegformerConfig config_;
};
TORCH_MODULE(Segformer);

// Number of trainable parameters (BN running stats excluded).
int64_t CountParameters(const torch::nn::Module& module);

// Uses every core (LibTorch's default here is 1 thread; issue 6), unless
// SetTorchThreads() chose a count before. Note: under heavy CPU contention
// libgomp's spinning barriers make 2+ threads far slower than 1; run with
// OMP_WAIT_POLICY=passive (read by libgomp at start-up) or 1 thread.
void UseAllCores();
// Sets LibTorch's intra-op thread count (0 = every core) for this process.
void SetTorchThreads(int threads);

}  // namespace asbuilt

#endif  // ASBUILT_SEG_SEGFORMER_H_
