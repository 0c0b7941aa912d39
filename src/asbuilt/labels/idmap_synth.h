#ifndef ASBUILT_LABELS_IDMAP_SYNTH_H_
#define ASBUILT_LABELS_IDMAP_SYNTH_H_

// A fixture generator: paints an exact label map in the nominal ID-map
// colours and makes them drift the way rendered ID maps do (PAPER.md §3.3):
// smooth lighting fields over the image change brightness, saturation and
// hue; each surface class gets its own reflectance factor; edges are
// anti-aliased by the pixel filter; a little per-pixel noise. Lets the
// calibration and conversion be measured against exact truth without a
// renderer, deterministically (seeded).

#include <cstdint>

#include <opencv2/core.hpp>

#include "asbuilt/labels/palette.h"

namespace asbuilt {

struct IdMapDriftOptions {
  // Smooth brightness (HSV value) factor range over the image; shadowed
  // corners are dark, lit walls near 1.
  double brightness_min = 0.55;
  double brightness_max = 1.05;
  // Smooth saturation factor range.
  double saturation_min = 0.75;
  double saturation_max = 1.0;
  // Smooth hue shift, ± degrees.
  double hue_shift_deg = 6.0;
  // Per-class reflectance factor on brightness, 1 ± this.
  double class_reflectance = 0.08;
  // Lighting field cell size, pixels (the fields vary over a few cells).
  double field_cell_px = 160.0;
  // Gaussian pixel filter σ, pixels, for anti-aliased edges; 0 = none.
  double antialias_sigma_px = 0.6;
  // Per-pixel Gaussian noise σ, 0..255 units.
  double noise_sigma = 2.0;
  std::uint64_t seed = 1;

  void Check() const;
};

// Returns a CV_8UC3 BGR ID map the size of `labels` (CV_8UC1). Pixels whose
// id has no colour in `nominal` (and 255) take the id-0 colour if any, else
// black. Throws InvalidArgument on bad inputs.
cv::Mat SynthesizeIdMap(const cv::Mat& labels, const Palette& nominal, const IdMapDriftOptions& options);

// A random label map that looks like a rendered room view: ceiling and floor
// (background) with slanted edges, a wall corner, a door on the floor line,
// one or two windows, a piece of furniture in front of the wall. For tests
// and benchmarks that need exact labels without a renderer.
cv::Mat SyntheticRoomLabels(int width_px, int height_px, std::uint64_t seed);

}  // namespace asbuilt

#endif  // ASBUILT_LABELS_IDMAP_SYNTH_H_
