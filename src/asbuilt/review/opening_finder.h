#ifndef ASBUILT_REVIEW_OPENING_FINDER_H_
#define ASBUILT_REVIEW_OPENING_FINDER_H_

// One click on a door or window finds its span in the photo (internal to
// review/; docs/review.md "One click on an opening"): the wall of the plan
// the click's ray meets, then the jambs — the two vertical lines on that
// wall, one either side of the click, across which the photo changes most
// along the opening's whole height — then the head (and a window's sill):
// the horizontal line between the jambs across which it changes most.
// Strengths are a low quantile of the gradient along each line, so a jamb,
// which runs the door's full height, outweighs a panel's or a chair's edge.

#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/pipeline/review_input.h"

namespace asbuilt {

struct OpeningSearchOptions {
  double min_door_m = 0.5, max_door_m = 2.6;
  double min_window_m = 0.3, max_window_m = 3.5;
  double reach_m = 2.0;  // How far along the wall from the click a jamb is looked for.
  double step_m = 0.01;
  double quantile = 0.3;  // Of a line's gradients: an edge along most of it.
  // Each jamb at least this many times the median line along the searched wall.
  double min_contrast = 1.5;
  double jamb_share = 0.7;  // Of the strongest line on its side of the click.
  double door_head_min_m = 1.7, door_head_max_m = 2.6;
  double window_band_m = 0.25;  // The jambs are first looked for this far above and below the click.
  void Check() const;
};

// The grey image's gradients (CV_32F), computed once per image.
struct ImageGradients {
  cv::Mat gx, gy;
};
ImageGradients GradientsOf(const cv::Mat& grey);

struct FoundOpening {
  int wall = -1;
  Vec2 start_m = Vec2::Zero(), end_m = Vec2::Zero();  // On the wall's line.
  double bottom_m = 0.0, top_m = 2.0;
};

// The opening of `kind` around `pixel` of `image`, on the walls of `plan`;
// nullopt with the reason in `why` when the click meets no wall or no pair
// of jambs stands out from the wall around it.
std::optional<FoundOpening> FindOpeningAt(const ImageGradients& gradients, const ReviewImage& image, const Plan& plan,
                                          const Vec2& pixel, OpeningKind kind, double ceiling_m, std::string* why,
                                          const OpeningSearchOptions& options = {});

}  // namespace asbuilt

#endif  // ASBUILT_REVIEW_OPENING_FINDER_H_
