#ifndef ASBUILT_PLAN_SAMPLE_H_
#define ASBUILT_PLAN_SAMPLE_H_

// Synthetic labelled points from a truth plan, as a stereo survey from one
// spot would see them: points on the visible inner wall faces (occlusion by
// other walls in 2-D), door and window points over the opening plus its
// casing (the label extends `*_casing_m` beyond the clear opening, as the
// blender-rooms labels do), glass and closed leaves slightly behind the face,
// noise mostly along the viewing ray with σ growing with distance
// (σ = sigma_base_m + sigma_per_m2 · d², like stereo depth error ∝ Z²), and a
// fraction of outliers spread through the room's bounding box. For tests and
// benchmarks of ReconstructPlan, and for the survey's self-checks.

#include <cstdint>
#include <optional>
#include <vector>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/formats/points_file.h"

namespace asbuilt {

struct SampleOptions {
  std::optional<Vec3> viewpoint_m;           // Capture centre; default: room polygon centroid at z 1.45 m.
  double wall_points_per_m2 = 150.0;         // Sample density over the wall surfaces (before occlusion).
  double opening_points_per_m2 = 400.0;      // Extra density inside door/window label areas.
  double sigma_base_m = 0.003;               // Noise σ at the viewpoint, metres.
  double sigma_per_m2 = 0.004;               // Growth of σ with squared distance, m per m².
  double lateral_fraction = 0.1;             // σ across the viewing ray, as a fraction of σ along it.
  double outlier_fraction = 0.05;            // Fraction of all points that are outliers.
  double door_casing_m = 0.07;               // Door label extends this far beyond the clear opening.
  double window_casing_m = 0.05;             // Window label extends this far beyond the clear opening.
  double default_height_m = 2.7;             // Wall height when the plan has none.
  PointSource source = PointSource::kDense;  // Source written on every point.

  void Check() const;
};

// The viewpoint SamplePointsFromPlan uses for these options.
Vec3 SampleViewpoint(const Plan& plan, const SampleOptions& options);

// Deterministic for a given seed. The plan needs at least one room polygon or
// walls; openings must reference valid walls (as ReadPlan guarantees).
std::vector<ClassPoint> SamplePointsFromPlan(const Plan& plan, const SampleOptions& options, std::uint64_t seed);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_SAMPLE_H_
