#ifndef ASBUILT_PLAN_LABEL_POINTS_H_
#define ASBUILT_PLAN_LABEL_POINTS_H_

// Exact class points from a synthetic capture's per-frame label and depth
// maps (capture.json `labels` + `depth`, left view): every labelled pixel
// (wall, door, window) with depth is back-projected to the world,
// C_L + Z·((i − cx)/fx · r + (j − cy)/fy · d + f) (blender-rooms README),
// through geometry/rig.h. This is the "exact labels" input of the plan
// stage: its score is the upper bound of what stereo + segmentation can reach.

#include <vector>

#include "asbuilt/formats/capture.h"
#include "asbuilt/formats/points_file.h"

namespace asbuilt {

struct LabelPointsOptions {
  int stride_px = 2;          // Use every n-th pixel in u and v (1 = all; ~300k points per frame).
  double max_depth_m = 15.0;  // Farther pixels (sky, far outdoors) are skipped.
  double sigma_m = 0.001;     // σ written on each point: depth quantisation (1 mm).

  void Check() const;
};

// Throws InputError naming the capture file's frame field when a frame has no
// labels or depth, or when an image cannot be read or has the wrong size.
std::vector<ClassPoint> PointsFromLabelledDepth(const Capture& capture, const LabelPointsOptions& options = {});

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_LABEL_POINTS_H_
