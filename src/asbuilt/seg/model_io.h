#ifndef ASBUILT_SEG_MODEL_IO_H_
#define ASBUILT_SEG_MODEL_IO_H_

// INTERNAL to seg/ (includes LibTorch): checkpoints and image ↔ tensor.
//
// A checkpoint is one LibTorch archive (torch::serialize) holding
//   "asbuilt_meta"   JSON (as uint8 tensor): format, config, scale, crop,
//                    epoch, step, history, options
//   "model/<name>"   every parameter and buffer of the network
//   "optimizer"      AdamW state (training checkpoints only)
// written through AtomicFile, so a kill never leaves a truncated file.

#include <torch/torch.h>

#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "asbuilt/seg/segformer.h"
#include "asbuilt/seg/segmenter.h"

namespace asbuilt {

// The network a checkpoint holds: a SegFormer, or a TensorFlow Lite graph
// fine-tuned by asbuilt (its topology in meta "graph", seg/tflite_segmenter.h).
inline constexpr const char* kCheckpointFormat = "asbuilt-segformer-v1";
inline constexpr const char* kTfliteCheckpointFormat = "asbuilt-tflite-v1";

void SaveCheckpoint(const std::filesystem::path& path, torch::nn::Module& model, torch::optim::Optimizer* optimizer,
                    const nlohmann::json& meta);

// Reads the metadata (either format); throws InputError(path) when not a
// checkpoint.
nlohmann::json ReadCheckpointMeta(const std::filesystem::path& path);
SegformerConfig ConfigFromMeta(const nlohmann::json& meta, const std::string& file);
nlohmann::json ConfigToJson(const SegformerConfig& config);

// Loads weights (and optimizer state when given and present). strict: every
// model tensor must be present with its shape (InputError otherwise); not
// strict: tensors with a missing name or another shape are skipped and
// counted (for --init from another head). Returns tensors loaded.
int LoadWeights(const std::filesystem::path& path, torch::nn::Module& model, torch::optim::Optimizer* optimizer,
                bool strict, int* skipped = nullptr);

// BGR 8-bit images of one size → normalised RGB float tensor (B, 3, H, W)
// (ImageNet mean/std, as mmseg).
torch::Tensor ImagesToTensor(const std::vector<cv::Mat>& bgr);
// Labels CV_8U → int64 tensor (B, H, W).
torch::Tensor LabelsToTensor(const std::vector<cv::Mat>& labels);
// Per-class maps (C, H, W) float → one CV_32F Mat per class (copies).
std::vector<cv::Mat> ClassMaps(const torch::Tensor& chw);

// A Segmenter over a model in memory (shares its weights; switches it to
// eval mode while segmenting and restores the previous mode).
std::unique_ptr<Segmenter> MakeSegmenter(Segformer model, SegmenterInfo info, const SegmentOptions& options);

// Info from checkpoint metadata.
SegmenterInfo InfoFromMeta(const nlohmann::json& meta, const std::string& file);

}  // namespace asbuilt

#endif  // ASBUILT_SEG_MODEL_IO_H_
