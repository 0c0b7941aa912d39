#include "asbuilt/seg/segformer.h"

#include <gtest/gtest.h>

#include "asbuilt/seg/segformer_config.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// Parameter count of the architecture described in segformer.h, worked out
// layer by layer (weights + biases, LayerNorm/BatchNorm γ and β).
std::int64_t ExpectedEncoderParameters(const SegformerConfig& c) {
  std::int64_t n = 0;
  std::int64_t in = c.in_channels;
  for (int i = 0; i < 4; ++i) {
    const std::int64_t d = c.embed_dims[i], k = c.patch_sizes[i], r = c.sr_ratios[i], h = d * c.mlp_ratio;
    n += k * k * in * d + d + 2 * d;                // Patch embedding conv + LayerNorm.
    std::int64_t block = 2 * d;                     // norm1
    block += d * d + d;                             // q
    block += d * 2 * d + 2 * d;                     // kv
    block += d * d + d;                             // proj
    if (r > 1) block += r * r * d * d + d + 2 * d;  // Spatial reduction conv + LayerNorm.
    block += 2 * d;                                 // norm2
    block += d * h + h + 9 * h + h + h * d + d;     // Mix-FFN: fc1, 3×3 depthwise, fc2.
    n += c.depths[i] * block + 2 * d;               // Blocks + stage LayerNorm.
    in = d;
  }
  return n;
}

std::int64_t ExpectedDecoderParameters(const SegformerConfig& c) {
  const std::int64_t C = c.decoder_dim;
  std::int64_t n = 0;
  for (int d : c.embed_dims) n += d * C + 2 * C;  // 1×1 conv (no bias) + BN.
  n += 4 * C * C + 2 * C;                         // Fusion.
  n += C * c.num_classes + c.num_classes;         // Classifier.
  return n;
}

TEST(Segformer, ParameterCountsMatchPublishedConfigurations) {
  SetTorchThreads(1);
  // 150 classes (ADE20K), as in the paper and mmsegmentation's model zoo:
  // B0 3.8M (encoder 3.4M), B1 13.7M, B2 27.5M (paper Table 1, rounded).
  struct Case {
    const char* arch;
    std::int64_t encoder, total;
    double paper_total_m;
  };
  const Case cases[] = {
      {"b0", 3319392, 3753718, 3.8}, {"b1", 13151424, 13716822, 13.7}, {"b2", 24196288, 27465046, 27.5}};
  for (const Case& c : cases) {
    SegformerConfig config = SegformerConfigFor(c.arch, 150);
    Segformer model(config);
    EXPECT_EQ(CountParameters(*model->encoder), ExpectedEncoderParameters(config)) << c.arch;
    EXPECT_EQ(CountParameters(*model->decoder), ExpectedDecoderParameters(config)) << c.arch;
    EXPECT_EQ(CountParameters(*model->encoder), c.encoder) << c.arch;
    EXPECT_EQ(CountParameters(*model), c.total) << c.arch;
    EXPECT_NEAR(CountParameters(*model) / 1e6, c.paper_total_m, 0.15) << c.arch;
  }
}

TEST(Segformer, FeatureAndLogitShapes) {
  torch::NoGradGuard no_grad;
  Segformer model(SegformerConfigFor("b0", 4));
  model->eval();
  torch::Tensor x = torch::randn({2, 3, 64, 96});
  std::vector<torch::Tensor> f = model->encoder->forward(x);
  ASSERT_EQ(f.size(), 4u);
  EXPECT_EQ(f[0].sizes(), (std::vector<int64_t>{2, 32, 16, 24}));
  EXPECT_EQ(f[1].sizes(), (std::vector<int64_t>{2, 64, 8, 12}));
  EXPECT_EQ(f[2].sizes(), (std::vector<int64_t>{2, 160, 4, 6}));
  EXPECT_EQ(f[3].sizes(), (std::vector<int64_t>{2, 256, 2, 3}));
  EXPECT_EQ(model->forward(x).sizes(), (std::vector<int64_t>{2, 4, 16, 24}));
}

TEST(Segformer, InitialLossIsNearLogOfClassCount) {
  torch::manual_seed(0);
  Segformer model(SegformerConfigFor("tiny", 4));
  model->eval();
  torch::Tensor logits = model->forward(torch::randn({1, 3, 32, 32}));
  torch::Tensor y = torch::zeros({1, 8, 8}, torch::kInt64);
  // Eval-mode BatchNorm with fresh statistics does not normalise, hence the slack.
  EXPECT_NEAR(torch::nn::functional::cross_entropy(logits, y).item<double>(), std::log(4.0), 0.5);
}

TEST(SegformerConfig, UnknownArchAndBadFieldsAreRejected) {
  EXPECT_THROW(SegformerConfigFor("b9"), InvalidArgument);
  SegformerConfig c = SegformerConfigFor("b0");
  c.num_heads[2] = 3;  // 160 % 3 != 0
  EXPECT_THROW(c.Check(), InvalidArgument);
  EXPECT_EQ(SegformerConfigFor("b0").ToString(), "b0: dims 32/64/160/256, depths 2/2/2/2, decoder 256, 4 classes");
}

}  // namespace
}  // namespace asbuilt
