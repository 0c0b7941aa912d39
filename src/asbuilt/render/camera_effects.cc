#include "asbuilt/render/camera_effects.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <fmt/format.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/util/hash.h"

namespace asbuilt {
namespace {

// Filmic tone curve (Narkowicz's ACES fit), then the sRGB transfer function.
inline float ToneMap(float x) {
  x = std::max(x, 0.0f);
  float y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
  return std::clamp(y, 0.0f, 1.0f);
}

inline float LinearToSrgb(float x) { return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f; }

// A standard normal value from a hashed key (Box–Muller).
inline float HashGaussian(std::uint64_t key) {
  std::uint64_t h = SplitMix64(key);
  float u1 = ((h >> 40) + 0.5f) * (1.0f / 16777216.0f);
  float u2 = (((h >> 16) & 0xFFFFFF) + 0.5f) * (1.0f / 16777216.0f);
  return std::sqrt(-2.0f * std::log(u1)) * std::cos(6.2831853f * u2);
}

}  // namespace

std::string ViewEffects::ToString() const {
  return fmt::format(
             "ViewEffects(exposure={:.3f} white_balance=[{:.3f}, {:.3f}, {:.3f}] vignetting={:.3f} "
             "blur_sigma_px={:.3f} noise_sigma={:.4f} jpeg_quality={})",
             exposure, white_balance.x(), white_balance.y(), white_balance.z(), vignetting, blur_sigma_px, noise_sigma,
             jpeg_quality) +
         (chromatic_aberration_px == 0 && sharpen == 0 && saturation == 1
              ? std::string()
              : fmt::format(" phone(chromatic_aberration_px={:.3f} sharpen={:.3f} saturation={:.3f})",
                            chromatic_aberration_px, sharpen, saturation));
}

ViewEffects RandomViewEffects(double strength, std::uint64_t seed, bool phone) {
  ViewEffects e;
  if (strength <= 0) return e;
  std::mt19937_64 rng(SplitMix64(seed ^ 0xEFFEC75ULL));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  e.exposure = std::exp(strength * 0.45 * u(rng));
  double temp = strength * 0.12 * u(rng);  // Warm/cool.
  double tint = strength * 0.04 * u(rng);  // Green/magenta.
  e.white_balance = Vec3(1.0 + temp, 1.0 + tint, 1.0 - temp);
  e.vignetting = strength * 0.35 * (0.5 + 0.5 * u(rng));
  e.blur_sigma_px = strength * 0.6 * (0.5 + 0.5 * u(rng));
  e.noise_sigma = strength * 0.02 * (0.5 + 0.5 * u(rng));
  double q = 0.5 + 0.5 * u(rng);
  e.jpeg_quality = q < 1.0 - strength * 0.8 ? 0 : 60 + static_cast<int>(35 * (0.5 + 0.5 * u(rng)));
  if (!phone) return e;
  // A phone's processing: drawn after the others, which stay as they were.
  auto u01 = [&] { return 0.5 + 0.5 * u(rng); };
  e.exposure *= std::exp(strength * 0.35 * u(rng));
  e.noise_sigma *= 1.0 + 1.5 * u01();
  if (u01() < 0.85 * strength) e.jpeg_quality = 35 + static_cast<int>(60 * u01());
  e.chromatic_aberration_px = strength * 1.2 * u01();
  e.sharpen = strength * 0.8 * u01();
  const bool more_colour = u(rng) > 0;
  e.saturation = 1.0 + strength * (more_colour ? 0.3 : -0.25) * u01();
  return e;
}

double AutoExposure(const Image& linear_rgb, double key) {
  const cv::Mat linear = AsMat(linear_rgb);
  double sum = 0.0;
  std::size_t n = 0;
  for (int y = 0; y < linear.rows; y += 2) {
    const auto* row = linear.ptr<cv::Vec3f>(y);
    for (int x = 0; x < linear.cols; x += 2) {
      const cv::Vec3f& c = row[x];
      double lum = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
      sum += std::log(1e-4 + lum);
      ++n;
    }
  }
  if (n == 0) return 1.0;
  double log_avg = std::exp(sum / n);
  return key / std::max(log_avg, 1e-4);
}

Image DevelopImage(const Image& linear_rgb, const ViewEffects& effects, std::uint64_t noise_seed) {
  const cv::Mat linear = AsMat(linear_rgb);
  const int w = linear.cols, h = linear.rows;
  const float cx = 0.5f * (w - 1), cy = 0.5f * (h - 1);
  const float r2max = cx * cx + cy * cy;
  cv::Mat srgb(h, w, CV_32FC3);
  const Eigen::Vector3f gains = (effects.white_balance * effects.exposure).cast<float>();
  for (int y = 0; y < h; ++y) {
    const auto* in = linear.ptr<cv::Vec3f>(y);
    auto* out = srgb.ptr<cv::Vec3f>(y);
    for (int x = 0; x < w; ++x) {
      float r2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / std::max(r2max, 1.0f);
      float vig = 1.0f - static_cast<float>(effects.vignetting) * r2;
      for (int c = 0; c < 3; ++c) {
        // Output in BGR order for OpenCV.
        out[x][2 - c] = LinearToSrgb(ToneMap(in[x][c] * gains[c] * vig));
      }
    }
  }
  if (effects.saturation != 1.0) {
    const float k = static_cast<float>(effects.saturation);
    for (int y = 0; y < h; ++y) {
      auto* row = srgb.ptr<cv::Vec3f>(y);
      for (int x = 0; x < w; ++x) {
        float grey = 0.0722f * row[x][0] + 0.7152f * row[x][1] + 0.2126f * row[x][2];  // BGR.
        for (int c = 0; c < 3; ++c) row[x][c] = grey + k * (row[x][c] - grey);
      }
    }
  }
  if (effects.chromatic_aberration_px > 0.01) {
    // Lateral chromatic aberration: red magnified, blue shrunk about the
    // centre so that they move ±chromatic_aberration_px at the corner.
    const double k = effects.chromatic_aberration_px / std::max(1.0, std::sqrt(static_cast<double>(r2max)));
    std::vector<cv::Mat> channels;
    cv::split(srgb, channels);
    for (auto [c, scale] : {std::pair{2, 1.0 + k}, std::pair{0, 1.0 - k}}) {
      cv::Mat m = (cv::Mat_<double>(2, 3) << scale, 0, cx * (1 - scale), 0, scale, cy * (1 - scale));
      cv::warpAffine(channels[c], channels[c], m, channels[c].size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    }
    cv::merge(channels, srgb);
  }
  if (effects.blur_sigma_px > 0.05) {
    cv::GaussianBlur(srgb, srgb, cv::Size(0, 0), effects.blur_sigma_px);
  }
  if (effects.sharpen > 0.01) {
    cv::Mat soft;
    cv::GaussianBlur(srgb, soft, cv::Size(0, 0), 1.0);
    cv::addWeighted(srgb, 1.0 + effects.sharpen, soft, -effects.sharpen, 0.0, srgb);
  }
  cv::Mat out(h, w, CV_8UC3);
  const float sigma = static_cast<float>(effects.noise_sigma);
  for (int y = 0; y < h; ++y) {
    const auto* in = srgb.ptr<cv::Vec3f>(y);
    auto* o = out.ptr<cv::Vec3b>(y);
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) {
        float v = in[x][c];
        if (sigma > 0) {
          // Shot noise grows with the signal; read noise is a floor.
          std::uint64_t key = noise_seed * 0x100000001B3ULL + (static_cast<std::uint64_t>(y) * w + x) * 3 + c;
          v += sigma * std::sqrt(0.25f + v) * HashGaussian(key);
        }
        o[x][c] = static_cast<std::uint8_t>(std::clamp(std::lround(v * 255.0f), 0L, 255L));
      }
    }
  }
  if (effects.jpeg_quality > 0) {
    std::vector<std::uint8_t> buffer;
    cv::imencode(".jpg", out, buffer, {cv::IMWRITE_JPEG_QUALITY, effects.jpeg_quality});
    out = cv::imdecode(buffer, cv::IMREAD_COLOR);
  }
  return AsImage(out);
}

}  // namespace asbuilt
