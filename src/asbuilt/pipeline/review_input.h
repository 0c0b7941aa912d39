#ifndef ASBUILT_PIPELINE_REVIEW_INPUT_H_
#define ASBUILT_PIPELINE_REVIEW_INPUT_H_

// What `asbuilt survey` keeps in OUT for `asbuilt review` (review/), so
// that a review re-fits the plan without running the segmenter again:
//
//   OUT/review/input.json   the capture (kind, images, cameras and poses per
//                           view), the plan settings, the ceiling, the labels'
//                           origin
//   OUT/review/labels/     each frame's labels (NNN.png, label ids) as the
//                           survey read them: the segmenter's or those given
//   OUT/review/points.bin   the plan's input points, exactly (binary: a
//                           header line, a count, 38 bytes a point — the
//                           fields of points.txt at full precision); each
//                           floor/ceiling contact is a labelled edge pixel of
//                           its frame, placed on the floor or ceiling plane, so
//                           projecting it through its frame's camera gives the
//                           edge pixel back
//
// Paths are stored relative to OUT when they lie inside it, else absolute.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "asbuilt/geometry/rig.h"
#include "asbuilt/plan/fit_plan.h"
#include "asbuilt/plan/plan_options.h"

namespace asbuilt {

// One image a review shows: a perspective frame (stereo: its left image) or
// the panorama.
struct ReviewImage {
  int frame = -1;               // Capture frame index; −1 for the panorama.
  std::filesystem::path image;  // Absolute once read.
  int width_px = 0, height_px = 0;
  PinholeCamera camera;          // Perspective frames.
  double yaw_deg = 0.0;          // World yaw of the optical axis (panorama: of its left edge, capture.json's yaw_deg).
  Vec3 camera_m = Vec3::Zero();  // Optical centre, world m.
};

struct ReviewInput {
  std::string kind;                    // "stereo", "mono" or "panorama".
  std::filesystem::path capture_json;  // Absolute once read.
  std::vector<ReviewImage> images;     // The panorama alone, or one per frame in capture order.
  // Each frame's labels (label ids, OUT/review/labels/NNN.png) with the
  // camera of the frame they label: a panorama's level views, or the frames.
  std::vector<ReviewImage> labels;
  PlanInput plan_input;
  PlanOptions plan_options;  // As the survey was given them (FitPlan resolves them again).
  std::string labels_source;
};

// Writes OUT/review/input.json and OUT/review/points.bin atomically.
void WriteReviewInput(const std::filesystem::path& out_dir, const ReviewInput& input);

// Reads them back. Throws InputError naming the file and field, or saying
// that OUT is not a survey output ("… has no review/input.json: not a folder
// written by `asbuilt survey` (or one written before the review existed)").
ReviewInput ReadReviewInput(const std::filesystem::path& out_dir);

}  // namespace asbuilt

#endif  // ASBUILT_PIPELINE_REVIEW_INPUT_H_
