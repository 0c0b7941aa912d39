#include "asbuilt/pano/perspective.h"

#include <cmath>

#include <fmt/format.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// Columns copied from the other side of the seam, so bilinear sampling wraps.
constexpr int kSeamPad = 2;

}  // namespace

Mat3 PanoView::WorldFromCamera() const {
  const double p = DegToRad(pitch_deg);
  Mat3 tilt;  // About the camera x axis; +pitch turns the optical axis (z) up (−y).
  tilt << 1, 0, 0, 0, std::cos(p), -std::sin(p), 0, std::sin(p), std::cos(p);
  return WorldFromCameraRotation(DegToRad(yaw_deg)) * tilt;
}

Vec3 PanoView::RayInWorld(const Vec2& pixel) const { return WorldFromCamera() * UnprojectToCamera(camera, pixel, 1.0); }

void PanoView::Check() const {
  camera.Check();
  CheckArgument(std::isfinite(yaw_deg), fmt::format("PanoView.yaw_deg = {}, must be finite", yaw_deg));
  CheckArgument(std::isfinite(pitch_deg) && std::abs(pitch_deg) < 90,
                fmt::format("PanoView.pitch_deg = {}, must be in (−90, 90)", pitch_deg));
}

std::string PanoView::ToString() const {
  return fmt::format("PanoView({}x{} fx={:.1f} yaw {:.1f}° pitch {:.1f}°)", camera.width_px, camera.height_px,
                     camera.fx, yaw_deg, pitch_deg);
}

Vec2 EquirectPixelFromDirection(const Vec3& d, int width_px, int height_px) {
  const double yaw = std::atan2(-d.x(), d.y());
  const double elevation = std::atan2(d.z(), std::hypot(d.x(), d.y()));
  double turn = -yaw / (2 * kPi);  // Clockwise turns from +Y, in [−0.5, 0.5].
  turn -= std::floor(turn);
  double u = width_px * turn - 0.5;
  if (u >= width_px - 0.5) u -= width_px;
  return Vec2(u, height_px * (0.5 - elevation / kPi) - 0.5);
}

Vec3 DirectionFromEquirectPixel(const Vec2& pixel, int width_px, int height_px) {
  const double yaw = -2 * kPi * (pixel.x() + 0.5) / width_px;
  const double elevation = kPi * (0.5 - (pixel.y() + 0.5) / height_px);
  return Vec3(-std::sin(yaw) * std::cos(elevation), std::cos(yaw) * std::cos(elevation), std::sin(elevation));
}

const FieldList<TurnInPlaceOptions>& TurnInPlaceOptionFields() {
  using O = TurnInPlaceOptions;
  static const FieldList<O> kList = {
      Bind(&O::width_px, {.name = "width_px", .description = "View width, px.", .minimum = 1.0, .maximum = 32768.0}),
      Bind(&O::height_px, {.name = "height_px", .description = "View height, px.", .minimum = 1.0, .maximum = 32768.0}),
      Bind(&O::fx, {.name = "fx",
                    .description = "Focal length, px (400 at 640 px wide: 77° horizontal field of view).",
                    .exclusive_minimum = 0.0}),
      Bind(&O::fy, {.name = "fy", .description = "Vertical focal length, px (0 = fx: square pixels).", .minimum = 0.0}),
      Bind(&O::views, {.name = "views", .description = "Views per panorama.", .minimum = 1.0, .maximum = 3600.0}),
      Bind(&O::yaw_step_deg,
           {.name = "yaw_step_deg", .description = "Degrees between views, counter-clockwise seen from above."}),
      Bind(&O::first_yaw_deg, {.name = "first_yaw_deg",
                               .description = "Yaw of the first view, degrees (0 looks along the pano frame's +Y)."}),
      Bind(&O::pitch_deg, {.name = "pitch_deg",
                           .description = "Tilt of every view, degrees, up positive.",
                           .exclusive_minimum = -90.0,
                           .exclusive_maximum = 90.0}),
  };
  return kList;
}

void TurnInPlaceOptions::Check() const { TurnInPlaceOptionFields().CheckValues(*this, "TurnInPlaceOptions"); }

std::vector<PanoView> TurnInPlaceViews(const TurnInPlaceOptions& options) {
  options.Check();
  const PinholeCamera camera{.width_px = options.width_px,
                             .height_px = options.height_px,
                             .fx = options.fx,
                             .fy = options.fy > 0 ? options.fy : options.fx,
                             .cx = 0.5 * options.width_px - 0.5,
                             .cy = 0.5 * options.height_px - 0.5};
  std::vector<PanoView> views;
  for (int i = 0; i < options.views; ++i) {
    views.push_back({.camera = camera,
                     .yaw_deg = options.first_yaw_deg + i * options.yaw_step_deg,
                     .pitch_deg = options.pitch_deg});
  }
  return views;
}

namespace {

void CheckEquirect(const Image& equirect, const char* caller) {
  CheckArgument(!equirect.empty(), fmt::format("{}: the panorama is empty", caller));
  CheckArgument(std::abs(equirect.width() - 2 * equirect.height()) <= 1,
                fmt::format("{}: an equirectangular panorama is twice as wide as high, got {}x{}", caller,
                            equirect.width(), equirect.height()));
}

// Each view pixel's position in `source` (an equirectangular image) padded by
// kSeamPad columns on either side.
void PanoViewMaps(const PanoView& view, const cv::Mat& source, cv::Mat* map_x, cv::Mat* map_y) {
  const int w = view.camera.width_px, h = view.camera.height_px;
  map_x->create(h, w, CV_32F);
  map_y->create(h, w, CV_32F);
  const Mat3 world_from_camera = view.WorldFromCamera();
  for (int v = 0; v < h; ++v) {
    float* mx = map_x->ptr<float>(v);
    float* my = map_y->ptr<float>(v);
    for (int u = 0; u < w; ++u) {
      const Vec3 ray =
          world_from_camera * Vec3((u - view.camera.cx) / view.camera.fx, (v - view.camera.cy) / view.camera.fy, 1.0);
      const Vec2 p = EquirectPixelFromDirection(ray, source.cols, source.rows);
      mx[u] = static_cast<float>(p.x() + kSeamPad);
      my[u] = static_cast<float>(p.y());
    }
  }
}

}  // namespace

Image RenderPanoView(const Image& equirect, const PanoView& view) {
  view.Check();
  CheckEquirect(equirect, "RenderPanoView");
  const cv::Mat pano = AsMat(equirect);
  // Reduce the panorama where a view pixel spans more than 1.5 panorama
  // pixels (at the view's centre, where its pixels span the most).
  cv::Mat source = pano;
  const double view_px_per_rad = std::min(view.camera.fx, view.camera.fy);
  const double pano_px_per_rad = equirect.width() / (2 * kPi);
  if (pano_px_per_rad > 1.5 * view_px_per_rad) {
    const int width = std::max(8, static_cast<int>(std::ceil(2 * kPi * view_px_per_rad)) & ~1);
    cv::resize(pano, source, cv::Size(width, width / 2), 0, 0, cv::INTER_AREA);
  }
  cv::Mat padded;
  cv::copyMakeBorder(source, padded, 0, 0, kSeamPad, kSeamPad, cv::BORDER_WRAP);

  cv::Mat map_x, map_y, out;
  PanoViewMaps(view, source, &map_x, &map_y);
  cv::remap(padded, out, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return AsImage(out);
}

Image RenderPanoLabelView(const Image& equirect_labels, const PanoView& view) {
  view.Check();
  CheckEquirect(equirect_labels, "RenderPanoLabelView");
  const cv::Mat labels = AsMat(equirect_labels);
  CheckArgument(
      labels.type() == CV_8UC1,
      fmt::format("RenderPanoLabelView: labels are 8-bit with one channel, got OpenCV type {}", labels.type()));
  cv::Mat padded, map_x, map_y, out;
  cv::copyMakeBorder(labels, padded, 0, 0, kSeamPad, kSeamPad, cv::BORDER_WRAP);
  PanoViewMaps(view, labels, &map_x, &map_y);
  cv::remap(padded, out, map_x, map_y, cv::INTER_NEAREST, cv::BORDER_REPLICATE);
  return AsImage(out);
}

}  // namespace asbuilt
