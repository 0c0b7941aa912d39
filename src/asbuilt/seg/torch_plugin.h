#ifndef ASBUILT_SEG_TORCH_PLUGIN_H_
#define ASBUILT_SEG_TORCH_PLUGIN_H_

// seg/'s LibTorch half is a plugin. Loading LibTorch costs about a second of
// dynamic linking and static initialisation, which every command paid while
// the binary linked it (`asbuilt mcp` answered `initialize` in 1.2 s instead
// of 0.3 s). So the SegFormer code (segformer, model_io, model_file,
// segmenter, train) is built as the module libasbuilt_torch.so, and the
// host's seg library implements the public entry points (LoadSegmenter,
// ReadSegmenterInfo, SegmenterAvailable, TrainSegmenter, ExportModel,
// ImportModel, AverageModels) by loading it with dlopen on first use and calling through
// this table. Callers keep using segmenter.h, train.h and model_file.h.
//
// Where the host looks, first hit wins:
//   1. $ASBUILT_TORCH_PLUGIN (a path to the .so);
//   2. libasbuilt_torch.so beside the running executable (/proc/self/exe);
//   3. the build tree's copy (tests and benchmarks run from subfolders).
// A missing or incompatible plugin is an Error ("segmentation needs
// libasbuilt_torch.so …"): exit 1 in the CLI, a tool error in MCP.
//
// Tests and benchmarks that use LibTorch directly link the implementation
// objects (target asbuilt_seg_torch) instead; torch_plugin.cc defines
// exactly the entry points those objects define, so the linker never pulls
// it in beside them.

#include <cstdint>

#include "asbuilt/seg/model_file.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/seg/train.h"

namespace asbuilt {

// Bump when the table or any type passed through it changes layout.
inline constexpr std::uint32_t kTorchPluginAbi = 2;

struct TorchPluginApi {
  std::uint32_t abi = kTorchPluginAbi;
  std::uint32_t size = sizeof(TorchPluginApi);
  decltype(&LoadSegmenter) load_segmenter = nullptr;
  decltype(&ReadSegmenterInfo) read_segmenter_info = nullptr;
  decltype(&TrainSegmenter) train_segmenter = nullptr;
  decltype(&ExportModel) export_model = nullptr;
  decltype(&ImportModel) import_model = nullptr;
  decltype(&AverageModels) average_models = nullptr;
};

}  // namespace asbuilt

// The plugin's one exported symbol.
extern "C" const asbuilt::TorchPluginApi* asbuilt_torch_plugin_api();

#endif  // ASBUILT_SEG_TORCH_PLUGIN_H_
