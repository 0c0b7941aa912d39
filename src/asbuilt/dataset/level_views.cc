#include "asbuilt/dataset/level_views.h"

#include <algorithm>
#include <string>

#include <fmt/format.h>
#include <opencv2/core.hpp>

#include "asbuilt/dataset/pairs.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace fs = std::filesystem;

LevelViewsSummary CutLevelViews(const fs::path& in, const fs::path& out) {
  const PairListing listing = ListPairs(in / "images", in / "labels");
  if (listing.pairs.empty()) throw InputError(in.string(), "", "no image/label pairs in images/ + labels/");
  LevelViewsSummary summary;
  for (const ImagePair& pair : listing.pairs) {
    const cv::Mat image = ReadColourImage(pair.image), label = ReadLabelImage(pair.label);
    const std::string stem = pair.image.stem().string(), ext = pair.image.extension().string();
    if (image.rows * 4 <= image.cols * 5) {
      WriteImageAtomic(out / "images" / (stem + ext), image);
      WriteImageAtomic(out / "labels" / (stem + ".png"), label);
      ++summary.skipped;
      continue;
    }
    const int w = image.cols, h = w * 3 / 4, middle = image.rows / 2 - h / 2, step = w * 160 / 512;
    for (int k = 0; k < 3; ++k) {
      const int top = std::clamp(middle + (k - 1) * step, 0, image.rows - h);
      const cv::Rect window(0, top, w, h);
      WriteImageAtomic(out / "images" / fmt::format("{}_{}{}", stem, k, ext), image(window));
      WriteImageAtomic(out / "labels" / fmt::format("{}_{}.png", stem, k), label(window));
    }
    ++summary.tall;
  }
  return summary;
}

}  // namespace asbuilt
