#ifndef ASBUILT_REVIEW_TRAINING_EXAMPLE_H_
#define ASBUILT_REVIEW_TRAINING_EXAMPLE_H_

// A reviewed survey as a labelled real example (issue 38): the images the
// segmenter read — a panorama's level views, or each frame's left image —
// with label maps drawn from the plan a person corrected, in asbuilt's
// dataset format:
//
//   OUT/review/training/images/NNN.jpg   (panorama views; frames keep their own files' format)
//   OUT/review/training/labels/NNN.png   (0 background, 1 wall, 2 door, 3 window)
//   OUT/review/training/manifest.json    (every pair in "train", source "real"; `asbuilt dataset check` reads it)
//   OUT/review/training/truth.json       (the corrected plan)
//
// The labels are the room's layout, the rule of `asbuilt pano views --zind`
// (pano/layout_labels.h), the same for training and scoring: each pixel's
// ray meets the plan's walls as vertical rectangles from the floor to the
// ceiling; where it meets one between them the pixel is wall, or door /
// window inside an opening's rectangle on that wall; above or below, or
// meeting no wall, background. Furniture before a wall is labelled wall.

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/pipeline/review_input.h"

namespace asbuilt {

// The label of each pixel of `image` (ReviewInput::labels' perspective
// frames), drawn from `plan` with walls `ceiling_m` high: 8-bit, the
// image's size.
cv::Mat PlanLabels(const ReviewImage& image, const Plan& plan, double ceiling_m);

struct TrainingExample {
  std::filesystem::path dir;  // OUT/review/training (or where it was staged).
  int views = 0;
  std::vector<std::string> files;  // Written, relative to `dir`.
};

// Writes the example into `dir` (created; files atomically). Throws
// InputError naming a survey image that cannot be read, InvalidArgument
// for a plan without walls.
TrainingExample WriteTrainingExample(const ReviewInput& input, const Plan& plan, double ceiling_m,
                                     const std::filesystem::path& dir);

}  // namespace asbuilt

#endif  // ASBUILT_REVIEW_TRAINING_EXAMPLE_H_
