#ifndef ASBUILT_SEG_TFLITE_SEGMENTER_H_
#define ASBUILT_SEG_TFLITE_SEGMENTER_H_

// Segmenters built on TensorFlow Lite graphs: the ADE20K-trained teachers in
// ../shared/data/ade20k-teachers read as they are (a path ending in
// ".tflite"), and networks asbuilt fine-tuned from them (an
// "asbuilt-tflite-v1" checkpoint: the graph's topology in its metadata, the
// trained weights as parameters; seg/model_io.h). Internal to seg/
// (includes LibTorch): LoadSegmenter() picks this reader for either.
//
// The file's 32 ADE20K-Top31 classes are mapped onto asbuilt's four: 1 wall
// → wall, 15 door → door, 9 windowpane → window, everything else (floor,
// ceiling, furniture, "other") → background, as `labels import --format
// ade20k` maps ADE's masks (docs/labels.md). A class's probability is the sum
// of its members' softmax; fine-tuning trains the 32-class network through
// that sum, so the floor and ceiling channels stay in the network.

#include <filesystem>
#include <memory>

#include <nlohmann/json.hpp>

#include "asbuilt/seg/segmenter.h"
#include "asbuilt/seg/tflite_net.h"

namespace asbuilt {

// Whether `path` names a TensorFlow Lite file (by its extension).
bool IsTfliteFile(const std::filesystem::path& path);

// The network of a .tflite file or of an asbuilt-tflite-v1 checkpoint
// (weights loaded). Throws InputError naming the file.
TfliteNet LoadTfliteNet(const std::filesystem::path& path);

// A .tflite file read as it is (its declared input size, the zero-shot
// class groups); a fine-tuned checkpoint is LoadTfliteNet + MakeTfliteSegmenter.
std::unique_ptr<Segmenter> LoadTfliteSegmenter(const std::filesystem::path& path, const SegmentOptions& options);
SegmenterInfo ReadTfliteSegmenterInfo(const std::filesystem::path& path);

// A Segmenter over a network in memory (shares its weights; switches it to
// eval mode while segmenting and restores the previous mode).
std::unique_ptr<Segmenter> MakeTfliteSegmenter(TfliteNet net, SegmenterInfo info, const SegmentOptions& options);

// What a checkpoint's metadata says of the network: {"arch": "tflite",
// "num_classes": 4, "source_classes", "class_map", "graph"}.
nlohmann::json TfliteCheckpointConfig(const TfliteNet& net);

// BGR 8-bit images of one size → (B, 3, H, W) RGB float in 0..255, the
// graph's input.
torch::Tensor RgbTensor(const std::vector<cv::Mat>& images);

// (B, C, H, W) logits of the file's classes → (B, 4, H, W) log-probabilities
// of asbuilt's classes (log of each group's summed softmax).
torch::Tensor GroupedLogProbabilities(const torch::Tensor& logits);

// The asbuilt class (0..3) of each ADE20K-Top31 output channel (0 = "other").
int AsbuiltClassOfAde32(int ade_class);

}  // namespace asbuilt

#endif  // ASBUILT_SEG_TFLITE_SEGMENTER_H_
