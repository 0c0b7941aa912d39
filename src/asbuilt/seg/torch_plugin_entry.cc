// The entry point of libasbuilt_torch.so (torch_plugin.h): the table of the
// LibTorch implementations, which this module links from asbuilt_seg_torch.
#include "asbuilt/seg/torch_plugin.h"

extern "C" __attribute__((visibility("default"))) const asbuilt::TorchPluginApi* asbuilt_torch_plugin_api() {
  static const asbuilt::TorchPluginApi api = {
      .load_segmenter = &asbuilt::LoadSegmenter,
      .read_segmenter_info = &asbuilt::ReadSegmenterInfo,
      .train_segmenter = &asbuilt::TrainSegmenter,
      .export_model = &asbuilt::ExportModel,
      .import_model = &asbuilt::ImportModel,
      .average_models = &asbuilt::AverageModels,
  };
  return &api;
}
