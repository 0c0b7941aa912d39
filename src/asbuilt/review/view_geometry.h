#ifndef ASBUILT_REVIEW_VIEW_GEOMETRY_H_
#define ASBUILT_REVIEW_VIEW_GEOMETRY_H_

// Pixels of a survey's images ↔ the world, for the review: the panorama's
// pixel (u, v) as docs/formats.md defines it (yaw ψ = yaw_deg − 360°·(u +
// 0.5)/W, elevation φ = 180°·(0.5 − (v + 0.5)/H)); a perspective frame's
// pixel through its level pinhole camera at its yaw (DESIGN.md conventions).

#include <optional>
#include <vector>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/geometry/rig.h"
#include "asbuilt/pipeline/review_input.h"

namespace asbuilt {

// The viewing ray of pixel (u, v) of `image`, in the world (not normalised).
Vec3 RayOfPixel(const ReviewImage& image, const Vec2& pixel);

// The pixel where world point p is seen in `image`; nullopt when it is
// behind a perspective camera. A panorama's u is in [−0.5, W − 0.5).
std::optional<Vec2> PixelOfPoint(const ReviewImage& image, const Vec3& p);

// Is (u, v) inside the image (pixel centres from 0, edges at −0.5 and W − 0.5)?
bool PixelInside(const ReviewImage& image, const Vec2& pixel);

// Where the ray of pixel meets the floor (z = 0); nullopt at or above the
// horizon.
std::optional<Vec2> FloorPointOfPixel(const ReviewImage& image, const Vec2& pixel);

// The first wall of `plan` the ray of pixel meets, seen from above: the
// point in plan, the wall index and the horizontal distance from the camera;
// nullopt when it meets none.
struct WallHit {
  Vec2 xy_m = Vec2::Zero();
  int wall = -1;
  double distance_m = 0.0;
};
std::optional<WallHit> WallOfPixel(const ReviewImage& image, const Plan& plan, const Vec2& pixel);

// The height above the floor at which the ray of pixel passes horizontal
// distance d from the camera.
double HeightAtDistance(const ReviewImage& image, const Vec2& pixel, double distance_m);

// Of several perspective frames, the one that sees p nearest its image
// centre (index into `images`); 0 for a panorama.
int BestImageFor(const std::vector<ReviewImage>& images, const Vec3& p);

}  // namespace asbuilt

#endif  // ASBUILT_REVIEW_VIEW_GEOMETRY_H_
