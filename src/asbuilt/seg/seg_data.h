#ifndef ASBUILT_SEG_SEG_DATA_H_
#define ASBUILT_SEG_SEG_DATA_H_

// Training/evaluation data for the segmenter: where the (image, label) pairs
// come from (a dataset manifest, or two folders split 9:1 by seed), reading
// them with validation, and the training augmentation (mmsegmentation's
// pipeline: random resize 0.5–2.0, random crop, flip, photometric
// distortion; plus blur and sensor noise). OpenCV only, no LibTorch.

#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/util/fields.h"

namespace asbuilt {

struct SegSample {
  std::string name;
  std::filesystem::path image;
  std::filesystem::path label;
};

struct SegDataSplit {
  std::vector<SegSample> train, val, test;
  std::string source;  // "manifest runs/m.json (RS5050)" or "folders images/ + labels/".
};

// Reads a manifest (dataset/manifest.h); throws its InputError.
SegDataSplit SplitFromManifest(const std::filesystem::path& manifest_path);

// Pairs images_dir/X.* with labels_dir/X.png (or, with labels_dir empty, a
// dataset folder: DIR/images + DIR/labels, DIR/left + DIR/labels, nested),
// shuffles with `seed` and holds out `val_fraction` (at least one pair when
// there are two or more) as validation. Throws InputError when no pair exists.
SegDataSplit SplitFromFolders(const std::filesystem::path& images_dir, const std::filesystem::path& labels_dir,
                              double val_fraction = 0.1, std::uint64_t seed = 0);

struct SegPair {
  cv::Mat bgr;    // CV_8UC3.
  cv::Mat label;  // CV_8UC1, ids < num_classes or 255.
};

// Reads and checks one pair (imageio's ReadColourImage and ReadLabelImage).
// Throws InputError naming the file: unreadable, label not single-channel
// 8-bit, sizes differ, label id not in {0..num_classes-1, 255}.
SegPair ReadSegPair(const SegSample& sample, int num_classes = 4);

struct AugmentOptions {
  int scale_width_px = 256;   // Base scale: images are first resized to fit it
  int scale_height_px = 192;  // (aspect kept), then by a random ratio below.
  double ratio_min = 0.5;     // Random resize range (paper/mmseg: 0.5–2.0).
  double ratio_max = 2.0;
  int crop_width_px = 192;      // Random crop; padded with label 255 when the
  int crop_height_px = 192;     // resized image is smaller.
  double cat_max_ratio = 0.75;  // mmseg RandomCrop: retry crops dominated by one class.
  bool flip = true;             // Horizontal flip, p = 0.5.
  bool photometric = true;      // Brightness, contrast, saturation, hue (mmseg).
  bool blur_noise = true;       // Gaussian blur (p 0.3) and noise (p 0.3).
  // Light that is not a window (issue 21: real photos' sunlit patches, lamps
  // and white appliances read as window). With this probability per crop:
  // 1–3 soft-edged patches of warm light (a sun patch's parallelogram or a
  // lamp's ellipse) brightened 1.5–4× and clipped, anywhere in the crop; and,
  // half as often, the window pixels dimmed to 35–90 % and desaturated (dull
  // or shaded windows), so that brightness alone does not say "window".
  // Labels unchanged. 0 = off (the shipped recipe).
  double stray_light_probability = 0;
  void Check() const;
};

// The field list (util/fields.h): names, bounds and descriptions, stated once.
const FieldList<AugmentOptions>& AugmentOptionFields();

// AugmentOptions::stray_light_probability's change, always applied: light
// patches over the image and, half the time, dimmed windows; labels untouched.
void AddStrayLight(SegPair& pair, std::mt19937_64& rng);

// Augments one pair in place to exactly crop size.
void AugmentPair(SegPair& pair, const AugmentOptions& options, std::mt19937_64& rng);

// Resizes to fit (w, h) keeping aspect (the test-time transform), label with
// nearest neighbour.
cv::Size FitSize(cv::Size image, int width_px, int height_px);

}  // namespace asbuilt

#endif  // ASBUILT_SEG_SEG_DATA_H_
