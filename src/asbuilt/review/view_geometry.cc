#include "asbuilt/review/view_geometry.h"

#include <cmath>
#include <limits>

#include "asbuilt/pano/perspective.h"

namespace asbuilt {
namespace {

bool IsPanorama(const ReviewImage& image) { return image.frame < 0; }

Mat3 RotZ(double rad) {
  Mat3 r;
  r << std::cos(rad), -std::sin(rad), 0, std::sin(rad), std::cos(rad), 0, 0, 0, 1;
  return r;
}

}  // namespace

Vec3 RayOfPixel(const ReviewImage& image, const Vec2& pixel) {
  if (IsPanorama(image)) {
    return RotZ(DegToRad(image.yaw_deg)) * DirectionFromEquirectPixel(pixel, image.width_px, image.height_px);
  }
  const Vec3 in_camera((pixel.x() - image.camera.cx) / image.camera.fx, (pixel.y() - image.camera.cy) / image.camera.fy,
                       1.0);
  return WorldFromCameraRotation(DegToRad(image.yaw_deg)) * in_camera;
}

std::optional<Vec2> PixelOfPoint(const ReviewImage& image, const Vec3& p) {
  const Vec3 d = p - image.camera_m;
  if (IsPanorama(image)) {
    return EquirectPixelFromDirection(RotZ(-DegToRad(image.yaw_deg)) * d, image.width_px, image.height_px);
  }
  return ProjectFromCamera(image.camera, WorldFromCameraRotation(DegToRad(image.yaw_deg)).transpose() * d);
}

bool PixelInside(const ReviewImage& image, const Vec2& pixel) {
  return pixel.allFinite() && pixel.x() >= -0.5 && pixel.x() <= image.width_px - 0.5 && pixel.y() >= -0.5 &&
         pixel.y() <= image.height_px - 0.5;
}

std::optional<Vec2> FloorPointOfPixel(const ReviewImage& image, const Vec2& pixel) {
  const Vec3 d = RayOfPixel(image, pixel);
  if (d.z() > -1e-6 * d.norm()) return std::nullopt;
  const double t = -image.camera_m.z() / d.z();
  return (image.camera_m + t * d).head<2>();
}

std::optional<WallHit> WallOfPixel(const ReviewImage& image, const Plan& plan, const Vec2& pixel) {
  const Vec3 d3 = RayOfPixel(image, pixel);
  const Vec2 d = d3.head<2>();
  if (d.norm() < 1e-9) return std::nullopt;
  const Vec2 dir = d.normalized(), c = image.camera_m.head<2>();
  std::optional<WallHit> best;
  for (std::size_t w = 0; w < plan.walls.size(); ++w) {
    const Vec2 a = plan.walls[w].start, e = plan.walls[w].end - a;
    const double denom = Cross(dir, e);
    if (std::abs(denom) < 1e-12) continue;
    const double t = Cross(a - c, e) / denom;    // Along the ray.
    const double s = Cross(a - c, dir) / denom;  // Along the wall.
    if (t <= 1e-6 || s < -1e-6 || s > 1 + 1e-6) continue;
    if (!best || t < best->distance_m)
      best = WallHit{.xy_m = c + t * dir, .wall = static_cast<int>(w), .distance_m = t};
  }
  return best;
}

double HeightAtDistance(const ReviewImage& image, const Vec2& pixel, double distance_m) {
  const Vec3 d = RayOfPixel(image, pixel);
  return image.camera_m.z() + distance_m * d.z() / d.head<2>().norm();
}

int BestImageFor(const std::vector<ReviewImage>& images, const Vec3& p) {
  int best = 0;
  double best_off = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < images.size(); ++i) {
    const ReviewImage& im = images[i];
    if (IsPanorama(im)) return static_cast<int>(i);
    const Vec3 in_camera = WorldFromCameraRotation(DegToRad(im.yaw_deg)).transpose() * (p - im.camera_m);
    if (in_camera.z() <= 1e-6) continue;
    // Horizontal angle off the optical axis.
    const double off = std::abs(std::atan2(in_camera.x(), in_camera.z()));
    if (off < best_off) {
      best_off = off;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace asbuilt
