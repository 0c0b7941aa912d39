#ifndef ASBUILT_SEG_TFLITE_SEGMENTER_H_
#define ASBUILT_SEG_TFLITE_SEGMENTER_H_

// Segmenters read from TensorFlow Lite files (the ADE20K-trained teachers in
// ../shared/data/ade20k-teachers). Internal to seg/: LoadSegmenter() picks
// this reader for a path ending in ".tflite".
//
// The file's 32 ADE20K-Top31 classes are mapped onto asbuilt's four ("zero
// shot"): 1 wall → wall, 15 door → door, 9 windowpane → window, everything
// else (floor, ceiling, furniture, "other") → background, as `labels import
// --format ade20k` maps ADE's masks (docs/labels.md). Probabilities() sums
// the softmax over each group.

#include <filesystem>
#include <memory>

#include "asbuilt/seg/segmenter.h"

namespace asbuilt {

std::unique_ptr<Segmenter> LoadTfliteSegmenter(const std::filesystem::path& path, const SegmentOptions& options);
SegmenterInfo ReadTfliteSegmenterInfo(const std::filesystem::path& path);

// The asbuilt class (0..3) of each ADE20K-Top31 output channel (0 = "other").
int AsbuiltClassOfAde32(int ade_class);

}  // namespace asbuilt

#endif  // ASBUILT_SEG_TFLITE_SEGMENTER_H_
