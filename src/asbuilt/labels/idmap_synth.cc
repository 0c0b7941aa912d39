#include "asbuilt/labels/idmap_synth.h"

#include <cmath>
#include <random>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// A smooth random field in [lo, hi]: random values on a coarse grid,
// bicubically upsampled and clamped.
cv::Mat SmoothField(cv::Size size, double cell_px, double lo, double hi, std::mt19937_64& rng) {
  const int gw = std::max(2, static_cast<int>(std::ceil(size.width / cell_px)) + 1);
  const int gh = std::max(2, static_cast<int>(std::ceil(size.height / cell_px)) + 1);
  std::uniform_real_distribution<float> u(static_cast<float>(lo), static_cast<float>(hi));
  cv::Mat grid(gh, gw, CV_32FC1);
  for (int y = 0; y < gh; ++y) {
    for (int x = 0; x < gw; ++x) grid.at<float>(y, x) = u(rng);
  }
  cv::Mat field;
  cv::resize(grid, field, size, 0, 0, cv::INTER_CUBIC);
  cv::min(field, hi, field);
  cv::max(field, lo, field);
  return field;
}

}  // namespace

void IdMapDriftOptions::Check() const {
  CheckArgument(brightness_min > 0 && brightness_min <= brightness_max,
                fmt::format("IdMapDriftOptions.brightness_min = {}, must be in (0, brightness_max]", brightness_min));
  CheckArgument(saturation_min >= 0 && saturation_min <= saturation_max && saturation_max <= 1.5,
                fmt::format("IdMapDriftOptions.saturation_min = {}, must be in [0, saturation_max]", saturation_min));
  CheckArgument(hue_shift_deg >= 0 && hue_shift_deg <= 180,
                fmt::format("IdMapDriftOptions.hue_shift_deg = {}, must be in 0..180", hue_shift_deg));
  CheckArgument(class_reflectance >= 0 && class_reflectance < 1,
                fmt::format("IdMapDriftOptions.class_reflectance = {}, must be in [0, 1)", class_reflectance));
  CheckArgument(field_cell_px >= 4, fmt::format("IdMapDriftOptions.field_cell_px = {}, must be >= 4", field_cell_px));
  CheckArgument(antialias_sigma_px >= 0,
                fmt::format("IdMapDriftOptions.antialias_sigma_px = {}, must be >= 0", antialias_sigma_px));
  CheckArgument(noise_sigma >= 0, fmt::format("IdMapDriftOptions.noise_sigma = {}, must be >= 0", noise_sigma));
}

cv::Mat SynthesizeIdMap(const cv::Mat& labels, const Palette& nominal, const IdMapDriftOptions& options) {
  options.Check();
  CheckArgument(labels.type() == CV_8UC1 && !labels.empty(), "SynthesizeIdMap: labels must be a CV_8UC1 map");
  std::mt19937_64 rng(options.seed);

  // Nominal colour of each id, in HSV (hue degrees, s and v in 0..1).
  std::array<cv::Vec3f, 256> hsv;
  cv::Vec3f background(0, 0, 0);
  std::array<bool, 256> known{};
  auto to_hsv = [](const Rgb& rgb) {
    cv::Mat3f px(1, 1, cv::Vec3f(rgb[2] / 255.0f, rgb[1] / 255.0f, rgb[0] / 255.0f)), out;
    cv::cvtColor(px, out, cv::COLOR_BGR2HSV);
    return out(0, 0);
  };
  for (const PaletteColour& c : nominal.colours) {
    if (known[c.id]) continue;
    known[c.id] = true;
    hsv[c.id] = to_hsv(c.rgb);
    if (c.id == 0) background = hsv[c.id];
  }
  std::uniform_real_distribution<float> refl(static_cast<float>(1 - options.class_reflectance),
                                             static_cast<float>(1 + options.class_reflectance));
  std::array<float, 256> reflectance;
  for (float& r : reflectance) r = refl(rng);

  // Lighting fields.
  const cv::Size size = labels.size();
  cv::Mat value = SmoothField(size, options.field_cell_px, options.brightness_min, options.brightness_max, rng);
  cv::Mat sat = SmoothField(size, options.field_cell_px, options.saturation_min, options.saturation_max, rng);
  cv::Mat hue = SmoothField(size, options.field_cell_px, -options.hue_shift_deg, options.hue_shift_deg, rng);

  cv::Mat3f drifted(size);
  for (int y = 0; y < size.height; ++y) {
    const std::uint8_t* id = labels.ptr<std::uint8_t>(y);
    for (int x = 0; x < size.width; ++x) {
      cv::Vec3f c = known[id[x]] ? hsv[id[x]] : background;
      float h = c[0] + hue.at<float>(y, x);
      if (h < 0) h += 360;
      if (h >= 360) h -= 360;
      float s = std::min(1.0f, c[1] * sat.at<float>(y, x));
      float v = std::min(1.0f, c[2] * value.at<float>(y, x) * reflectance[id[x]]);
      drifted(y, x) = cv::Vec3f(h, s, v);
    }
  }
  cv::Mat3f bgr;
  cv::cvtColor(drifted, bgr, cv::COLOR_HSV2BGR);
  bgr *= 255.0f;
  // Pixel filter: blends colours only where they change (the fields are smooth).
  if (options.antialias_sigma_px > 0) {
    cv::GaussianBlur(bgr, bgr, cv::Size(0, 0), options.antialias_sigma_px, options.antialias_sigma_px,
                     cv::BORDER_REPLICATE);
  }
  if (options.noise_sigma > 0) {
    cv::Mat3f noise(size);
    cv::RNG cvrng(options.seed * 0x9E3779B97F4A7C15ULL + 1);
    cvrng.fill(noise, cv::RNG::NORMAL, 0.0, options.noise_sigma);
    bgr += noise;
  }
  cv::Mat out;
  bgr.convertTo(out, CV_8UC3);  // Rounds and saturates to 0..255.
  return out;
}

cv::Mat SyntheticRoomLabels(int width_px, int height_px, std::uint64_t seed) {
  CheckArgument(width_px >= 32 && height_px >= 32, "SyntheticRoomLabels: the image must be at least 32x32");
  std::mt19937_64 rng(seed);
  auto uni = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  const double w = width_px, h = height_px;
  auto fill = [&](std::vector<cv::Point2d> poly, std::uint8_t id, cv::Mat& m) {
    std::vector<cv::Point> fixed;
    for (const cv::Point2d& p : poly) fixed.emplace_back(cvRound(p.x * 256), cvRound(p.y * 256));
    cv::fillPoly(m, std::vector<std::vector<cv::Point>>{fixed}, cv::Scalar(id), cv::LINE_8, 8);
  };
  cv::Mat labels(height_px, width_px, CV_8UC1, cv::Scalar(0));
  // Wall band between a ceiling line and a floor line, both bent at a corner.
  const double corner_x = uni(0.2, 0.8) * w;
  const double ceil_l = uni(0.05, 0.2) * h, ceil_c = uni(0.1, 0.25) * h, ceil_r = uni(0.05, 0.2) * h;
  const double floor_l = uni(0.75, 0.95) * h, floor_c = uni(0.7, 0.85) * h, floor_r = uni(0.75, 0.95) * h;
  fill({{0, ceil_l}, {corner_x, ceil_c}, {w, ceil_r}, {w, floor_r}, {corner_x, floor_c}, {0, floor_l}}, 1, labels);
  // Height of the floor / ceiling line at x.
  auto floor_at = [&](double x) {
    return x < corner_x ? floor_l + (floor_c - floor_l) * x / corner_x
                        : floor_c + (floor_r - floor_c) * (x - corner_x) / (w - corner_x);
  };
  auto ceil_at = [&](double x) {
    return x < corner_x ? ceil_l + (ceil_c - ceil_l) * x / corner_x
                        : ceil_c + (ceil_r - ceil_c) * (x - corner_x) / (w - corner_x);
  };
  // Door: on the floor line, about 0.75 of the wall height.
  const double dx0 = uni(0.05, 0.7) * w, dx1 = dx0 + uni(0.1, 0.2) * w;
  const double dtop = 0.25;
  fill({{dx0, floor_at(dx0)},
        {dx1, floor_at(dx1)},
        {dx1, ceil_at(dx1) + dtop * (floor_at(dx1) - ceil_at(dx1))},
        {dx0, ceil_at(dx0) + dtop * (floor_at(dx0) - ceil_at(dx0))}},
       2, labels);
  // Windows: between sill and head, away from the door.
  const int windows = 1 + static_cast<int>(rng() % 2);
  for (int i = 0; i < windows; ++i) {
    double x0 = uni(0.02, 0.85) * w, x1 = x0 + uni(0.08, 0.15) * w;
    if (x1 > dx0 - 4 && x0 < dx1 + 4) continue;  // Would overlap the door.
    auto at = [&](double x, double t) { return ceil_at(x) + t * (floor_at(x) - ceil_at(x)); };
    fill({{x0, at(x0, 0.15)}, {x1, at(x1, 0.15)}, {x1, at(x1, 0.55)}, {x0, at(x0, 0.55)}}, 3, labels);
  }
  // Furniture (background) in front of the lower wall.
  const double fx0 = uni(0, 0.8) * w, fx1 = fx0 + uni(0.1, 0.25) * w, fy = uni(0.55, 0.75) * h;
  fill({{fx0, fy}, {fx1, fy + uni(-10, 10)}, {fx1, h}, {fx0, h}}, 0, labels);
  return labels;
}

}  // namespace asbuilt
