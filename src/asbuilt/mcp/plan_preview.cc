#include "asbuilt/mcp/plan_preview.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/util/error.h"

namespace asbuilt::mcp {
namespace {

// Colours (BGR).
const cv::Scalar kBackground(250, 250, 250);
const cv::Scalar kFloor(232, 238, 242);
const cv::Scalar kWall(55, 55, 55);
const cv::Scalar kWindowFill(240, 215, 160);
const cv::Scalar kWindowLine(150, 90, 30);
const cv::Scalar kDoor(40, 100, 190);
const cv::Scalar kFurnitureFill(170, 200, 225);
const cv::Scalar kFurnitureLine(80, 110, 140);
const cv::Scalar kRig(30, 30, 210);
const cv::Scalar kLight(0, 190, 250);
const cv::Scalar kText(40, 40, 40);

// World (x, y) metres → pixel, +Y up on the picture.
struct Mapping {
  double min_x = 0, max_y = 0, scale = 1;  // Pixels per metre.
  int margin = 0;
  cv::Point2d operator()(const Vec2& p) const {
    return {margin + (p.x() - min_x) * scale, margin + (max_y - p.y()) * scale};
  }
  cv::Point Px(const Vec2& p) const {
    cv::Point2d q = (*this)(p);
    return {static_cast<int>(std::lround(q.x * 16)), static_cast<int>(std::lround(q.y * 16))};
  }
};

constexpr int kShift = 4;  // Sub-pixel bits for OpenCV drawing (×16 above).

Vec2 Rotate(const Vec2& v, double rad) {
  return {std::cos(rad) * v.x() - std::sin(rad) * v.y(), std::sin(rad) * v.x() + std::cos(rad) * v.y()};
}

// Outward normal of a wall of a counter-clockwise polygon (interior on the left).
Vec2 Outward(const Vec2& a, const Vec2& b) {
  Vec2 d = (b - a).normalized();
  return {d.y(), -d.x()};
}

// Polygon offset outwards by `t` with mitred corners (mitre capped at 4t).
std::vector<Vec2> Offset(const std::vector<Vec2>& poly, double t) {
  const std::size_t n = poly.size();
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& prev = poly[(i + n - 1) % n];
    const Vec2& cur = poly[i];
    const Vec2& next = poly[(i + 1) % n];
    if ((cur - prev).norm() < 1e-9 || (next - cur).norm() < 1e-9) {
      out.push_back(cur);
      continue;
    }
    Vec2 n1 = Outward(prev, cur), n2 = Outward(cur, next);
    Vec2 bis = n1 + n2;
    double c = bis.norm();
    if (c < 1e-6) {
      out.push_back(cur + t * n1);
      continue;
    }
    bis /= c;
    double len = t / std::max(0.25, bis.dot(n1));
    out.push_back(cur + len * bis);
  }
  return out;
}

void FillPoly(cv::Mat& img, const Mapping& m, const std::vector<Vec2>& poly, const cv::Scalar& c) {
  std::vector<cv::Point> pts;
  for (const Vec2& p : poly) pts.push_back(m.Px(p));
  if (pts.size() >= 3) cv::fillPoly(img, std::vector<std::vector<cv::Point>>{pts}, c, cv::LINE_AA, kShift);
}

void Line(cv::Mat& img, const Mapping& m, const Vec2& a, const Vec2& b, const cv::Scalar& c,
          int thickness = 1) {
  cv::line(img, m.Px(a), m.Px(b), c, thickness, cv::LINE_AA, kShift);
}

void Text(cv::Mat& img, const std::string& s, cv::Point2d centre, double scale = 0.42,
          const cv::Scalar& c = kText) {
  int baseline = 0;
  cv::Size size = cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  cv::Point origin(static_cast<int>(centre.x - size.width / 2.0),
                   static_cast<int>(centre.y + size.height / 2.0));
  cv::putText(img, s, origin, cv::FONT_HERSHEY_SIMPLEX, scale, c, 1, cv::LINE_AA);
}

void DrawOpening(cv::Mat& img, const Mapping& m, const Room& room, const Opening& o) {
  const int n = static_cast<int>(room.polygon.size());
  if (o.wall < 0 || o.wall >= n) return;
  Vec2 a = room.polygon[o.wall], b = room.polygon[(o.wall + 1) % n];
  if ((b - a).norm() < 1e-9) return;
  Vec2 d = (b - a).normalized();
  Vec2 out = Outward(a, b);
  double t = std::max(room.wall_thickness_m, 0.02);
  Vec2 p0 = a + d * o.offset_m, p1 = a + d * (o.offset_m + o.width_m);
  std::vector<Vec2> gap = {p0 - out * 0.01, p1 - out * 0.01, p1 + out * (t + 0.01),
                           p0 + out * (t + 0.01)};
  if (o.kind == OpeningKind::kWindow) {
    FillPoly(img, m, gap, kWindowFill);
    Line(img, m, p0, p1, kWindowLine);
    Line(img, m, p0 + out * (t / 2), p1 + out * (t / 2), kWindowLine);
    Line(img, m, p0 + out * t, p1 + out * t, kWindowLine);
    return;
  }
  FillPoly(img, m, gap, kBackground);
  // Hinge on the right seen from inside (looking along `out`, right is −d):
  // the opening's start end; on the left, its far end. The leaf swings in.
  bool right = o.hinge == HingeSide::kRight;
  Vec2 hinge = right ? p0 : p1;
  Vec2 closed = (right ? d : -d) * o.width_m;  // Hinge → other jamb.
  double open = DegToRad(o.open_deg > 0 ? o.open_deg : 90.0);
  // Rotate the closed leaf towards the inside (−out).
  double sign = Rotate(closed, 0.1).dot(-out) > 0 ? 1.0 : -1.0;
  Vec2 leaf = Rotate(closed, sign * open);
  Line(img, m, hinge, hinge + leaf, kDoor, 2);
  std::vector<cv::Point> arc;
  for (int i = 0; i <= 24; ++i) arc.push_back(m.Px(hinge + Rotate(closed, sign * open * i / 24.0)));
  cv::polylines(img, arc, false, kDoor, 1, cv::LINE_AA, kShift);
}

void DrawFurniture(cv::Mat& img, const Mapping& m, const Furniture& f) {
  double yaw = DegToRad(f.yaw_deg);
  double hx = f.size_m.x() / 2, hy = f.size_m.y() / 2;
  std::vector<Vec2> box;
  for (Vec2 c : {Vec2(-hx, -hy), Vec2(hx, -hy), Vec2(hx, hy), Vec2(-hx, hy)}) {
    box.push_back(f.centre_m + Rotate(c, yaw));
  }
  FillPoly(img, m, box, kFurnitureFill);
  for (int i = 0; i < 4; ++i) Line(img, m, box[i], box[(i + 1) % 4], kFurnitureLine);
}

// A "nice" scale bar length (1, 2 or 5 × 10^k metres) near `target_m`.
double NiceLength(double target_m) {
  double p = std::pow(10.0, std::floor(std::log10(target_m)));
  for (double k : {1.0, 2.0, 5.0, 10.0}) {
    if (k * p >= target_m) return k * p;
  }
  return 10 * p;
}

}  // namespace

void PlanPreviewOptions::Check() const {
  CheckArgument(width_px >= 64 && width_px <= 4096,
                fmt::format("PlanPreviewOptions.width_px = {}, must be in 64..4096", width_px));
  CheckArgument(max_height_px >= 64 && max_height_px <= 4096,
                fmt::format("PlanPreviewOptions.max_height_px = {}, must be in 64..4096",
                            max_height_px));
  CheckArgument(margin_px >= 0 && 2 * margin_px < std::min(width_px, max_height_px) - 16,
                fmt::format("PlanPreviewOptions.margin_px = {}, must be >= 0 and leave room "
                            "for the drawing", margin_px));
}

std::string RenderPlanPreviewPng(const Scene& scene, const PlanPreviewOptions& options) {
  options.Check();
  const std::vector<Viewpoint> views = ResolveViewpoints(scene);

  // Bounds of everything drawn.
  double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;
  auto grow = [&](const Vec2& p) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return;
    min_x = std::min(min_x, p.x()), max_x = std::max(max_x, p.x());
    min_y = std::min(min_y, p.y()), max_y = std::max(max_y, p.y());
  };
  for (const Room& r : scene.rooms) {
    if (r.polygon.size() < 3) {
      for (const Vec2& p : r.polygon) grow(p);
      continue;
    }
    for (const Vec2& p : Offset(r.polygon, r.wall_thickness_m)) grow(p);
  }
  for (const Furniture& f : scene.furniture) grow(f.centre_m);
  for (const Viewpoint& v : views) grow(v.position_m.head<2>());
  for (const Light& l : scene.lights) {
    if (l.kind != LightKind::kSun) grow(l.position_m.head<2>());
  }
  if (min_x > max_x) min_x = min_y = -3, max_x = max_y = 3;
  double span_x = std::max(max_x - min_x, 1.0), span_y = std::max(max_y - min_y, 1.0);
  double cx = (min_x + max_x) / 2, cy = (min_y + max_y) / 2;
  min_x = cx - span_x / 2, max_y = cy + span_y / 2;

  Mapping m;
  m.margin = options.margin_px;
  m.min_x = min_x;
  m.max_y = max_y;
  m.scale = (options.width_px - 2.0 * options.margin_px) / span_x;
  int height = static_cast<int>(std::ceil(span_y * m.scale)) + 2 * options.margin_px;
  if (height > options.max_height_px) {
    m.scale = (options.max_height_px - 2.0 * options.margin_px) / span_y;
    height = options.max_height_px;
  }
  cv::Mat img(height, options.width_px, CV_8UC3, kBackground);

  // Rooms: walls as the band between the inner polygon and its offset.
  for (const Room& r : scene.rooms) {
    if (r.polygon.size() < 3) continue;
    FillPoly(img, m, Offset(r.polygon, std::max(r.wall_thickness_m, 0.02)), kWall);
    FillPoly(img, m, r.polygon, kFloor);
  }
  for (const Room& r : scene.rooms) {
    for (const Opening& o : r.openings) DrawOpening(img, m, r, o);
  }
  for (const Furniture& f : scene.furniture) DrawFurniture(img, m, f);
  for (const Light& l : scene.lights) {
    if (l.kind == LightKind::kSun) continue;
    cv::circle(img, m.Px(l.position_m.head<2>()), 5 * 16, kLight, 2, cv::LINE_AA, kShift);
  }

  // The rig: a dot per position, a short ray per view direction.
  const std::size_t max_rays = 360;
  for (std::size_t i = 0; i < views.size() && i < max_rays; ++i) {
    Vec2 p = views[i].position_m.head<2>();
    double yaw = DegToRad(views[i].yaw_deg);
    Vec2 forward(-std::sin(yaw), std::cos(yaw));
    if (options.view_rays) Line(img, m, p, p + forward * (28.0 / m.scale), kRig, 1);
    cv::circle(img, m.Px(p), 4 * 16, kRig, cv::FILLED, cv::LINE_AA, kShift);
  }

  // Wall numbers and lengths, outside each wall.
  if (options.wall_labels) {
    for (const Room& r : scene.rooms) {
      const int n = static_cast<int>(r.polygon.size());
      if (n < 3) continue;
      for (int w = 0; w < n; ++w) {
        Vec2 a = r.polygon[w], b = r.polygon[(w + 1) % n];
        if ((b - a).norm() < 1e-9) continue;
        Vec2 mid = (a + b) / 2 + Outward(a, b) * (r.wall_thickness_m + 16.0 / m.scale);
        Text(img, fmt::format("{}: {:.2f} m", w, (b - a).norm()), m(mid));
      }
    }
  }

  // North arrow (top right) and scale bar (bottom left).
  cv::Point2d north(options.width_px - 22.0, 36.0);
  cv::arrowedLine(img, north + cv::Point2d(0, 18), north - cv::Point2d(0, 10), kText, 2,
                  cv::LINE_AA, 0, 0.35);
  Text(img, "N", north - cv::Point2d(0, 20), 0.45);
  double bar_m = NiceLength(span_x / 5);
  double bar_px = bar_m * m.scale;
  cv::Point2d bar0(12, height - 14.0), bar1(12 + bar_px, height - 14.0);
  cv::line(img, bar0, bar1, kText, 2, cv::LINE_AA);
  cv::line(img, bar0 - cv::Point2d(0, 4), bar0 + cv::Point2d(0, 4), kText, 1, cv::LINE_AA);
  cv::line(img, bar1 - cv::Point2d(0, 4), bar1 + cv::Point2d(0, 4), kText, 1, cv::LINE_AA);
  Text(img, fmt::format("{:g} m", bar_m), cv::Point2d((bar0.x + bar1.x) / 2, height - 26.0), 0.4);
  if (scene.rooms.empty()) {
    Text(img, "no rooms yet: call add_room", cv::Point2d(options.width_px / 2.0, height / 2.0), 0.6);
  }

  std::vector<unsigned char> png;
  if (!cv::imencode(".png", img, png)) throw Error("plan preview: PNG encoding failed");
  return std::string(png.begin(), png.end());
}

}  // namespace asbuilt::mcp
