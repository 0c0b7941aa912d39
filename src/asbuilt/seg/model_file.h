#ifndef ASBUILT_SEG_MODEL_FILE_H_
#define ASBUILT_SEG_MODEL_FILE_H_

// Model files: moving SegFormer weights between asbuilt checkpoints and safetensors
// files, so PyTorch users can train, inspect or fine-tune asbuilt's model in
// Python (tools/pytorch/asbuilt_segformer.py is the same network with the
// same tensor names) and bring the result back. Does not include LibTorch.
//
//   asbuilt model export models/segformer_b0_asbuilt.pt -o tiny.safetensors
//   asbuilt model import trained.safetensors -o models/mine.pt
//
// The safetensors file holds every parameter and buffer under its asbuilt
// name ("encoder.block0_0.attn.q.weight", "decoder.fuse.1.running_mean", …)
// and, in "__metadata__", "asbuilt_meta": the checkpoint metadata JSON
// (format, config, scale, crop, history…) — see seg/model_io.h.

#include <filesystem>
#include <vector>

#include "asbuilt/seg/segmenter.h"

namespace asbuilt {

// Writes a checkpoint's weights and metadata (no optimizer state) as
// safetensors, atomically. Throws InputError naming the checkpoint.
SegmenterInfo ExportModel(const std::filesystem::path& checkpoint, const std::filesystem::path& out_safetensors);

// Reads a safetensors file written by ExportModel or the Python twin and
// writes an asbuilt checkpoint, atomically. Strict: every tensor of the
// configured model must be present with its shape (F32, or F16/BF16
// converted), and no other tensor may be; the metadata must name the format
// and a valid config and scale. Throws InputError naming the file and the
// tensor or metadata field.
SegmenterInfo ImportModel(const std::filesystem::path& safetensors, const std::filesystem::path& out_checkpoint);

// Writes the weighted mean of checkpoints of one network (a "model soup":
// fine-tunes of one model along different data or schedules, averaged weight
// by weight), atomically, with the first one's metadata and the list it was
// averaged from (its validation history no longer applies and is dropped).
// `weights` (one per checkpoint, summing to 1; empty: equal) say how much
// each counts. Throws InputError naming a checkpoint of another network.
SegmenterInfo AverageModels(const std::vector<std::filesystem::path>& checkpoints, const std::vector<double>& weights,
                            const std::filesystem::path& out_checkpoint);

}  // namespace asbuilt

#endif  // ASBUILT_SEG_MODEL_FILE_H_
