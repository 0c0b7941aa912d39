#ifndef ASBUILT_SEG_TOY_ROOMS_H_
#define ASBUILT_SEG_TOY_ROOMS_H_

// Toy rooms: a small, self-contained ray caster of box rooms with doors,
// windows, pictures and furniture, giving a colour view and its exact label
// map (0 bg, 1 wall, 2 door, 3 window). It exists so seg/ can be tested and
// its training bootstrapped without the full renderer (render/, dataset/):
// tests make tiny sets in milliseconds. Domain randomisation: room size,
// camera pose and field of view, materials, lighting, exposure, noise.
// No LibTorch here.

#include <cstdint>
#include <filesystem>

#include <opencv2/core.hpp>

#include "asbuilt/util/progress.h"

namespace asbuilt {

struct ToyRoomOptions {
  int width_px = 256;      // Output size; views are rendered at 2× and averaged
  int height_px = 192;     // down (anti-aliased colour, centre-sampled labels).
  std::uint64_t seed = 1;  // View i of seed s is always the same image.
  void Check() const;
};

struct ToyView {
  cv::Mat bgr;    // CV_8UC3.
  cv::Mat label;  // CV_8UC1, ids 0..3.
};

// Renders view `index` of the set defined by options.seed.
ToyView RenderToyRoom(const ToyRoomOptions& options, std::uint64_t index);

// Writes `count` views as DIR/images/NNNNN.png and DIR/labels/NNNNN.png
// (atomically, one file at a time). Returns the number written.
int WriteToyRoomSet(const std::filesystem::path& dir, int count, const ToyRoomOptions& options,
                    const ProgressCallback& progress = {});

}  // namespace asbuilt

#endif  // ASBUILT_SEG_TOY_ROOMS_H_
