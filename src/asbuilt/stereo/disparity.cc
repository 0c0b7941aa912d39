#include "asbuilt/stereo/disparity.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <vector>

#include <fmt/format.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/disparity_filter.hpp>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// The one place the OpenCV matchers are configured (STYLE.md 5).
cv::Ptr<cv::StereoMatcher> MakeLeftMatcher(const DisparityOptions& o, int min_disp, int num_disp, int channels) {
  if (o.matcher == DisparityMatcher::kBm) {
    auto bm = cv::StereoBM::create(num_disp, o.block_size_px);
    bm->setMinDisparity(min_disp);
    bm->setUniquenessRatio(o.uniqueness_percent);
    bm->setSpeckleWindowSize(o.speckle_window_px);
    bm->setSpeckleRange(o.speckle_range_px);
    bm->setPreFilterCap(31);
    bm->setTextureThreshold(10);
    bm->setDisp12MaxDiff(-1);
    return bm;
  }
  const int area = channels * o.block_size_px * o.block_size_px;
  return cv::StereoSGBM::create(min_disp, num_disp, o.block_size_px, o.p1_per_block_px * area, o.p2_per_block_px * area,
                                /*disp12MaxDiff=*/-1,
                                /*preFilterCap=*/63, o.uniqueness_percent, o.speckle_window_px, o.speckle_range_px,
                                o.full_dp ? cv::StereoSGBM::MODE_HH : cv::StereoSGBM::MODE_SGBM_3WAY);
}

// OpenCV's SGBM (every mode) places the cost parabola's minimum with
// integer arithmetic, d·16 + (16·(S[d−1] − S[d+1]) + den)/(2·den), and C's
// division truncates toward zero: where the parabola's offset δ from the best
// whole disparity is below −1/32 px the result is rounded up, 1/16 px too
// high, instead of to the nearest sixteenth. This maps a matcher value s (in
// sixteenths) back to the nearest-sixteenth estimate: a fraction of 9–15
// sixteenths came from a negative δ (−1/16); a whole value mixes δ in
// [−1/32, 1/32) (exact) with δ in (−3/32, −1/32) (one too high), so it takes
// their mid-point (−1/32), unbiased where δ's density is locally flat; 1–8
// sixteenths are exact. The speckle and 3×3 median filters after the fit
// keep values on this lattice.
float UnroundSgbm(short s) {
  const int fraction = ((s % 16) + 16) % 16;
  if (fraction >= 9) return (s - 1) / 16.0f;
  if (fraction == 0) return (s - 0.5f) / 16.0f;
  return s / 16.0f;
}

// `unround`: the values are SGBM's raw output (UnroundSgbm).
cv::Mat ToFloatDisparity(const cv::Mat& fixed16, int min_disp, bool unround) {
  cv::Mat out(fixed16.size(), CV_32F);
  const int invalid = (min_disp - 1) * 16;
  for (int y = 0; y < fixed16.rows; ++y) {
    const short* s = fixed16.ptr<short>(y);
    float* d = out.ptr<float>(y);
    for (int x = 0; x < fixed16.cols; ++x) {
      d[x] = s[x] <= invalid ? kNaN : (unround ? UnroundSgbm(s[x]) : s[x] / 16.0f);
    }
  }
  return out;
}

// Percentile of the finite values of a float map; NaN if none.
double Percentile(const cv::Mat& m, double q) {
  std::vector<float> v;
  v.reserve(m.total());
  for (int y = 0; y < m.rows; ++y) {
    const float* p = m.ptr<float>(y);
    for (int x = 0; x < m.cols; ++x) {
      if (std::isfinite(p[x])) v.push_back(p[x]);
    }
  }
  if (v.empty()) return NAN;
  auto k = static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) * (v.size() - 1));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

struct RawPair {
  cv::Mat left16, right16;
  cv::Ptr<cv::StereoMatcher> matcher;
};

// Each run of holes on a row takes the smaller of the valid disparities that
// bound it: holes are mostly occlusions, and occluded pixels belong to the
// farther surface.
void FillHolesFromBackground(cv::Mat& disp) {
  for (int y = 0; y < disp.rows; ++y) {
    float* r = disp.ptr<float>(y);
    int x = 0;
    while (x < disp.cols) {
      if (std::isfinite(r[x])) {
        ++x;
        continue;
      }
      const int start = x;
      while (x < disp.cols && !std::isfinite(r[x])) ++x;
      const float a = start > 0 ? r[start - 1] : kNaN, b = x < disp.cols ? r[x] : kNaN;
      const float v = std::isfinite(a) && std::isfinite(b) ? std::min(a, b) : (std::isfinite(a) ? a : b);
      for (int i = start; i < x; ++i) r[i] = v;
    }
  }
  // Rows with no valid pixel at all copy the nearest filled row.
  std::vector<int> filled;
  for (int y = 0; y < disp.rows; ++y) {
    if (disp.cols > 0 && std::isfinite(disp.at<float>(y, 0))) filled.push_back(y);
  }
  if (filled.empty()) return;
  for (int y = 0; y < disp.rows; ++y) {
    if (std::isfinite(disp.at<float>(y, 0))) continue;
    auto it = std::lower_bound(filled.begin(), filled.end(), y);
    int src = it == filled.end() ? filled.back() : *it;
    if (it != filled.begin() && (it == filled.end() || y - *(it - 1) < *it - y)) src = *(it - 1);
    disp.row(src).copyTo(disp.row(y));
  }
}

RawPair MatchBoth(const cv::Mat& left, const cv::Mat& right, const DisparityOptions& o, int min_disp, int num_disp,
                  bool need_right) {
  cv::Mat l = left, r = right;
  if (o.matcher == DisparityMatcher::kBm && l.channels() == 3) {
    cv::cvtColor(left, l, cv::COLOR_BGR2GRAY);
    cv::cvtColor(right, r, cv::COLOR_BGR2GRAY);
  }
  auto matcher = MakeLeftMatcher(o, min_disp, num_disp, l.channels());
  RawPair raw;
  raw.matcher = matcher;
  matcher->compute(l, r, raw.left16);
  if (need_right) {
    auto right_matcher = cv::ximgproc::createRightMatcher(matcher);
    right_matcher->compute(r, l, raw.right16);
  }
  return raw;
}

}  // namespace

void DisparityOptions::Check() const {
  CheckArgument(
      num_disparities_px > 0 && num_disparities_px % 16 == 0,
      fmt::format("DisparityOptions.num_disparities_px = {}, must be a positive multiple of 16", num_disparities_px));
  CheckArgument(block_size_px >= 1 && block_size_px % 2 == 1 && block_size_px <= 255,
                fmt::format("DisparityOptions.block_size_px = {}, must be odd in [1, 255]", block_size_px));
  CheckArgument(matcher != DisparityMatcher::kBm || block_size_px >= 5,
                fmt::format("DisparityOptions.block_size_px = {}, must be >= 5 for BM", block_size_px));
  CheckArgument(p1_per_block_px > 0 && p2_per_block_px > p1_per_block_px,
                fmt::format("DisparityOptions.p2_per_block_px = {} must exceed p1_per_block_px = {} > 0",
                            p2_per_block_px, p1_per_block_px));
  CheckArgument(uniqueness_percent >= 0 && uniqueness_percent <= 100,
                fmt::format("DisparityOptions.uniqueness_percent = {}, must be in [0, 100]", uniqueness_percent));
  CheckArgument(speckle_window_px >= 0,
                fmt::format("DisparityOptions.speckle_window_px = {}, must be >= 0", speckle_window_px));
  CheckArgument(speckle_range_px >= 0,
                fmt::format("DisparityOptions.speckle_range_px = {}, must be >= 0", speckle_range_px));
  CheckArgument(max_left_right_diff_px >= 0,
                fmt::format("DisparityOptions.max_left_right_diff_px = {}, must be >= 0", max_left_right_diff_px));
  CheckArgument(median_px == 0 || median_px == 3 || median_px == 5,
                fmt::format("DisparityOptions.median_px = {}, must be 0, 3 or 5", median_px));
  CheckArgument(wls_lambda > 0, fmt::format("DisparityOptions.wls_lambda = {}, must be > 0", wls_lambda));
  CheckArgument(wls_sigma > 0, fmt::format("DisparityOptions.wls_sigma = {}, must be > 0", wls_sigma));
}

std::string DisparityOptions::ToString() const {
  return fmt::format("{}{} range [{}, {}) block {} LR {} WLS {} fill {} multi-scale {}",
                     matcher == DisparityMatcher::kSgbm ? (full_dp ? "SGBM-HH" : "SGBM") : "BM",
                     matcher == DisparityMatcher::kSgbm && !unround_subpixel ? " (OpenCV rounding)" : "",
                     min_disparity_px, min_disparity_px + num_disparities_px, block_size_px,
                     left_right_check ? fmt::format("±{:g}px", max_left_right_diff_px) : "off",
                     wls_filter ? "on" : "off", fill_holes ? "on" : "off", multi_scale ? "on" : "off");
}

std::string DisparityResult::ToString() const {
  return fmt::format("disparity {}x{}, range [{}, {}), {:.1f}% valid, {:.0f} ms", disparity_px.cols, disparity_px.rows,
                     min_disparity_px, min_disparity_px + num_disparities_px, 100.0 * valid_fraction, 1000.0 * seconds);
}

DisparityResult ComputeDisparity(const cv::Mat& left, const cv::Mat& right, const DisparityOptions& options) {
  options.Check();
  CheckArgument(!left.empty() && !right.empty(), "ComputeDisparity: empty image");
  CheckArgument(left.size() == right.size() && left.type() == right.type(),
                fmt::format("ComputeDisparity: left {}x{} and right {}x{} images differ in size or type", left.cols,
                            left.rows, right.cols, right.rows));
  CheckArgument(left.depth() == CV_8U && (left.channels() == 1 || left.channels() == 3),
                "ComputeDisparity: images must be 8-bit gray or BGR");
  const auto start = std::chrono::steady_clock::now();
  DisparityResult result;
  int min_disp = options.min_disparity_px;
  int num_disp = options.num_disparities_px;

  // Coarse pass: half-size images, half the range; narrow the fine range.
  if (options.multi_scale && num_disp >= 32) {
    cv::Mat l2, r2;
    cv::pyrDown(left, l2);
    cv::pyrDown(right, r2);
    DisparityOptions coarse = options;
    coarse.multi_scale = false;
    coarse.wls_filter = false;
    coarse.left_right_check = true;
    coarse.min_disparity_px = static_cast<int>(std::floor(min_disp / 2.0));
    coarse.num_disparities_px = std::max(16, (num_disp / 2 + 15) / 16 * 16);
    coarse.block_size_px = std::max(options.matcher == DisparityMatcher::kBm ? 5 : 3, (options.block_size_px / 2) | 1);
    DisparityResult c = ComputeDisparity(l2, r2, coarse);
    const double lo = Percentile(c.disparity_px, 0.01), hi = Percentile(c.disparity_px, 0.99);
    if (std::isfinite(lo) && std::isfinite(hi)) {
      int new_min = std::max(min_disp, static_cast<int>(std::floor(2 * lo)) - 16);
      int new_max = std::min(min_disp + num_disp, static_cast<int>(std::ceil(2 * hi)) + 16);
      int new_num = std::max(16, (new_max - new_min + 15) / 16 * 16);
      if (new_num < num_disp) {
        min_disp = new_min;
        num_disp = new_num;
      }
    }
  }
  result.min_disparity_px = min_disp;
  result.num_disparities_px = num_disp;

  const bool need_right = options.left_right_check || options.wls_filter;
  // Left images for WLS guidance must match the matcher's input channels.
  RawPair raw = MatchBoth(left, right, options, min_disp, num_disp, need_right);
  cv::Mat disp =
      ToFloatDisparity(raw.left16, min_disp, options.unround_subpixel && options.matcher == DisparityMatcher::kSgbm);

  // Left–right consistency: the right view's disparity (negated by the right
  // matcher) at x − d must agree.
  if (options.left_right_check) {
    cv::Mat right_disp(raw.right16.size(), CV_32F);
    for (int y = 0; y < raw.right16.rows; ++y) {
      const short* s = raw.right16.ptr<short>(y);
      float* d = right_disp.ptr<float>(y);
      for (int x = 0; x < raw.right16.cols; ++x) {
        // Right matcher disparities are negative; invalid ones sit below −max.
        const float v = -s[x] / 16.0f;
        d[x] = (v < min_disp || v >= min_disp + num_disp) ? kNaN : v;
      }
    }
    for (int y = 0; y < disp.rows; ++y) {
      float* d = disp.ptr<float>(y);
      const float* r = right_disp.ptr<float>(y);
      for (int x = 0; x < disp.cols; ++x) {
        if (!std::isfinite(d[x])) continue;
        const int xr = static_cast<int>(std::lround(x - d[x]));
        if (xr < 0 || xr >= disp.cols || !std::isfinite(r[xr]) ||
            std::abs(r[xr] - d[x]) > options.max_left_right_diff_px) {
          d[x] = kNaN;
        }
      }
    }
  }
  result.valid = cv::Mat(disp.size(), CV_8U);
  int n_valid = 0;
  for (int y = 0; y < disp.rows; ++y) {
    const float* d = disp.ptr<float>(y);
    unsigned char* m = result.valid.ptr<unsigned char>(y);
    for (int x = 0; x < disp.cols; ++x) {
      m[x] = std::isfinite(d[x]) ? 255 : 0;
      n_valid += m[x] != 0;
    }
  }
  result.valid_fraction = static_cast<double>(n_valid) / std::max<std::size_t>(1, disp.total());

  if (options.wls_filter) {
    // ximgproc's confidence-weighted WLS with both views (its own LR test).
    auto wls = cv::ximgproc::createDisparityWLSFilter(raw.matcher);
    wls->setLambda(options.wls_lambda);
    wls->setSigmaColor(options.wls_sigma);
    cv::Mat filtered;
    wls->filter(raw.left16, left, filtered, raw.right16);
    disp = ToFloatDisparity(filtered, min_disp, /*unround=*/false);
  }
  if (options.fill_holes) {
    FillHolesFromBackground(disp);
    if (options.median_px > 0 && cv::countNonZero(disp == disp) == static_cast<int>(disp.total())) {
      cv::Mat smoothed;
      cv::medianBlur(disp, smoothed, options.median_px);
      disp = smoothed;
    }
  }
  result.disparity_px = disp;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

namespace {

// Keys' cubic convolution (a = −0.5) at fraction t between row[i] and
// row[i + 1]: far less phase error at sub-pixel shifts than linear
// interpolation, whose error draws a patch match towards half pixels.
double CubicAt(const float* row, int i, double t) {
  const double p0 = row[i - 1], p1 = row[i], p2 = row[i + 1], p3 = row[i + 2];
  return p1 + 0.5 * t * (p2 - p0 + t * (2 * p0 - 5 * p1 + 4 * p2 - p3 + t * (3 * (p1 - p2) + p3 - p0)));
}

// The (2r+1)² patch of `image` centred on (u, v), cubic along the row, as
// zero mean and unit variance, and its derivative along u (central
// differences, in the same units). False when it leaves the image or is flat.
bool NormalisedPatch(const cv::Mat& image, double u, int v, int r, std::vector<double>& values,
                     std::vector<double>& along) {
  const int side = 2 * r + 1;
  const double x0 = u - r;
  const int i0 = static_cast<int>(std::floor(x0));
  const double t = x0 - i0;
  if (v - r < 0 || v + r >= image.rows || i0 - 2 < 0 || i0 + side + 2 >= image.cols) return false;
  values.resize(side * side);
  along.resize(side * side);
  double mean = 0, var = 0;
  for (int y = 0, k = 0; y < side; ++y) {
    const float* row = image.ptr<float>(v - r + y);
    for (int x = 0; x < side; ++x, ++k) {
      const int i = i0 + x;
      values[k] = CubicAt(row, i, t);
      along[k] = 0.5 * (CubicAt(row, i + 1, t) - CubicAt(row, i - 1, t));
      mean += values[k];
    }
  }
  mean /= values.size();
  for (double value : values) var += (value - mean) * (value - mean);
  var /= values.size();
  if (var < 0.25) return false;  // Below half a gray level: no texture.
  const double scale = 1.0 / std::sqrt(var);
  for (std::size_t k = 0; k < values.size(); ++k) {
    values[k] = (values[k] - mean) * scale;
    along[k] *= scale;
  }
  return true;
}

}  // namespace

std::optional<SubpixelDisparity> RefineDisparityAt(const cv::Mat& left_gray, const cv::Mat& right_gray, int u, int v,
                                                   double d0, int radius_px, int iterations) {
  CheckArgument(left_gray.type() == CV_32FC1 && right_gray.type() == CV_32FC1 && left_gray.size() == right_gray.size(),
                "RefineDisparityAt: images must be CV_32FC1 of one size");
  if (radius_px < 1 || !std::isfinite(d0)) return std::nullopt;
  // Both views move by half the sub-pixel part e of d = whole + e, the left
  // patch to u + e/2 and the right to u − whole − e/2: both are then blurred
  // alike by the interpolation (fractions e/2 and 1 − e/2), which otherwise
  // draws a one-sided estimate towards half pixels.
  const double whole = std::round(d0);
  double e = d0 - whole, residual = 0, jj = 0;
  std::vector<double> l, lx, r, rx;
  for (int it = 0; it < iterations; ++it) {
    if (!NormalisedPatch(left_gray, u + 0.5 * e, v, radius_px, l, lx) ||
        !NormalisedPatch(right_gray, u - whole - 0.5 * e, v, radius_px, r, rx)) {
      return std::nullopt;
    }
    double num = 0;
    residual = jj = 0;
    for (std::size_t k = 0; k < l.size(); ++k) {
      const double diff = l[k] - r[k], g = 0.5 * (lx[k] + rx[k]);  // ∂(l − r)/∂e.
      num += diff * g;
      jj += g * g;
      residual += diff * diff;
    }
    if (jj <= 1e-9) return std::nullopt;
    const double step = std::clamp(-num / jj, -0.5, 0.5);
    e += step;
    if (std::abs(whole + e - d0) > 1.0) return std::nullopt;
    if (std::abs(step) < 1e-3) break;
  }
  return SubpixelDisparity{
      .disparity_px = whole + e, .left_u_px = u + 0.5 * e, .sigma_px = std::sqrt(residual / (l.size() - 1) / jj)};
}

cv::Mat ColorizeDisparity(const cv::Mat& disparity_px, double lo, double hi) {
  CV_Assert(disparity_px.type() == CV_32F);
  if (!std::isfinite(lo)) lo = Percentile(disparity_px, 0.01);
  if (!std::isfinite(hi)) hi = Percentile(disparity_px, 0.99);
  if (!std::isfinite(lo) || !std::isfinite(hi) || hi <= lo) {
    lo = 0;
    hi = 1;
  }
  cv::Mat gray(disparity_px.size(), CV_8U), mask(disparity_px.size(), CV_8U);
  for (int y = 0; y < gray.rows; ++y) {
    const float* d = disparity_px.ptr<float>(y);
    for (int x = 0; x < gray.cols; ++x) {
      const bool ok = std::isfinite(d[x]);
      mask.at<unsigned char>(y, x) = ok ? 0 : 255;
      gray.at<unsigned char>(y, x) = ok ? cv::saturate_cast<unsigned char>(255.0 * (d[x] - lo) / (hi - lo)) : 0;
    }
  }
  cv::Mat color;
  cv::applyColorMap(gray, color, cv::COLORMAP_TURBO);
  color.setTo(cv::Scalar(0, 0, 0), mask);
  return color;
}

void WritePfm(const cv::Mat& image_32f, const std::filesystem::path& path) {
  CheckArgument(image_32f.type() == CV_32F, "WritePfm: image must be CV_32F, one channel");
  std::string out = fmt::format("Pf\n{} {}\n-1\n", image_32f.cols, image_32f.rows);
  const std::size_t header = out.size();
  out.resize(header + image_32f.total() * sizeof(float));
  char* dst = out.data() + header;
  for (int y = image_32f.rows - 1; y >= 0; --y) {
    const float* row = image_32f.ptr<float>(y);
    for (int x = 0; x < image_32f.cols; ++x) {
      float v = std::isfinite(row[x]) ? row[x] : std::numeric_limits<float>::infinity();
      std::memcpy(dst, &v, sizeof(float));
      dst += sizeof(float);
    }
  }
  WriteFileAtomic(path, out);
}

cv::Mat ReadPfm(const std::filesystem::path& path) {
  const std::string data = ReadFile(path);
  const std::string name = path.string();
  // Header: "Pf" <ws> width <ws> height <ws> scale <one ws char>.
  std::size_t pos = 0;
  auto token = [&]() {
    while (pos < data.size() && std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
    std::size_t start = pos;
    while (pos < data.size() && !std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
    return data.substr(start, pos - start);
  };
  const std::string magic = token();
  if (magic != "Pf")
    throw InputError(name, "header", fmt::format("expected \"Pf\" (one-channel PFM), got \"{}\"", magic));
  int width = 0, height = 0;
  double scale = 0;
  try {
    width = std::stoi(token());
    height = std::stoi(token());
    scale = std::stod(token());
  } catch (const std::exception&) {
    throw InputError(name, "header", "bad width/height/scale");
  }
  ++pos;
  if (width <= 0 || height <= 0 || scale == 0) throw InputError(name, "header", "bad width/height/scale");
  const std::size_t need = static_cast<std::size_t>(width) * height * sizeof(float);
  if (data.size() < pos + need) {
    throw InputError(name, "data", fmt::format("truncated: need {} bytes of pixels, have {}", need, data.size() - pos));
  }
  if (scale > 0) throw InputError(name, "header", "big-endian PFM is not supported");
  cv::Mat out(height, width, CV_32F);
  const char* src = data.data() + pos;
  for (int y = height - 1; y >= 0; --y) {
    float* row = out.ptr<float>(y);
    for (int x = 0; x < width; ++x) {
      float v;
      std::memcpy(&v, src, sizeof(float));
      src += sizeof(float);
      row[x] = std::isfinite(v) ? v : kNaN;
    }
  }
  return out;
}

}  // namespace asbuilt
