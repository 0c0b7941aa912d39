#include "asbuilt/stereo/frame_points.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "asbuilt/geometry/label_class.h"
#include "asbuilt/stereo/cue_choice.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

bool IsComponent(unsigned char label) { return label >= 1 && label <= 3; }

// Median of the valid disparities in a (2r+1)² window; NaN if fewer than 3.
double GuideDisparity(const cv::Mat& disparity, const Vec2& px, int r) {
  const int cu = static_cast<int>(std::lround(px.x())), cv_ = static_cast<int>(std::lround(px.y()));
  std::vector<float> v;
  for (int y = std::max(0, cv_ - r); y <= std::min(disparity.rows - 1, cv_ + r); ++y) {
    const float* d = disparity.ptr<float>(y);
    for (int x = std::max(0, cu - r); x <= std::min(disparity.cols - 1, cu + r); ++x) {
      if (std::isfinite(d[x])) v.push_back(d[x]);
    }
  }
  if (v.size() < 3) return NAN;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Median valid disparity over the pixels of `label` within radius r; NaN if
// fewer than 5.
double ClassDisparity(const cv::Mat& disparity, const cv::Mat& labels, const Vec2& px, unsigned char label, int r) {
  const int cu = static_cast<int>(std::lround(px.x())), cv_ = static_cast<int>(std::lround(px.y()));
  std::vector<float> v;
  for (int y = std::max(0, cv_ - r); y <= std::min(disparity.rows - 1, cv_ + r); ++y) {
    const float* d = disparity.ptr<float>(y);
    const unsigned char* l = labels.ptr<unsigned char>(y);
    for (int x = std::max(0, cu - r); x <= std::min(disparity.cols - 1, cu + r); ++x) {
      if (l[x] == label && std::isfinite(d[x])) v.push_back(d[x]);
    }
  }
  if (v.size() < 5) return NAN;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

bool RightLabelAgrees(const cv::Mat& labels_right, const Vec2& right_px, unsigned char label, int radius) {
  if (labels_right.empty()) return true;
  const int cu = static_cast<int>(std::lround(right_px.x())), cv_ = static_cast<int>(std::lround(right_px.y()));
  for (int y = std::max(0, cv_ - radius); y <= std::min(labels_right.rows - 1, cv_ + radius); ++y) {
    for (int x = std::max(0, cu - radius); x <= std::min(labels_right.cols - 1, cu + radius); ++x) {
      if (labels_right.at<unsigned char>(y, x) == label) return true;
    }
  }
  return false;
}

// Whether the label edge between columns u_wall (wall) and u_open (class c)
// of row v continues straight up and down for `rows` rows: each of those rows
// has the same wall → c transition within one pixel of it.
bool VerticalEdge(const cv::Mat& labels, int v, int u_wall, int u_open, unsigned char c, int rows) {
  for (int y = v - rows; y <= v + rows; ++y) {
    if (y == v) continue;
    if (y < 0 || y >= labels.rows) return false;
    const unsigned char* l = labels.ptr<unsigned char>(y);
    bool found = false;
    for (int shift = -1; shift <= 1 && !found; ++shift) {
      const int w = u_wall + shift, o = u_open + shift;
      if (std::min(w, o) < 0 || std::max(w, o) >= labels.cols) continue;
      found = l[w] == kLabelWall && l[o] == c;
    }
    if (!found) return false;
  }
  return true;
}

cv::Mat ToGray8(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat gray;
  cv::cvtColor(image, gray, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return gray;
}

}  // namespace

void FramePointsOptions::Check() const {
  disparity.Check();
  corners.Check();
  match.Check();
  vertices.Check();
  // Every single-option bound is stated once, in FramePointsOptionFields().
  FramePointsOptionFields().CheckValues(*this, "FramePointsOptions");
  CheckArgument(
      max_depth_m > min_depth_m,
      fmt::format("FramePointsOptions.min_depth_m = {}, max_depth_m = {}: need min < max", min_depth_m, max_depth_m));
}

std::string FrameCues::CarriedBy() const {
  std::string out;
  auto add = [&](bool on, const char* name) {
    if (!on) return;
    if (!out.empty()) out += '+';
    out += name;
  };
  add(corners_matched > 0, "corner");
  add(edge_points > 0, "edge");
  add(dense_points > 0, "dense");
  add(boundary_points > 0, "boundary");
  add(vertex_points > 0, "vertex");
  add(floor_contacts + ceiling_contacts > 0, "contact");
  return out.empty() ? "none" : out;
}

std::string FrameCues::BriefReport() const {
  return fmt::format(
      "frame {}: corners {}/{}, edges {}/{}, dense {} ({} refined; {:.0f}% of labelled px "
      "consistent), boundary {}, "
      "vertices {}, contacts floor {} (+{} occluded) ceiling {}{} — {}, {:.0f} "
      "ms",
      index, corners_matched, corners_found, edge_points, edge_candidates, dense_points, dense_refined,
      100.0 * dense_valid_fraction, boundary_points, vertex_points, floor_contacts, floor_rejected, ceiling_contacts,
      stereo_checked == 0 ? ""
                          : fmt::format(", wall stereo consistent down its "
                                        "columns at {}/{} px ({:.0f} %)",
                                        stereo_agreed, stereo_checked, 100.0 * stereo_agreed / stereo_checked),
      CarriedBy(), 1000.0 * seconds);
}

namespace {

// What one pass over a frame shares between its cues (FramePointsPass).
struct FramePass {
  const StereoFrame& frame;
  const FramePointsOptions& options;
  // Wall pixels give corner/edge/dense points (outside contacted columns)
  // and boundary points take the wall's stereo depth; without it they take
  // the contacts'.
  bool wall_stereo = true;
  cv::Mat gray_left8;                     // CV_8UC1.
  cv::Mat gray_left, gray_right;          // CV_32F.
  double full_min = 0.0, full_max = 0.0;  // The disparity search range (px).
  Eigen::Isometry3d world_from_cam = Eigen::Isometry3d::Identity();
  // Wall pixels placed by a contact (CV_8U), and per column the wall's
  // disparity at its floor contact (NaN: none): FrameContacts.
  cv::Mat covered;
  std::vector<float> contact_disparity;
  std::vector<float> ceiling_rise;  // Per column, FrameContacts::ceiling_rise.
  FramePointsResult* result = nullptr;

  const cv::Mat& disparity() const { return result->disparity.disparity_px; }

  // Triangulates (Z = f·B/d, X = (u − cx)·Z/fx, Y = (v − cy)·Z/fy) into the
  // world and adds the point; nullopt when it lies outside the depth range.
  // Its σ is σ_d's at the depth of `d_for_sigma` (the neighbourhood's
  // disparity, FramePointsOptions::sigma_from_neighbours) when finite, else
  // of d.
  std::optional<Vec3> AddPoint(unsigned char label, const Vec2& px, double d, double sigma_d, PointSource source,
                               double d_for_sigma = NAN) const {
    const double fx = frame.camera.fx;
    const std::optional<double> z = DepthFromDisparity(fx, frame.baseline_m, d);
    if (!z || *z < options.min_depth_m || *z > options.max_depth_m) return std::nullopt;
    const Vec3 p = world_from_cam * UnprojectToCamera(frame.camera, px, *z);
    const std::optional<double> z_sigma = options.sigma_from_neighbours && std::isfinite(d_for_sigma)
                                              ? DepthFromDisparity(fx, frame.baseline_m, d_for_sigma)
                                              : z;
    result->points.push_back({static_cast<LabelClass>(label), p,
                              DepthSigmaFromDisparitySigma(fx, frame.baseline_m, z_sigma.value_or(*z), sigma_d), source,
                              frame.index});
    return p;
  }

  // A match along the row, searched around the dense disparity there.
  std::optional<RowMatch> MatchGuided(const Vec2& px) const {
    const double guide = GuideDisparity(disparity(), px, static_cast<int>(std::ceil(options.guide_radius_px)));
    const double lo = std::isfinite(guide) ? guide - options.guide_radius_px : full_min;
    const double hi = std::isfinite(guide) ? guide + options.guide_radius_px : full_max;
    return MatchAlongRow(gray_left, gray_right, px, lo, hi, options.match);
  }

  // Whether a pixel's point is already placed by a contact (or, without the
  // wall's stereo, wall pixels give no stereo points at all).
  bool Explained(const Vec2& px, unsigned char label) const {
    if (label != kLabelWall) return false;
    if (!wall_stereo) return true;
    const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
    return u >= 0 && v >= 0 && u < covered.cols && v < covered.rows && covered.at<unsigned char>(v, u) != 0;
  }
};

// Corners: contour polygons per class, matched along the row.
void AddCornerPoints(const FramePass& pass) {
  const FramePointsOptions& options = pass.options;
  const StereoFrame& frame = pass.frame;
  FramePointsResult& result = *pass.result;
  const auto corners = FindClassCorners(frame.labels_left, pass.gray_left8, options.corners);
  result.cues.corners_found = static_cast<int>(corners.size());
  for (const ClassCorner& c : corners) {
    if (pass.Explained(c.pixel, static_cast<unsigned char>(c.label))) continue;
    const auto m = pass.MatchGuided(c.pixel);
    if (!m) continue;
    const unsigned char label = static_cast<unsigned char>(c.label);
    // A corner where a nearer object cuts the region (a T-junction) takes
    // the occluder's disparity; the region's own pixels disagree.
    const double own =
        ClassDisparity(pass.disparity(), frame.labels_left, c.pixel, label, 2 * options.match.patch_radius_px);
    if (std::isfinite(own) && std::abs(own - m->disparity_px) > options.corner_region_tolerance_px) continue;
    const Vec2 right_px(c.pixel.x() - m->disparity_px, c.pixel.y() + m->row_offset_px);
    if (!RightLabelAgrees(frame.labels_right, right_px, label, options.right_label_radius_px)) continue;
    if (auto p = pass.AddPoint(label, c.pixel, m->disparity_px, options.corner_sigma_px, PointSource::kCorner, own)) {
      result.corners.push_back({c, *m, *p});
      ++result.cues.corners_matched;
    }
  }
}

// Edges: row maxima of the horizontal gradient inside component regions,
// away from background (whose edges may be occlusions: furniture).
void AddEdgePoints(const FramePass& pass) {
  const FramePointsOptions& options = pass.options;
  const StereoFrame& frame = pass.frame;
  const cv::Mat& gray_left = pass.gray_left;
  FramePointsResult& result = *pass.result;
  cv::Mat gx;
  cv::Sobel(gray_left, gx, CV_32F, 1, 0, 3, 0.25);  // Gray levels per pixel.
  gx = cv::abs(gx);
  const int h = options.match.patch_radius_px;
  // Door/window regions hold the glass and what lies beyond; only their
  // frames (a band along the region border) give edge points.
  cv::Mat band_distance;
  {
    cv::Mat opening = (frame.labels_left == kLabelDoor) | (frame.labels_left == kLabelWindow);
    cv::distanceTransform(opening, band_distance, cv::DIST_L2, 3);
  }
  const float opening_band_px = static_cast<float>(options.window_band_px);
  for (int v = h + 2; v < gray_left.rows - h - 2; v += options.edge_row_step_px) {
    const float* g = gx.ptr<float>(v);
    const unsigned char* lab = frame.labels_left.ptr<unsigned char>(v);
    for (int u = h + 2; u < gray_left.cols - h - 2; ++u) {
      if (!IsComponent(lab[u]) || g[u] < options.edge_min_gradient || g[u] < g[u - 1] || g[u] <= g[u + 1]) {
        continue;
      }
      if (pass.Explained(Vec2(u, v), lab[u])) continue;
      if (lab[u] != kLabelWall && band_distance.at<float>(v, u) > opening_band_px) continue;
      bool clean = true;
      for (int y = v - 1; y <= v + 1 && clean; ++y) {
        const unsigned char* row = frame.labels_left.ptr<unsigned char>(y);
        for (int x = u - h; x <= u + h; ++x) {
          if (!IsComponent(row[x])) {
            clean = false;
            break;
          }
        }
      }
      if (!clean) continue;
      ++result.cues.edge_candidates;
      const Vec2 px(u, v);
      const auto m = pass.MatchGuided(px);
      if (!m) continue;
      // The region's own disparity over a window wider than the matcher's
      // foreground fattening: an edge of a nearer object (an open door
      // leaf) must not lend its disparity to the wall behind it.
      const double own =
          ClassDisparity(pass.disparity(), frame.labels_left, px, lab[u], 2 * options.match.patch_radius_px);
      if (std::isfinite(own) && std::abs(own - m->disparity_px) > options.corner_region_tolerance_px) continue;
      if (!RightLabelAgrees(frame.labels_right, Vec2(u - m->disparity_px, v + m->row_offset_px), lab[u],
                            options.right_label_radius_px)) {
        continue;
      }
      if (pass.AddPoint(lab[u], px, m->disparity_px, options.edge_sigma_px, PointSource::kEdge, own)) {
        ++result.cues.edge_points;
      }
    }
  }
}

// Vertices: wall–wall corner columns, placed by their own matches (they
// need no texture on the walls, nor a contact).
void AddVertexPoints(const FramePass& pass) {
  const FramePointsOptions& options = pass.options;
  FramePointsResult& result = *pass.result;
  for (const WallVertex& wv : FindWallVertices(pass.gray_left, pass.gray_right, pass.frame.labels_left, pass.full_min,
                                               pass.full_max, options.vertices)) {
    if (pass.AddPoint(1, Vec2(wv.u_left_px, wv.v_mid_px), wv.disparity_px, options.vertex_sigma_px,
                      PointSource::kVertex)) {
      ++result.cues.vertex_points;
    }
  }
}

// The median of a per-column figure over the columns u0 + dir·k, k in
// [0, to], where it is finite; NaN if nowhere.
double SideMedian(const std::vector<float>& per_column, int u0, int dir, int to) {
  std::vector<float> vals;
  for (int k = 0; k <= to; ++k) {
    const int x = u0 + dir * k;
    if (x < 0 || x >= static_cast<int>(per_column.size())) break;
    if (std::isfinite(per_column[x])) vals.push_back(per_column[x]);
  }
  if (vals.empty()) return NAN;
  std::nth_element(vals.begin(), vals.begin() + vals.size() / 2, vals.end());
  return vals[vals.size() / 2];
}

// A one-camera view's opening edge with no floor contact beside it: it
// waits for the ceiling's height, at the depth of the wall's ceiling edge in
// the columns u0 + dir·k, k in [0, to] (PendingContacts::CeilingBoundary).
void AddCeilingBoundary(const FramePass& pass, unsigned char label, const Vec2& px, int u0, int dir, int to) {
  const double rise = SideMedian(pass.ceiling_rise, u0, dir, to);
  if (!std::isfinite(rise)) return;
  const Vec3 direction = pass.world_from_cam.linear() * UnprojectToCamera(pass.frame.camera, px, 1.0);
  pass.result->contacts.ceiling_boundaries.push_back({.edge = {.label = static_cast<LabelClass>(label),
                                                               .origin_m = pass.world_from_cam.translation(),
                                                               .direction = direction,
                                                               .fy_px = pass.frame.camera.fy,
                                                               .frame = pass.frame.index},
                                                      .wall_rise = rise});
}

// Boundaries: where a door/window label meets the wall along a row, the
// label edge lies halfway between the two pixel centres; it is placed at
// the wall's depth there, so the opening's edge is measured on the wall
// surface (the plan then slides it along its viewing ray onto the fitted
// wall). Casings protrude only 1.5 cm, so near the edge the opening's own
// depth is the wall's; where it is not, the edge is an occlusion.
void AddBoundaryPoints(const FramePass& pass) {
  const FramePointsOptions& options = pass.options;
  const StereoFrame& frame = pass.frame;
  const cv::Mat& disparity = pass.disparity();
  FramePointsResult& result = *pass.result;
  const cv::Mat& labels = frame.labels_left;
  const cv::Mat& valid = result.disparity.valid;
  const int rows = labels.rows, cols = labels.cols;
  // Median valid disparity of `label` pixels in rows v ± 2, at columns
  // u0 + dir·k for k in [from, to]; NaN if fewer than 3.
  auto side_disparity = [&](int v, int u0, int dir, int from, int to, unsigned char label) {
    std::vector<float> vals;
    for (int y = std::max(0, v - 2); y <= std::min(rows - 1, v + 2); ++y) {
      const unsigned char* l = labels.ptr<unsigned char>(y);
      const unsigned char* ok = valid.ptr<unsigned char>(y);
      const float* d = disparity.ptr<float>(y);
      for (int k = from; k <= to; ++k) {
        const int x = u0 + dir * k;
        if (x < 0 || x >= cols) break;
        if (l[x] == label && ok[x] && std::isfinite(d[x])) vals.push_back(d[x]);
      }
    }
    if (vals.size() < 3) return static_cast<double>(NAN);
    std::nth_element(vals.begin(), vals.begin() + vals.size() / 2, vals.end());
    return static_cast<double>(vals[vals.size() / 2]);
  };
  // The contact disparity of the wall beside the edge: the median over the
  // contacted columns u0 + dir·k, k in [0, to]; NaN if none.
  auto contact_side = [&](int u0, int dir, int to) { return SideMedian(pass.contact_disparity, u0, dir, to); };
  auto run_of = [&](const unsigned char* row, int u0, int dir, unsigned char label, int n) {
    for (int k = 0; k < n; ++k) {
      const int x = u0 + dir * k;
      if (x < 0 || x >= cols || row[x] != label) return false;
    }
    return true;
  };
  for (int v = 2; v < rows - 2; v += options.boundary_row_step_px) {
    const unsigned char* lab = labels.ptr<unsigned char>(v);
    for (int u = 1; u < cols; ++u) {
      const unsigned char a = lab[u - 1], b = lab[u];
      unsigned char c = 0;
      int u_wall = 0, u_open = 0, to_wall = 0;
      if (a == 1 && (b == 2 || b == 3)) {
        c = b, u_wall = u - 1, u_open = u, to_wall = -1;
      } else if (b == 1 && (a == 2 || a == 3)) {
        c = a, u_wall = u, u_open = u - 1, to_wall = 1;
      } else {
        continue;
      }
      // Both sides a few pixels wide (no label slivers).
      if (!run_of(lab, u_wall, to_wall, 1, 3) || !run_of(lab, u_open, -to_wall, c, 3)) continue;
      // Only the sides of an opening: the cameras are level, so its
      // vertical edges are image columns; a row also crosses the slanted
      // top and bottom edges of an obliquely seen opening.
      if (!VerticalEdge(labels, v, u_wall, u_open, c, options.boundary_vertical_rows)) continue;
      const double d_wall =
          pass.wall_stereo
              ? side_disparity(v, u_wall, to_wall, options.boundary_wall_gap_px,
                               options.boundary_wall_gap_px + options.boundary_wall_span_px, 1)
              : contact_side(u_wall, to_wall, options.boundary_wall_gap_px + options.boundary_wall_span_px);
      if (!std::isfinite(d_wall)) {
        if (!pass.wall_stereo && frame.labels_right.empty()) {
          AddCeilingBoundary(pass, c, Vec2(u - 0.5, v), u_wall, to_wall,
                             options.boundary_wall_gap_px + options.boundary_wall_span_px);
        }
        continue;
      }
      // (Without the wall's stereo, the opening's own is no better: no check.)
      if (pass.wall_stereo) {
        const double d_in = side_disparity(v, u_open, -to_wall, 0, options.boundary_inside_px - 1, c);
        if (!std::isfinite(d_in) || std::abs(d_in - d_wall) > std::max(options.boundary_tolerance_px, 0.08 * d_wall)) {
          continue;
        }
      }
      const Vec2 px(u - 0.5, v);
      if (!RightLabelAgrees(frame.labels_right, Vec2(px.x() - d_wall, v), c, options.right_label_radius_px)) {
        continue;
      }
      if (pass.AddPoint(c, px, d_wall, options.boundary_sigma_px, PointSource::kBoundary)) {
        ++result.cues.boundary_points;
      }
    }
  }
}

// The share of labelled wall/door/window pixels with a consistent disparity.
double DenseValidFraction(const cv::Mat& labels, const cv::Mat& valid) {
  int labelled = 0, consistent = 0;
  for (int v = 0; v < labels.rows; ++v) {
    const unsigned char* lab = labels.ptr<unsigned char>(v);
    const unsigned char* ok = valid.ptr<unsigned char>(v);
    for (int u = 0; u < labels.cols; ++u) {
      if (IsComponent(lab[u])) {
        ++labelled;
        consistent += ok[u] != 0;
      }
    }
  }
  return labelled > 0 ? static_cast<double>(consistent) / labelled : NAN;
}

// Half the side of the window over which NeighbourDisparity averages, px:
// wide against the matcher's per-pixel noise, narrow against a wall's
// change of depth across the image.
constexpr int kNeighbourRadiusPx = 6;

// Per pixel, the mean of the valid disparities of `label` pixels in the
// (2r+1)² window around it (CV_32F; NaN where there are none): the depth a
// dense point's σ is taken at, so that its weight in the plan's fit does not
// rise with its own error (a point read too near would otherwise count more,
// as σ ∝ Z², and pull its wall in).
cv::Mat NeighbourDisparity(const cv::Mat& disparity, const cv::Mat& valid, const cv::Mat& labels, unsigned char label,
                           int r) {
  cv::Mat use = (labels == label) & valid, values = cv::Mat::zeros(disparity.size(), CV_32F), count;
  disparity.copyTo(values, use);
  use.convertTo(count, CV_32F, 1.0 / 255);
  const cv::Size window(2 * r + 1, 2 * r + 1);
  cv::boxFilter(values, values, CV_32F, window, cv::Point(-1, -1), /*normalize=*/false, cv::BORDER_CONSTANT);
  cv::boxFilter(count, count, CV_32F, window, cv::Point(-1, -1), /*normalize=*/false, cv::BORDER_CONSTANT);
  cv::Mat mean(disparity.size(), CV_32F, cv::Scalar(NAN));
  cv::divide(values, count, mean);
  mean.setTo(NAN, count < 0.5f);
  return mean;
}

// Dense: consistent disparities well inside each enabled class region.
void AddDensePoints(const FramePass& pass) {
  const FramePointsOptions& options = pass.options;
  const StereoFrame& frame = pass.frame;
  const cv::Mat& disparity = pass.disparity();
  FramePointsResult& result = *pass.result;
  const bool enabled[4] = {false, options.dense_wall, options.dense_door, options.dense_window};
  const cv::Mat kernel = cv::getStructuringElement(
      cv::MORPH_RECT, cv::Size(2 * options.dense_inset_px + 1, 2 * options.dense_inset_px + 1));
  for (int c = kLabelWall; c <= kLabelWindow; ++c) {
    if (!enabled[c]) continue;
    cv::Mat mask = frame.labels_left == c;
    if (options.dense_inset_px > 0) cv::erode(mask, mask, kernel);
    if (c == kLabelWindow) {
      // Windows: only the frame and casing band along the region border;
      // the glass shows the outside.
      cv::Mat distance;
      cv::distanceTransform(frame.labels_left == c, distance, cv::DIST_L2, 3);
      mask &= distance <= options.window_band_px;
    }
    const cv::Mat neighbours = NeighbourDisparity(disparity, result.disparity.valid, frame.labels_left,
                                                  static_cast<unsigned char>(c), kNeighbourRadiusPx);
    for (int v = 0; v < mask.rows; v += options.dense_stride_px) {
      const unsigned char* m = mask.ptr<unsigned char>(v);
      const unsigned char* ok = result.disparity.valid.ptr<unsigned char>(v);
      const float* d = disparity.ptr<float>(v);
      const float* around = neighbours.ptr<float>(v);
      for (int u = 0; u < mask.cols; u += options.dense_stride_px) {
        if (!m[u] || !ok[u] || !std::isfinite(d[u])) continue;
        if (c == kLabelWall && (!pass.wall_stereo || pass.covered.at<unsigned char>(v, u))) continue;
        if (!RightLabelAgrees(frame.labels_right, Vec2(u - d[u], v), static_cast<unsigned char>(c), 0)) continue;
        // SGBM's sub-pixel parabola is drawn towards whole pixels; where the
        // images pin the disparity down better, take theirs.
        double disparity_px = d[u], u_px = u;
        bool refined = false;
        if (options.dense_refine_radius_px > 0) {
          const auto r = RefineDisparityAt(pass.gray_left, pass.gray_right, u, v, d[u], options.dense_refine_radius_px);
          if (r && r->sigma_px <= options.dense_refine_max_sigma_px) {
            disparity_px = r->disparity_px;
            u_px = r->left_u_px;
            refined = true;
          }
        }
        if (pass.AddPoint(static_cast<unsigned char>(c), Vec2(u_px, v), disparity_px, options.dense_sigma_px,
                          PointSource::kDense, around[u])) {
          ++result.cues.dense_points;
          result.cues.dense_refined += refined;
        }
      }
    }
  }
}

// One pass over a frame. `contacts`: add contact points (and run the stereo
// check); `wall_stereo`: FramePass::wall_stereo. `disparity_given`: reuse
// this disparity instead of computing one.
FramePointsResult FramePointsPass(const StereoFrame& frame, const FramePointsOptions& options, bool contacts,
                                  bool wall_stereo, const DisparityResult* disparity_given) {
  const auto start = std::chrono::steady_clock::now();
  FramePointsResult result;
  result.cues.index = frame.index;
  FramePass pass{.frame = frame, .options = options, .wall_stereo = wall_stereo, .result = &result};
  pass.gray_left8 = ToGray8(frame.left);
  pass.gray_left8.convertTo(pass.gray_left, CV_32F);
  ToGray8(frame.right).convertTo(pass.gray_right, CV_32F);
  result.disparity = disparity_given ? *disparity_given : ComputeDisparity(frame.left, frame.right, options.disparity);
  pass.full_min = result.disparity.min_disparity_px;
  pass.full_max = pass.full_min + result.disparity.num_disparities_px - 1;
  pass.world_from_cam = WorldFromCamera(frame.pose, frame.baseline_m, StereoEye::kLeft);

  // Contacts first (contacts.h): wall pixels of contacted columns give no
  // stereo points below.
  if (contacts) {
    FrameContacts found = FindFrameContacts(frame, result.disparity.disparity_px, options);
    result.points = std::move(found.points);
    result.contacts = std::move(found.pending);
    result.cues.floor_contacts = found.floor_contacts;
    result.cues.floor_rejected = found.floor_rejected;
    result.cues.ceiling_contacts = found.ceiling_contacts;
    result.cues.skirting_height_m = found.skirting_height_m;
    pass.covered = std::move(found.covered);
    pass.contact_disparity = std::move(found.wall_disparity_px);
    pass.ceiling_rise = std::move(found.ceiling_rise);
    if (!wall_stereo) {
      const WallStereoCheck check = CheckWallStereo(frame.labels_left, result.disparity, options);
      result.cues.stereo_checked = check.checked;
      result.cues.stereo_agreed = check.agreed;
    }
  } else {
    pass.covered = cv::Mat::zeros(frame.labels_left.size(), CV_8U);
    pass.contact_disparity.assign(frame.labels_left.cols, NAN);
    pass.ceiling_rise.assign(frame.labels_left.cols, NAN);
  }
  if (options.use_corners) AddCornerPoints(pass);
  if (options.use_edges) AddEdgePoints(pass);
  if (options.use_vertices) AddVertexPoints(pass);
  if (options.use_boundaries) AddBoundaryPoints(pass);
  result.cues.dense_valid_fraction = DenseValidFraction(frame.labels_left, result.disparity.valid);
  if (options.use_dense) AddDensePoints(pass);
  result.cues.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace

FramePointsResult ComputeFramePoints(const StereoFrame& frame, const FramePointsOptions& options) {
  options.Check();
  frame.camera.Check();
  CheckArgument(
      !frame.left.empty() && frame.left.size() == frame.right.size() && frame.left.type() == frame.right.type(),
      "ComputeFramePoints: left and right images must be non-empty, "
      "same size and type");
  CheckArgument(frame.labels_left.type() == CV_8UC1 && frame.labels_left.size() == frame.left.size(),
                fmt::format("ComputeFramePoints: frame {}: left labels must be "
                            "CV_8UC1 of the image size",
                            frame.index));
  CheckArgument(frame.labels_right.empty() ||
                    (frame.labels_right.type() == CV_8UC1 && frame.labels_right.size() == frame.left.size()),
                fmt::format("ComputeFramePoints: frame {}: right labels must "
                            "be CV_8UC1 of the image size",
                            frame.index));
  CheckArgument(frame.baseline_m > 0, "ComputeFramePoints: baseline_m must be > 0");
  switch (options.contacts) {
    case ContactUse::kOff:
      return FramePointsPass(frame, options, /*contacts=*/false,
                             /*wall_stereo=*/true, nullptr);
    case ContactUse::kAlways:
      return FramePointsPass(frame, options, /*contacts=*/true,
                             /*wall_stereo=*/true, nullptr);
    case ContactUse::kWhereStereoFails:
      break;
  }
  // Both alternatives from one disparity map; the capture decides between
  // them (CapturePoints). Door and window corner, edge and dense points, and
  // vertex points, are
  // the same in both, so the contact pass computes only what differs —
  // contacts, the stereo check, boundaries at the contacts' depth — and
  // takes those from the stereo pass.
  FramePointsResult result = FramePointsPass(frame, options, /*contacts=*/false,
                                             /*wall_stereo=*/true, nullptr);
  FramePointsOptions contact_options = options;
  contact_options.use_corners = contact_options.use_edges = contact_options.use_dense = false;
  contact_options.use_vertices = false;  // The same in both: taken from the stereo pass below.
  FramePointsResult with_contacts = FramePointsPass(frame, contact_options, /*contacts=*/true,
                                                    /*wall_stereo=*/false, &result.disparity);
  FrameCues& cues = with_contacts.cues;
  for (const ClassPoint& p : result.points) {
    // Vertex points need neither the wall's stereo nor contacts: both
    // alternatives keep them.
    if (p.source == PointSource::kVertex) {
      with_contacts.points.push_back(p);
      ++cues.vertex_points;
      continue;
    }
    if (p.label == LabelClass::kWall || p.source == PointSource::kBoundary) continue;
    with_contacts.points.push_back(p);
    cues.corners_matched += p.source == PointSource::kCorner;
    cues.edge_points += p.source == PointSource::kEdge;
    cues.dense_points += p.source == PointSource::kDense;
  }
  cues.corners_found = result.cues.corners_found;
  cues.edge_candidates = result.cues.edge_candidates;
  // Each alternative's cues say what it found; both carry the check and the
  // time of both passes.
  const double seconds = result.cues.seconds + cues.seconds;
  result.contact_points = std::move(with_contacts.points);
  result.contacts = std::move(with_contacts.contacts);
  result.cues.stereo_checked = cues.stereo_checked;
  result.cues.stereo_agreed = cues.stereo_agreed;
  result.cues.seconds = seconds;
  result.contact_cues = cues;
  result.contact_cues.seconds = seconds;
  return result;
}

namespace {

// Door and window pixels of a mono frame placed on their wall's plane: a
// level camera sees a vertical wall at one depth down each column, and its
// inverse depth is affine in the column (1/z = a + b·u for any vertical
// plane). The floor contacts give 1/z per column; across an opening's run of
// columns along a row, bordered by wall on both sides, it is interpolated
// linearly between the nearest contact columns on either side (or taken
// from the column's own contact: a window above a wall base). What a stereo
// frame's dense points do for an opening's interior — without them the plan
// sees only the opening's two label edges and no opening between them.
// Every dense_stride_px-th row and column; source kDense, σ of the contacts.
void AddMonoOpeningPoints(const MonoFrame& frame, const FramePointsOptions& options, FramePointsResult* result) {
  const PinholeCamera& cam = frame.camera;
  const double h = frame.pose.position_m.z();
  if (!(h > 0.05)) return;
  const int rows = frame.labels.rows, cols = frame.labels.cols;
  const Mat3 world_from_cam = WorldFromCameraRotation(frame.pose.yaw_rad);
  const Vec3 origin = frame.pose.position_m;
  // Inverse depth per column from every floor contact of this frame.
  std::vector<double> inv_z(cols, NAN), sigma(cols, NAN);
  auto take = [&](const ClassPoint& p) {
    if (p.source != PointSource::kContact || p.frame != frame.index || std::abs(p.position_m.z()) > 1e-6) return;
    const Vec3 q = world_from_cam.transpose() * (p.position_m - origin);
    if (q.z() <= 0) return;
    const int u = static_cast<int>(std::lround(cam.fx * q.x() / q.z() + cam.cx));
    if (u < 0 || u >= cols) return;
    for (int x = u; x < std::min(cols, u + options.contact_col_step_px); ++x) {
      inv_z[x] = 1.0 / q.z();
      sigma[x] = p.sigma_m;
    }
  };
  for (const ClassPoint& p : result->points) take(p);
  for (const auto& f : result->contacts.paired_floor) take(f.point);
  for (const auto& f : result->contacts.topped_floor) take(f.point);
  const int stride = std::max(1, options.dense_stride_px);
  for (int v = 0; v < rows; v += stride) {
    const unsigned char* lab = frame.labels.ptr<unsigned char>(v);
    for (int u0 = 1; u0 < cols - 1; ++u0) {
      const unsigned char c = lab[u0];
      if ((c != kLabelDoor && c != kLabelWindow) || lab[u0 - 1] != kLabelWall) continue;
      int u1 = u0;
      while (u1 + 1 < cols && lab[u1 + 1] == c) ++u1;
      if (u1 + 1 >= cols || lab[u1 + 1] != kLabelWall) {
        u0 = u1;
        continue;
      }
      // The nearest contact columns beside the run (at most a run's width
      // away).
      const int reach = u1 - u0 + 1;
      int left = -1, right = -1;
      for (int x = u0 - 1; x >= std::max(0, u0 - reach) && left < 0; --x) left = std::isfinite(inv_z[x]) ? x : -1;
      for (int x = u1 + 1; x <= std::min(cols - 1, u1 + reach) && right < 0; ++x)
        right = std::isfinite(inv_z[x]) ? x : -1;
      for (int u = u0; u <= u1; u += stride) {
        double iz = inv_z[u], s = sigma[u];
        if (!std::isfinite(iz)) {
          if (left < 0 || right < 0) continue;
          const double w = double(u - left) / (right - left);
          iz = (1 - w) * inv_z[left] + w * inv_z[right];
          s = std::max(sigma[left], sigma[right]);
        }
        if (!(iz > 0)) continue;
        const double z = 1.0 / iz;
        if (z < options.min_depth_m || z > options.max_depth_m) continue;
        const Vec3 p = origin + world_from_cam * UnprojectToCamera(cam, Vec2(u, v), z);
        result->points.push_back({static_cast<LabelClass>(c), p, s, PointSource::kDense, frame.index});
        ++result->cues.dense_points;
      }
      u0 = u1;
    }
  }
}

}  // namespace

FramePointsResult ComputeMonoFramePoints(const MonoFrame& frame, const FramePointsOptions& options) {
  options.Check();
  frame.camera.Check();
  CheckArgument(
      !frame.image.empty() && frame.image.cols == frame.camera.width_px && frame.image.rows == frame.camera.height_px,
      fmt::format("ComputeMonoFramePoints: frame {}: the image must "
                  "be non-empty and of the camera's size",
                  frame.index));
  CheckArgument(frame.labels.type() == CV_8UC1 && frame.labels.size() == frame.image.size(),
                fmt::format("ComputeMonoFramePoints: frame {}: labels must be "
                            "CV_8UC1 of the image size",
                            frame.index));
  // The stereo pass with a nominal 1 m "baseline" whose disparities are all
  // invalid: it then adds contacts and boundaries at the contacts' depth
  // (disparity and depth convert through the same f·B both ways, so B
  // cancels) and nothing that needs a match. The rig centre is moved by
  // half that baseline so the left camera sits at the frame's position.
  constexpr double kNominalBaselineM = 1.0;
  const double yaw = frame.pose.yaw_rad;
  StereoFrame stereo{
      .left = frame.image,
      .right = frame.image,
      .labels_left = frame.labels,
      .camera = frame.camera,
      .baseline_m = kNominalBaselineM,
      .pose = {frame.pose.position_m + 0.5 * kNominalBaselineM * Vec3(std::cos(yaw), std::sin(yaw), 0), yaw},
      .index = frame.index};
  DisparityResult none;
  none.disparity_px = cv::Mat(frame.labels.size(), CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  none.valid = cv::Mat::zeros(frame.labels.size(), CV_8U);
  none.num_disparities_px = 16;
  FramePointsOptions mono = options;
  mono.use_corners = mono.use_edges = mono.use_dense = mono.use_vertices = false;
  FramePointsResult result = FramePointsPass(stereo, mono, /*contacts=*/true,
                                             /*wall_stereo=*/false, &none);
  if (options.use_dense) AddMonoOpeningPoints(frame, options, &result);
  return result;
}

}  // namespace asbuilt
