// CornerOptions' and RowMatchOptions' field lists (corners.h); Check() stays
// in corners.cc.

#include "asbuilt/stereo/corners.h"

namespace asbuilt {

const FieldList<CornerOptions>& CornerOptionFields() {
  using O = CornerOptions;
  static const FieldList<O> kList = {
      Bind(&O::min_region_area_px, {.name = "min_region_area_px",
                                    .description = "Smaller label regions are ignored (specks, slivers), px².",
                                    .minimum = 1.0}),
      Bind(&O::approx_epsilon_px,
           {.name = "approx_epsilon_px",
            .description = "Polygon tolerance max(this, fraction · perimeter), px; larger keeps fewer corners.",
            .exclusive_minimum = 0.0}),
      Bind(&O::approx_epsilon_fraction, {.name = "approx_epsilon_fraction",
                                         .description = "Polygon tolerance as a fraction of the perimeter (< 0.5).",
                                         .minimum = 0.0,
                                         .maximum = 0.5}),
      Bind(&O::border_margin_px,
           {.name = "border_margin_px",
            .description = "Vertices this near the image border are frame cut-offs and dropped, px.",
            .minimum = 0.0}),
      Bind(&O::refine_radius_px, {.name = "refine_radius_px",
                                  .description = "Sub-pixel refinement window (2r+1)² on the gray image; 0 = none.",
                                  .minimum = 0.0}),
      Bind(&O::max_refine_shift_px,
           {.name = "max_refine_shift_px",
            .description = "A refinement moving farther is discarded (the label vertex is kept), px.",
            .minimum = 0.0}),
  };
  return kList;
}

const FieldList<RowMatchOptions>& RowMatchOptionFields() {
  using O = RowMatchOptions;
  static const FieldList<O> kList = {
      Bind(&O::patch_radius_px, {.name = "patch_radius_px",
                                 .description = "Patch (2r+1)² compared by zero-mean normalised cross-correlation.",
                                 .minimum = 1.0,
                                 .maximum = 50.0}),
      Bind(&O::row_tolerance_px, {.name = "row_tolerance_px",
                                  .description = "Also search rows v ± this (imperfect rectification).",
                                  .minimum = 0.0,
                                  .maximum = 10.0}),
      Bind(&O::min_score, {.name = "min_score",
                           .description = "Best correlation must reach this.",
                           .exclusive_minimum = -1.0,
                           .maximum = 1.0}),
      Bind(&O::ambiguity_margin,
           {.name = "ambiguity_margin",
            .description = "Best correlation must beat every other peak 2 px away or more by this "
                           "(repeated texture).",
            .minimum = 0.0}),
      Bind(&O::min_patch_stddev,
           {.name = "min_patch_stddev",
            .description = "Patches with a smaller gray-level σ have no texture and are rejected.",
            .minimum = 0.0}),
      Bind(&O::min_horizontal_structure,
           {.name = "min_horizontal_structure",
            .description = "Mean |∂I/∂x| over mean |∇I| needed (a horizontal edge cannot be located along a row).",
            .minimum = 0.0,
            .maximum = 1.0}),
      Bind(&O::gauss_newton_iterations,
           {.name = "gauss_newton_iterations",
            .description = "Sub-pixel refinement steps after the parabola fit (0: the parabola, biased to whole "
                           "pixels).",
            .minimum = 0.0,
            .maximum = 100.0}),
  };
  return kList;
}

}  // namespace asbuilt
