#include "asbuilt/pano/layout_labels.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <opencv2/core.hpp>

#include "asbuilt/geometry/label_class.h"
#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

std::uint8_t LabelOfOpening(ZindOpeningKind kind) {
  switch (kind) {
    case ZindOpeningKind::kDoor:
      return 2;
    case ZindOpeningKind::kWindow:
      return 3;
    case ZindOpeningKind::kOpening:
      return kPassageLabel;
  }
  return kPassageLabel;
}

// A wall's rectangle: the edge a → b, and the openings on it as intervals
// along the edge (metres from a) and heights.
struct WallRect {
  Vec2 a, dir;  // dir: unit vector a → b.
  double length = 0;
  struct Hole {
    double s0, s1, bottom, top;
    std::uint8_t label;
  };
  std::vector<Hole> holes;
};

// The layout as wall rectangles, built once per image.
class LayoutScene {
 public:
  LayoutScene(const ZindPanorama& pano, const ZindLayout& layout)
      : camera_(0, 0, pano.camera_height_m), ceiling_(pano.ceiling_height_m) {
    const std::size_t n = layout.vertices_m.size();
    for (std::size_t i = 0; i < n; ++i) {
      WallRect w;
      w.a = layout.vertices_m[i];
      const Vec2 b = layout.vertices_m[(i + 1) % n];
      w.length = (b - w.a).norm();
      w.dir = w.length > 0 ? Vec2((b - w.a) / w.length) : Vec2(1, 0);
      walls_.push_back(w);
    }
    for (const ZindOpening& o : layout.openings) {
      if (o.wall < 0 || o.wall >= static_cast<int>(walls_.size())) continue;
      WallRect& w = walls_[static_cast<std::size_t>(o.wall)];
      double s0 = w.dir.dot(o.start_m - w.a), s1 = w.dir.dot(o.end_m - w.a);
      if (s0 > s1) std::swap(s0, s1);
      w.holes.push_back({s0, s1, o.bottom_m, o.top_m, LabelOfOpening(o.kind)});
    }
  }

  std::uint8_t Label(const Vec3& ray) const {
    // Nearest wall along the ray's horizontal part: camera_xy + t·ray_xy = a + s·dir.
    const Vec2 origin = camera_.head<2>(), d = ray.head<2>();
    double best_t = std::numeric_limits<double>::infinity(), best_s = 0;
    const WallRect* best = nullptr;
    for (const WallRect& w : walls_) {
      const double den = Cross(d, w.dir);
      if (std::abs(den) < 1e-12 || w.length <= 0) continue;
      const Vec2 ao = w.a - origin;
      const double t = Cross(ao, w.dir) / den;
      const double s = Cross(ao, d) / den;
      if (t <= 0 || s < 0 || s > w.length || t >= best_t) continue;
      best_t = t;
      best_s = s;
      best = &w;
    }
    if (best == nullptr) return 0;
    const double z = camera_.z() + best_t * ray.z();
    if (z < 0 || z > ceiling_) return 0;  // Floor or ceiling first.
    std::uint8_t label = 1;
    for (const WallRect::Hole& h : best->holes) {
      if (best_s >= h.s0 && best_s <= h.s1 && z >= h.bottom && z <= h.top) {
        // A passage drawn over a door keeps the ignore label; otherwise the first wins.
        if (label == kLabelWall || h.label == kPassageLabel) label = h.label;
      }
    }
    return label;
  }

 private:
  Vec3 camera_;
  double ceiling_;
  std::vector<WallRect> walls_;
};

}  // namespace

std::uint8_t LayoutLabelOfRay(const ZindPanorama& pano, const ZindLayout& layout, const Vec3& ray) {
  return LayoutScene(pano, layout).Label(ray);
}

Image LayoutLabels(const ZindPanorama& pano, const PanoView& view, ZindLayoutKind layout) {
  view.Check();
  const LayoutScene scene(pano, pano.Layout(layout));
  const Mat3 world_from_camera = view.WorldFromCamera();
  Image labels(view.camera.width_px, view.camera.height_px, 1, PixelType::kU8);
  for (int v = 0; v < labels.height(); ++v) {
    std::uint8_t* row = labels.Row<std::uint8_t>(v);
    for (int u = 0; u < labels.width(); ++u) {
      row[u] = scene.Label(world_from_camera *
                           Vec3((u - view.camera.cx) / view.camera.fx, (v - view.camera.cy) / view.camera.fy, 1.0));
    }
  }
  return labels;
}

Image LayoutLabelsEquirect(const ZindPanorama& pano, int width_px, int height_px, ZindLayoutKind layout) {
  CheckArgument(width_px > 0 && height_px > 0,
                fmt::format("LayoutLabelsEquirect: size {}x{}, must be positive", width_px, height_px));
  const LayoutScene scene(pano, pano.Layout(layout));
  Image labels(width_px, height_px, 1, PixelType::kU8);
  for (int v = 0; v < height_px; ++v) {
    std::uint8_t* row = labels.Row<std::uint8_t>(v);
    for (int u = 0; u < width_px; ++u)
      row[u] = scene.Label(DirectionFromEquirectPixel(Vec2(u, v), width_px, height_px));
  }
  return labels;
}

Image DrawLabelOverlay(const Image& bgr_image, const Image& labels_image, double alpha) {
  const cv::Mat bgr = AsMat(bgr_image), labels = AsMat(labels_image);
  CheckArgument(bgr.type() == CV_8UC3 && labels.type() == CV_8UC1 && bgr.size() == labels.size(),
                "DrawLabelOverlay: needs an 8-bit BGR image and 8-bit labels of the same size");
  // BGR, as seg's LabelOverlay: wall blue, door green, window red; ignore grey.
  const auto colour = [](std::uint8_t l) -> const cv::Vec3b* {
    static const cv::Vec3b kColours[4] = {{0, 0, 0}, {255, 128, 0}, {0, 200, 0}, {0, 0, 255}};
    static const cv::Vec3b kIgnore = {128, 128, 128};
    if (l >= 1 && l <= 3) return &kColours[l];
    return l == kPassageLabel ? &kIgnore : nullptr;
  };
  cv::Mat out = bgr.clone();
  for (int r = 0; r < out.rows; ++r) {
    cv::Vec3b* o = out.ptr<cv::Vec3b>(r);
    const std::uint8_t* l = labels.ptr<std::uint8_t>(r);
    for (int c = 0; c < out.cols; ++c) {
      const cv::Vec3b* k = colour(l[c]);
      if (k == nullptr) continue;
      for (int i = 0; i < 3; ++i) o[c][i] = static_cast<std::uint8_t>((1 - alpha) * o[c][i] + alpha * (*k)[i]);
    }
  }
  return AsImage(out);
}

}  // namespace asbuilt
