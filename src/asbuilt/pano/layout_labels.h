#ifndef ASBUILT_PANO_LAYOUT_LABELS_H_
#define ASBUILT_PANO_LAYOUT_LABELS_H_

// Label maps drawn from a panorama's annotated room layout (formats/zind.h),
// for views of that panorama (pano/perspective.h) or the panorama itself.
//
// Each pixel's viewing ray leaves the camera at (0, 0, camera_height_m) in
// the pano frame. The walls are vertical rectangles over the layout's edges
// from the floor (z = 0) to the ceiling (ceiling_height_m). The nearest wall
// the ray meets decides: where it meets it between floor and ceiling, the
// pixel is wall (1), or door (2), window (3) or ignore (255, a ZInD passage)
// when the point lies in the rectangle of a door, window or passage on that
// wall; where it meets it below the floor or above the ceiling, the ray hit
// the floor or ceiling first: background (0).
//
// What the labels are, and are not: the room's *layout*. Furniture, people
// and anything else standing in front of a wall is labelled wall (or door,
// window), the floor and ceiling background. A door's label covers its whole
// opening, including what is seen through it when it stands open (asbuilt's
// label convention); an open door leaf swung into the room is not door.
// Openings on no wall (ZindOpening::wall = −1) are not drawn.

#include <cstdint>

#include "asbuilt/formats/zind.h"
#include "asbuilt/geometry/label_class.h"
#include "asbuilt/imageio/image.h"
#include "asbuilt/pano/perspective.h"

namespace asbuilt {

inline constexpr std::uint8_t kPassageLabel = kLabelIgnore;  // ZInD openings (passages): ignored.

// The label of one viewing ray (pano frame direction, any length).
std::uint8_t LayoutLabelOfRay(const ZindPanorama& pano, const ZindLayout& layout, const Vec3& ray);

// The label map (8-bit, the view's size) of a view of the panorama.
Image LayoutLabels(const ZindPanorama& pano, const PanoView& view, ZindLayoutKind layout = ZindLayoutKind::kRaw);

// The label map of the whole panorama as a W × H equirectangular image.
Image LayoutLabelsEquirect(const ZindPanorama& pano, int width_px, int height_px,
                           ZindLayoutKind layout = ZindLayoutKind::kRaw);

// Labels over an image, to look at: wall blue, door green, window red (the
// colours of `asbuilt segment --overlay`), ignore grey; background as is.
// `bgr` 3 × 8-bit and `labels` 8-bit of the same size (InvalidArgument else).
Image DrawLabelOverlay(const Image& bgr, const Image& labels, double alpha = 0.45);

}  // namespace asbuilt

#endif  // ASBUILT_PANO_LAYOUT_LABELS_H_
