#ifndef ASBUILT_SEG_SEGFORMER_CONFIG_H_
#define ASBUILT_SEG_SEGFORMER_CONFIG_H_

// SegFormer architectures (Xie et al., "SegFormer: Simple and Efficient
// Design for Semantic Segmentation with Transformers", NeurIPS 2021), as plain
// data: no LibTorch here, so any module may name an architecture.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace asbuilt {

// One Mix Transformer (MiT) encoder + all-MLP decoder configuration.
struct SegformerConfig {
  std::string arch = "b0";                             // Name: b0, b1, b2, tiny.
  int in_channels = 3;                                 // RGB.
  std::array<int, 4> embed_dims = {32, 64, 160, 256};  // Channels per stage.
  std::array<int, 4> num_heads = {1, 2, 5, 8};         // Attention heads per stage.
  std::array<int, 4> depths = {2, 2, 2, 2};            // Transformer blocks per stage.
  std::array<int, 4> sr_ratios = {8, 4, 2, 1};         // Spatial reduction of K, V.
  std::array<int, 4> patch_sizes = {7, 3, 3, 3};       // Overlapping patch embedding kernel.
  std::array<int, 4> strides = {4, 2, 2, 2};           // Patch embedding stride.
  int mlp_ratio = 4;                                   // Mix-FFN hidden = ratio × dim.
  int decoder_dim = 256;                               // All-MLP decoder width C.
  int num_classes = 4;                                 // 0 bg, 1 wall, 2 door, 3 window.
  double drop_path_rate = 0.1;                         // Stochastic depth (max, linear).
  double decoder_dropout = 0.1;                        // Dropout before the classifier.

  // Throws InvalidArgument naming the field (e.g. num_heads not dividing dims).
  void Check() const;
  // One line: "b0: dims 32/64/160/256, depths 2/2/2/2, decoder 256, 4 classes".
  std::string ToString() const;
};

// The published configurations (paper Table 6 / mmsegmentation configs):
//   b0: dims 32/64/160/256,  depths 2/2/2/2, decoder C = 256
//   b1: dims 64/128/320/512, depths 2/2/2/2, decoder C = 256
//   b2: dims 64/128/320/512, depths 3/4/6/3, decoder C = 768
// plus "tiny" (b0's encoder with decoder C = 128), the shipped model's
// CPU-friendly variant. Throws InvalidArgument for an unknown name.
SegformerConfig SegformerConfigFor(std::string_view arch, int num_classes = 4);
std::vector<std::string> SegformerArchNames();

}  // namespace asbuilt

#endif  // ASBUILT_SEG_SEGFORMER_CONFIG_H_
