#include "asbuilt/stereo/wall_vertices.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "asbuilt/geometry/label_class.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// Offset of a parabola's vertex through (−1, a), (0, b), (1, c), in [−0.5, 0.5].
double ParabolaPeak(double a, double b, double c) {
  const double den = a - 2 * b + c;
  if (std::abs(den) < 1e-12) return 0;
  return std::clamp(0.5 * (a - c) / den, -0.5, 0.5);
}

// Zero-mean normalised cross-correlation of two equally long profiles.
double Ncc(const double* a, const double* b, int n) {
  double ma = 0, mb = 0;
  for (int i = 0; i < n; ++i) ma += a[i], mb += b[i];
  ma /= n, mb /= n;
  double ab = 0, aa = 0, bb = 0;
  for (int i = 0; i < n; ++i) {
    ab += (a[i] - ma) * (b[i] - mb);
    aa += (a[i] - ma) * (a[i] - ma);
    bb += (b[i] - mb) * (b[i] - mb);
  }
  return aa > 1e-12 && bb > 1e-12 ? ab / std::sqrt(aa * bb) : 0;
}

}  // namespace

void WallVertexOptions::Check() const {
  CheckArgument(side_px >= 1, "wall vertices: side_px must be >= 1");
  CheckArgument(min_rows >= 2, "wall vertices: min_rows must be >= 2");
  CheckArgument(min_contrast > 0, "wall vertices: min_contrast must be > 0");
  CheckArgument(block_rows >= 1, "wall vertices: block_rows must be >= 1");
  CheckArgument(min_sign_agreement > 0.5 && min_sign_agreement <= 1,
                "wall vertices: min_sign_agreement must be in (0.5, 1]");
  CheckArgument(profile_half_width_px >= 2, "wall vertices: profile_half_width_px must be >= 2");
  CheckArgument(min_ncc > 0 && min_ncc <= 1, "wall vertices: min_ncc must be in (0, 1]");
  CheckArgument(ambiguity_margin >= 0, "wall vertices: ambiguity_margin must be >= 0");
}

std::vector<WallVertex> FindWallVertices(const cv::Mat& gray_left, const cv::Mat& gray_right,
                                         const cv::Mat& labels_left, double min_disparity_px, double max_disparity_px,
                                         const WallVertexOptions& options) {
  options.Check();
  CheckArgument(gray_left.type() == CV_32F && gray_right.type() == CV_32F && labels_left.type() == CV_8UC1 &&
                    gray_left.size() == gray_right.size() && gray_left.size() == labels_left.size(),
                "FindWallVertices: gray images must be CV_32F and labels CV_8UC1, all of one size");
  const int rows = gray_left.rows, cols = gray_left.cols, s = options.side_px, w = options.profile_half_width_px;
  std::vector<WallVertex> found;
  if (cols < 2 * (s + w + 2)) return found;

  // Wall on both sides: a horizontal run of 2s+1 wall labels centred on u.
  cv::Mat wall;
  cv::Mat(labels_left == kLabelWall).convertTo(wall, CV_32F, 1.0 / 255);
  cv::Mat run;
  cv::blur(wall, run, cv::Size(2 * s + 1, 1), cv::Point(-1, -1), cv::BORDER_CONSTANT);
  auto eligible = [&](int v, int u) { return run.at<float>(v, u) > 1 - 1e-4f; };
  auto gradient = [](const cv::Mat& g, int v, int u) { return 0.5 * (g.at<float>(v, u + 1) - g.at<float>(v, u - 1)); };

  // Mean gradient per column over its eligible rows.
  std::vector<double> mean(cols, 0.0);
  std::vector<int> count(cols, 0);
  for (int v = 0; v < rows; ++v) {
    for (int u = s + 1; u < cols - s - 1; ++u) {
      if (!eligible(v, u)) continue;
      mean[u] += gradient(gray_left, v, u);
      ++count[u];
    }
  }
  for (int u = 0; u < cols; ++u) mean[u] = count[u] > 0 ? mean[u] / count[u] : 0.0;

  std::vector<int> col_rows;
  std::vector<double> left_profile(2 * w + 1), right_profile;
  for (int u = s + w + 2; u < cols - s - w - 2; ++u) {
    const double g = mean[u], a = std::abs(g);
    if (count[u] < options.min_rows || a < options.min_contrast) continue;
    if (a < std::abs(mean[u - 1]) || a <= std::abs(mean[u + 1])) continue;
    // A peak, not a slope: twice the mean gradient 4…w px to either side.
    double around = 0;
    int n_around = 0;
    for (int k = 4; k <= w; ++k) around += std::abs(mean[u - k]) + std::abs(mean[u + k]), n_around += 2;
    if (a < 2 * around / n_around) continue;

    col_rows.clear();
    for (int v = 0; v < rows; ++v) {
      if (eligible(v, u)) col_rows.push_back(v);
    }
    // Sign test over blocks of rows (the step's gradient spreads over u ± 1).
    int blocks = 0, agree = 0;
    for (size_t b = 0; b + options.block_rows <= col_rows.size(); b += options.block_rows) {
      double sum = 0;
      for (int k = 0; k < options.block_rows; ++k) {
        const int v = col_rows[b + k];
        for (int x = u - 1; x <= u + 1; ++x) sum += gradient(gray_left, v, x);
      }
      ++blocks;
      agree += (sum > 0) == (g > 0);
    }
    if (blocks < 3 || agree < options.min_sign_agreement * blocks) continue;

    // Mean intensity profiles over those rows: the left one around u, the
    // right one over the disparity range.
    const int d_lo = std::max(0, static_cast<int>(std::ceil(min_disparity_px)));
    const int d_hi = std::min(static_cast<int>(std::floor(max_disparity_px)), u - w - 2);
    if (d_hi < d_lo) continue;
    const int x0 = u - d_hi - w - 1;  // Right profile covers [x0, x0 + n).
    const int n = (d_hi - d_lo) + 2 * w + 3;
    right_profile.assign(n, 0.0);
    std::fill(left_profile.begin(), left_profile.end(), 0.0);
    for (int v : col_rows) {
      const float* l = gray_left.ptr<float>(v);
      const float* r = gray_right.ptr<float>(v);
      for (int k = -w; k <= w; ++k) left_profile[k + w] += l[u + k];
      for (int i = 0; i < n; ++i) right_profile[i] += r[x0 + i];
    }
    std::vector<double> score(d_hi - d_lo + 1);
    for (int d = d_lo; d <= d_hi; ++d) {
      score[d - d_lo] = Ncc(left_profile.data(), right_profile.data() + (u - d - w - x0), 2 * w + 1);
    }
    const int best = static_cast<int>(std::max_element(score.begin(), score.end()) - score.begin());
    if (score[best] < options.min_ncc) continue;
    double rival = -1;
    for (int i = 0; i < static_cast<int>(score.size()); ++i) {
      if (std::abs(i - best) < 2) continue;
      const bool local =
          (i == 0 || score[i] >= score[i - 1]) && (i + 1 == static_cast<int>(score.size()) || score[i] >= score[i + 1]);
      if (local) rival = std::max(rival, score[i]);
    }
    if (rival > score[best] - options.ambiguity_margin) continue;

    // Sub-pixel: the gradient peaks in both views.
    auto right_gradient = [&](int x) {
      double sum = 0;
      for (int v : col_rows) sum += gradient(gray_right, v, x);
      return sum / static_cast<double>(col_rows.size());
    };
    const int xr0 = u - (best + d_lo);
    int xr = xr0;
    double gr = right_gradient(xr0);
    for (int x = xr0 - 1; x <= xr0 + 1; x += 2) {
      const double gx = right_gradient(x);
      if ((gx > 0) == (g > 0) && std::abs(gx) > std::abs(gr)) xr = x, gr = gx;
    }
    if ((gr > 0) != (g > 0) || std::abs(gr) < 0.5 * a) continue;
    const double ul = u + ParabolaPeak(std::abs(mean[u - 1]), a, std::abs(mean[u + 1]));
    const double ur =
        xr + ParabolaPeak(std::abs(right_gradient(xr - 1)), std::abs(gr), std::abs(right_gradient(xr + 1)));
    const double disparity = ul - ur;
    if (disparity < min_disparity_px || disparity > max_disparity_px || disparity <= 0) continue;
    found.push_back({.u_left_px = ul,
                     .u_right_px = ur,
                     .disparity_px = disparity,
                     .v_mid_px = 0.5 * (col_rows.front() + col_rows.back()),
                     .rows = static_cast<int>(col_rows.size()),
                     .contrast = g,
                     .ncc = score[best]});
  }
  return found;
}

}  // namespace asbuilt
