#include "asbuilt/seg/segformer_config.h"

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {

void SegformerConfig::Check() const {
  CheckArgument(in_channels > 0, fmt::format("SegformerConfig.in_channels = {}, must be > 0", in_channels));
  CheckArgument(num_classes > 0, fmt::format("SegformerConfig.num_classes = {}, must be > 0", num_classes));
  CheckArgument(decoder_dim > 0, fmt::format("SegformerConfig.decoder_dim = {}, must be > 0", decoder_dim));
  CheckArgument(mlp_ratio > 0, fmt::format("SegformerConfig.mlp_ratio = {}, must be > 0", mlp_ratio));
  for (int i = 0; i < 4; ++i) {
    CheckArgument(embed_dims[i] > 0 && num_heads[i] > 0 && embed_dims[i] % num_heads[i] == 0,
                  fmt::format("SegformerConfig.num_heads[{}] = {} must divide embed_dims[{}] = {}", i, num_heads[i], i,
                              embed_dims[i]));
    CheckArgument(depths[i] > 0, fmt::format("SegformerConfig.depths[{}] = {}, must be > 0", i, depths[i]));
    CheckArgument(sr_ratios[i] > 0, fmt::format("SegformerConfig.sr_ratios[{}] = {}, must be > 0", i, sr_ratios[i]));
    CheckArgument(strides[i] > 0 && patch_sizes[i] > 0,
                  fmt::format("SegformerConfig.strides/patch_sizes[{}] must be > 0", i));
  }
  CheckArgument(drop_path_rate >= 0 && drop_path_rate < 1,
                fmt::format("SegformerConfig.drop_path_rate = {}, must be in [0, 1)", drop_path_rate));
  CheckArgument(decoder_dropout >= 0 && decoder_dropout < 1,
                fmt::format("SegformerConfig.decoder_dropout = {}, must be in [0, 1)", decoder_dropout));
}

std::string SegformerConfig::ToString() const {
  return fmt::format("{}: dims {}/{}/{}/{}, depths {}/{}/{}/{}, decoder {}, {} classes", arch, embed_dims[0],
                     embed_dims[1], embed_dims[2], embed_dims[3], depths[0], depths[1], depths[2], depths[3],
                     decoder_dim, num_classes);
}

SegformerConfig SegformerConfigFor(std::string_view arch, int num_classes) {
  SegformerConfig c;
  c.num_classes = num_classes;
  if (arch == "b0") {
  } else if (arch == "tiny") {
    c.decoder_dim = 128;
  } else if (arch == "b1") {
    c.embed_dims = {64, 128, 320, 512};
  } else if (arch == "b2") {
    c.embed_dims = {64, 128, 320, 512};
    c.depths = {3, 4, 6, 3};
    c.decoder_dim = 768;
  } else {
    throw InvalidArgument(fmt::format("unknown SegFormer architecture '{}'; known: b0, b1, b2, tiny", arch));
  }
  if (arch != "b0" && arch != "tiny") c.num_heads = {1, 2, 5, 8};
  c.arch = std::string(arch);
  c.Check();
  return c;
}

std::vector<std::string> SegformerArchNames() { return {"b0", "b1", "b2", "tiny"}; }

}  // namespace asbuilt
