#ifndef ASBUILT_PANO_PERSPECTIVE_H_
#define ASBUILT_PANO_PERSPECTIVE_H_

// Perspective views from an equirectangular 360° panorama, as a camera
// turning in place at the panorama's centre would take them.
//
// Frames (DESIGN.md conventions). The panorama's *pano frame* is an asbuilt
// world frame centred on the camera: +Z up, yaw ψ = 0 looks along +Y,
// positive yaw turns counter-clockwise seen from above. An equirectangular
// image W × H (OpenCV pixel centres) maps directions to pixels by
//   u = W·frac(−ψ / 2π) − 0.5,   v = H·(0.5 − φ/π) − 0.5,
// ψ the direction's yaw, φ its elevation: the left edge looks along +Y,
// columns run clockwise seen from above (as a photographer turning right
// sees them), the top row looks straight up. ZInD panoramas follow this in
// the pano frame formats/zind.h defines (checked on the sample tour's doors).
//
// A view is a pinhole camera (OpenCV frame: x right, y down, z forward) at
// the centre, turned to yaw ψ and tilted up by pitch θ:
//   world_from_camera = WorldFromCameraRotation(ψ) · Rx(θ).
//
//   PanoView view{.camera = {.width_px = 640, .height_px = 480, .fx = 400, .fy = 400}, .yaw_deg = 30};
//   Image bgr = RenderPanoView(equirect_bgr, view);

#include <vector>

#include "asbuilt/geometry/rig.h"
#include "asbuilt/imageio/image.h"
#include "asbuilt/util/fields.h"

namespace asbuilt {

// One perspective view from the panorama's centre.
struct PanoView {
  PinholeCamera camera;    // Intrinsics; cx, cy default to the image centre of 640×480.
  double yaw_deg = 0.0;    // DESIGN.md yaw of the optical axis.
  double pitch_deg = 0.0;  // Tilt of the optical axis, up positive.

  // Rotation taking camera-frame vectors into the pano frame.
  Mat3 WorldFromCamera() const;
  // The viewing ray of pixel (u, v) in the pano frame (not normalised).
  Vec3 RayInWorld(const Vec2& pixel) const;
  void Check() const;            // Throws InvalidArgument naming a bad camera field or angle.
  std::string ToString() const;  // "PanoView(640x480 fx=400.0 yaw 30.0° pitch 0.0°)".
};

// Equirectangular pixel (OpenCV centres) of a direction in the pano frame,
// and back. u is in [−0.5, W − 0.5).
Vec2 EquirectPixelFromDirection(const Vec3& direction, int width_px, int height_px);
Vec3 DirectionFromEquirectPixel(const Vec2& pixel, int width_px, int height_px);

// Evenly turned views: `views` views, yaw first_yaw_deg + i·yaw_step_deg.
struct TurnInPlaceOptions {
  int width_px = 640;  // View size.
  int height_px = 480;
  double fx = 400.0;  // Focal length, pixels (400 at 640 px wide: 77° horizontal field of view).
  double fy = 0.0;    // 0 = fx (square pixels).
  int views = 12;
  double yaw_step_deg = 30.0;  // Positive turns counter-clockwise seen from above.
  double first_yaw_deg = 0.0;
  double pitch_deg = 0.0;  // Every view's tilt, up positive; |pitch| < 90.
  void Check() const;
};
// The field list (util/fields.h).
const FieldList<TurnInPlaceOptions>& TurnInPlaceOptionFields();
std::vector<PanoView> TurnInPlaceViews(const TurnInPlaceOptions& options);

// The view's image sampled from an equirectangular panorama (any channel
// count and type; 3 × 8-bit BGR for photos) with bilinear interpolation,
// wrapping across the 0/360° seam. Where the view's pixels are coarser than
// the panorama's (a small view of a large panorama), the panorama is first
// reduced by area averaging so the view does not alias. Throws
// InvalidArgument when the panorama is empty or not 2:1 (±1 pixel).
Image RenderPanoView(const Image& equirect, const PanoView& view);

// The view's labels from an equirectangular label panorama (8-bit, one
// channel): each view pixel takes the id of the panorama pixel nearest its
// ray, so no id is blended with its neighbour's. Throws InvalidArgument as
// RenderPanoView does.
Image RenderPanoLabelView(const Image& equirect_labels, const PanoView& view);

}  // namespace asbuilt

#endif  // ASBUILT_PANO_PERSPECTIVE_H_
