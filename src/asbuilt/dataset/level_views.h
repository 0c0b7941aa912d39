#ifndef ASBUILT_DATASET_LEVEL_VIEWS_H_
#define ASBUILT_DATASET_LEVEL_VIEWS_H_

// A panorama's tall level views (as a saved review exports them: 512×1024,
// the whole turn from floor to ceiling) cut into level views of the renders'
// aspect, so that a model trained on them sees real rooms at the scale it
// sees renders: each tall image and its label become three 4:3 windows
// across its width, one centred on its middle row (the horizon) and one
// 0.3125 widths above and below it, where the walls' floor and ceiling edges
// are. Labels are cut alike (docs/dataset.md).

#include <filesystem>

namespace asbuilt {

struct LevelViewsSummary {
  int tall = 0;     // Tall pairs cut, three windows each.
  int skipped = 0;  // Pairs no taller than 5:4, copied as they are.
};

// Reads the pairs of `in` (images/ + labels/, pairs.h ListPairs) and writes
// `out`/images/STEM_K.jpg|png and labels/STEM_K.png (K = 0 upper, 1 middle,
// 2 lower), atomically. Throws InputError naming `in` when it holds no pairs,
// or an unreadable file.
LevelViewsSummary CutLevelViews(const std::filesystem::path& in, const std::filesystem::path& out);

}  // namespace asbuilt

#endif  // ASBUILT_DATASET_LEVEL_VIEWS_H_
