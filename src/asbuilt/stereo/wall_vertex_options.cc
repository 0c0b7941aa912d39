// WallVertexOptions' field list (wall_vertices.h); Check() stays in
// wall_vertices.cc.

#include "asbuilt/stereo/wall_vertices.h"

namespace asbuilt {

const FieldList<WallVertexOptions>& WallVertexOptionFields() {
  using O = WallVertexOptions;
  static const FieldList<O> kList = {
      Bind(&O::side_px,
           {.name = "side_px", .description = "Wall labels on both sides for this many columns.", .minimum = 1.0}),
      Bind(&O::min_rows,
           {.name = "min_rows", .description = "Rows with wall on both sides a column needs.", .minimum = 2.0}),
      Bind(&O::min_contrast, {.name = "min_contrast",
                              .description = "|mean gradient| at the peak, gray levels per pixel.",
                              .exclusive_minimum = 0.0}),
      Bind(&O::block_rows, {.name = "block_rows",
                            .description = "Rows are averaged in blocks of this many for the sign test.",
                            .minimum = 1.0}),
      Bind(&O::min_sign_agreement, {.name = "min_sign_agreement",
                                    .description = "Fraction of blocks that must share the peak's sign (> 0.5).",
                                    .exclusive_minimum = 0.5,
                                    .maximum = 1.0}),
      Bind(&O::profile_half_width_px, {.name = "profile_half_width_px",
                                       .description = "Intensity profiles are compared over ± this, px.",
                                       .minimum = 2.0}),
      Bind(&O::min_ncc, {.name = "min_ncc",
                         .description = "Weakest accepted profile match.",
                         .exclusive_minimum = 0.0,
                         .maximum = 1.0}),
      Bind(&O::ambiguity_margin, {.name = "ambiguity_margin",
                                  .description = "A rival 2 px away or more must score this much less than the match.",
                                  .minimum = 0.0}),
  };
  return kList;
}

}  // namespace asbuilt
