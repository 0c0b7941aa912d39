#ifndef ASBUILT_DATASET_PAIRS_H_
#define ASBUILT_DATASET_PAIRS_H_

// Finding (image, label) pairs on disk: the `--images DIR --labels DIR`
// options of every command, and the dataset folders `dataset mix` reads.

#include <filesystem>
#include <string>
#include <vector>

namespace asbuilt {

struct ImagePair {
  std::string name;              // File stem ("000"), prefixed "room/000" in nested datasets.
  std::filesystem::path image;   // RGB image (png, jpg, jpeg, bmp, tif, tiff, webp).
  std::filesystem::path label;   // Label PNG, same stem.
  std::string ToString() const;  // "000 (left/000.png, labels/000.png)"
};

struct PairListing {
  std::vector<ImagePair> pairs;  // Sorted by name.
  std::vector<std::filesystem::path> images_without_label;
  std::vector<std::filesystem::path> labels_without_image;
  std::string ToString() const;  // "12 pairs (1 image without label, 0 labels without image)"
};

// Matches the images in `images_dir` with the label PNGs in `labels_dir` by
// file stem (non-recursive; hidden files and AtomicFile temp files skipped).
// Throws InputError naming the folder if one is not a readable folder, and
// naming both files if two images share a stem (a.jpg and a.png).
PairListing ListPairs(const std::filesystem::path& images_dir, const std::filesystem::path& labels_dir);

// The pairs of a dataset folder, whatever its layout:
//   DIR/images + DIR/labels      (real photos, imported annotations)
//   DIR/left + DIR/labels        (a rendered or Blender capture folder)
//   DIR/<sub>/... (any depth)    (a tree of such folders: names "sub/stem")
// Throws InputError naming DIR if it holds no such folder.
PairListing ListDatasetPairs(const std::filesystem::path& dir);

}  // namespace asbuilt

#endif  // ASBUILT_DATASET_PAIRS_H_
