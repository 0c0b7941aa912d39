#include "asbuilt/seg/seg_data.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "asbuilt/dataset/manifest.h"
#include "asbuilt/dataset/pairs.h"
#include "asbuilt/geometry/label_class.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace fs = std::filesystem;

SegDataSplit SplitFromManifest(const fs::path& manifest_path) {
  Manifest m = ReadManifest(manifest_path);
  SegDataSplit split;
  auto convert = [&](const std::vector<ManifestEntry>& entries, std::vector<SegSample>& out) {
    for (const ManifestEntry& e : entries) {
      out.push_back({e.image, m.Resolve(e.image), m.Resolve(e.label)});
    }
  };
  convert(m.train, split.train);
  convert(m.val, split.val);
  convert(m.test, split.test);
  split.source = fmt::format("manifest {} ({})", manifest_path.string(), m.ToString());
  if (split.train.empty()) throw InputError(manifest_path.string(), "train", "no training pairs");
  return split;
}

SegDataSplit SplitFromFolders(const fs::path& images_dir, const fs::path& labels_dir, double val_fraction,
                              std::uint64_t seed) {
  CheckArgument(val_fraction >= 0 && val_fraction < 1,
                fmt::format("validation fraction = {}, must be in [0, 1)", val_fraction));
  PairListing listing = labels_dir.empty() ? ListDatasetPairs(images_dir) : ListPairs(images_dir, labels_dir);
  if (listing.pairs.empty()) {
    throw InputError(images_dir.string(), "", "no (image, label) pairs found: " + listing.ToString());
  }
  std::vector<SegSample> all;
  for (const ImagePair& p : listing.pairs) all.push_back({p.name, p.image, p.label});
  std::mt19937_64 rng(seed);
  std::shuffle(all.begin(), all.end(), rng);
  size_t n_val = static_cast<size_t>(std::round(val_fraction * all.size()));
  if (val_fraction > 0 && n_val == 0 && all.size() >= 2) n_val = 1;
  SegDataSplit split;
  split.val.assign(all.begin(), all.begin() + n_val);
  split.train.assign(all.begin() + n_val, all.end());
  split.source = labels_dir.empty() ? fmt::format("folder {} ({})", images_dir.string(), listing.ToString())
                                    : fmt::format("folders {} + {} ({})", images_dir.string(), labels_dir.string(),
                                                  listing.ToString());
  return split;
}

SegPair ReadSegPair(const SegSample& sample, int num_classes) {
  SegPair p;
  p.bgr = ReadColourImage(sample.image);
  p.label = ReadLabelImage(sample.label);
  CheckImageSize(p.label, p.bgr.cols, p.bgr.rows, sample.label, "", "its image " + sample.image.string());
  for (int r = 0; r < p.label.rows; ++r) {
    const std::uint8_t* l = p.label.ptr<std::uint8_t>(r);
    for (int c = 0; c < p.label.cols; ++c) {
      if (l[c] >= num_classes && l[c] != 255) {
        throw InputError(
            sample.label.string(), "",
            fmt::format("label id {} at ({}, {}) is not a class (0..{}) or 255 (ignore)", l[c], c, r, num_classes - 1));
      }
    }
  }
  return p;
}

const FieldList<AugmentOptions>& AugmentOptionFields() {
  using O = AugmentOptions;
  static const FieldList<O> kList = {
      Bind(&O::scale_width_px, {.name = "scale_width_px",
                                .description = "Base scale: images are fitted (aspect kept) into this width, px.",
                                .minimum = 1.0}),
      Bind(&O::scale_height_px, {.name = "scale_height_px", .description = "… and this height, px.", .minimum = 1.0}),
      Bind(&O::ratio_min, {.name = "ratio_min",
                           .description = "Random resize after the fit, smallest ratio (mmseg: 0.5).",
                           .exclusive_minimum = 0.0}),
      Bind(
          &O::ratio_max,
          {.name = "ratio_max", .description = "Random resize, largest ratio (mmseg: 2.0).", .exclusive_minimum = 0.0}),
      Bind(&O::crop_width_px, {.name = "crop_width_px",
                               .description = "Random crop width, px; padded with ignore when the image is smaller.",
                               .minimum = 1.0}),
      Bind(&O::crop_height_px, {.name = "crop_height_px", .description = "Random crop height, px.", .minimum = 1.0}),
      Bind(&O::cat_max_ratio, {.name = "cat_max_ratio",
                               .description = "A crop one class covers more of is drawn again (mmseg RandomCrop).",
                               .exclusive_minimum = 0.0,
                               .maximum = 1.0}),
      Bind(&O::flip, {.name = "flip", .description = "Horizontal flips, p = 0.5."}),
      Bind(&O::photometric,
           {.name = "photometric", .description = "Photometric distortion: brightness, contrast, saturation, hue."}),
      Bind(&O::blur_noise, {.name = "blur_noise", .description = "Gaussian blur (p 0.3) and sensor noise (p 0.3)."}),
      Bind(&O::stray_light_probability,
           {.name = "stray_light_probability",
            .description = "Share of crops given patches of sun or lamp light and dimmed windows, so that bright "
                           "is not window (real photos; 0 = off).",
            .minimum = 0.0,
            .maximum = 1.0}),
  };
  return kList;
}

void AugmentOptions::Check() const {
  AugmentOptionFields().CheckValues(*this, "AugmentOptions");
  CheckArgument(ratio_min <= ratio_max,
                fmt::format("AugmentOptions ratio range [{}, {}] is empty", ratio_min, ratio_max));
}

cv::Size FitSize(cv::Size image, int width_px, int height_px) {
  double s = std::min(static_cast<double>(width_px) / image.width, static_cast<double>(height_px) / image.height);
  return {std::max(1, static_cast<int>(std::lround(image.width * s))),
          std::max(1, static_cast<int>(std::lround(image.height * s)))};
}

void AddStrayLight(SegPair& pair, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u01(0, 1);
  auto U = [&](double a, double b) { return a + (b - a) * u01(rng); };
  const int w = pair.bgr.cols, h = pair.bgr.rows;
  const double extent = std::min(w, h);
  cv::Mat gain(pair.bgr.size(), CV_32F, cv::Scalar(0));
  const int patches = 1 + static_cast<int>(u01(rng) * 3);
  for (int i = 0; i < patches; ++i) {
    cv::Mat mask(pair.bgr.size(), CV_8U, cv::Scalar(0));
    const cv::Point2d c(U(0, w), U(0, h));
    const double a = U(0.08, 0.35) * extent, b = U(0.05, 0.25) * extent, angle = U(0, 180);
    if (u01(rng) < 0.6) {
      // A sun patch: a window's shape thrown obliquely, a parallelogram.
      const double skew = U(-0.8, 0.8), t = angle * CV_PI / 180;
      const cv::Point2d ax(a * std::cos(t), a * std::sin(t)),
          ay(b * (-std::sin(t) + skew * std::cos(t)), b * (std::cos(t) + skew * std::sin(t)));
      const std::vector<cv::Point> quad = {c - ax - ay, c + ax - ay, c + ax + ay, c - ax + ay};
      cv::fillConvexPoly(mask, quad, cv::Scalar(255), cv::LINE_AA);
    } else {
      // A lamp's pool of light or a glossy highlight: an ellipse.
      cv::ellipse(mask, cv::Point(c), cv::Size(static_cast<int>(a), static_cast<int>(b)), angle, 0, 360,
                  cv::Scalar(255), cv::FILLED, cv::LINE_AA);
    }
    cv::Mat soft;
    mask.convertTo(soft, CV_32F, 1.0 / 255);
    cv::GaussianBlur(soft, soft, cv::Size(0, 0), U(0.5, 0.5 * b));  // Soft edges, the core kept.
    cv::scaleAdd(soft, U(0.5, 3.0), gain, gain);
  }
  cv::Mat f;
  pair.bgr.convertTo(f, CV_32FC3);
  // Warm light: blue gains less than red (BGR order).
  const double warmth = U(0, 0.25);
  std::vector<cv::Mat> ch;
  cv::split(f, ch);
  for (int k = 0; k < 3; ++k) {
    const double tint = k == 0 ? 1 - warmth : (k == 2 ? 1 + 0.5 * warmth : 1);
    cv::Mat g = gain * tint + 1;
    ch[static_cast<std::size_t>(k)] = ch[static_cast<std::size_t>(k)].mul(g);
  }
  cv::merge(ch, f);
  f.convertTo(pair.bgr, CV_8UC3);  // Saturates: blown-out light, as in photos.
  if (u01(rng) < 0.5) {
    // A dull or shaded window: darker and greyer than the room around it.
    cv::Mat window = pair.label == kLabelWindow;
    if (cv::countNonZero(window) == 0) return;
    cv::Mat grey, grey3, dim;
    cv::cvtColor(pair.bgr, grey, cv::COLOR_BGR2GRAY);
    cv::cvtColor(grey, grey3, cv::COLOR_GRAY2BGR);
    const double keep = U(0.2, 1.0), scale = U(0.35, 0.9);
    cv::addWeighted(pair.bgr, keep * scale, grey3, (1 - keep) * scale, 0, dim);
    dim.copyTo(pair.bgr, window);
  }
}

void AugmentPair(SegPair& pair, const AugmentOptions& o, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u01(0, 1);
  auto U = [&](double a, double b) { return a + (b - a) * u01(rng); };
  // Random resize around the base scale.
  cv::Size fit = FitSize(pair.bgr.size(), o.scale_width_px, o.scale_height_px);
  double ratio = U(o.ratio_min, o.ratio_max);
  cv::Size size(std::max(1, static_cast<int>(fit.width * ratio)), std::max(1, static_cast<int>(fit.height * ratio)));
  cv::resize(pair.bgr, pair.bgr, size, 0, 0, cv::INTER_LINEAR);
  // INTER_NEAREST_EXACT: plain INTER_NEAREST takes the source pixel left of
  // and above each target centre, moving label edges half a pixel right and
  // down of the image's (SegmenterInfo::label_offset_px).
  cv::resize(pair.label, pair.label, size, 0, 0, cv::INTER_NEAREST_EXACT);
  // Pad to the crop size (label 255 = ignore), then crop.
  int pad_w = std::max(0, o.crop_width_px - size.width), pad_h = std::max(0, o.crop_height_px - size.height);
  if (pad_w > 0 || pad_h > 0) {
    cv::copyMakeBorder(pair.bgr, pair.bgr, 0, pad_h, 0, pad_w, cv::BORDER_CONSTANT, cv::Scalar(0, 0, 0));
    cv::copyMakeBorder(pair.label, pair.label, 0, pad_h, 0, pad_w, cv::BORDER_CONSTANT, cv::Scalar(255));
  }
  cv::Rect crop;
  for (int attempt = 0; attempt < 10; ++attempt) {
    int x = static_cast<int>(U(0, pair.bgr.cols - o.crop_width_px + 1 - 1e-9));
    int y = static_cast<int>(U(0, pair.bgr.rows - o.crop_height_px + 1 - 1e-9));
    crop = cv::Rect(x, y, o.crop_width_px, o.crop_height_px);
    // mmseg cat_max_ratio: accept unless one class covers too much.
    int hist[256] = {0};
    cv::Mat l = pair.label(crop);
    for (int r = 0; r < l.rows; ++r) {
      const std::uint8_t* p = l.ptr<std::uint8_t>(r);
      for (int c = 0; c < l.cols; ++c) ++hist[p[c]];
    }
    int total = 0, best = 0, kinds = 0;
    for (int k = 0; k < 255; ++k) {
      total += hist[k];
      best = std::max(best, hist[k]);
      kinds += hist[k] > 0;
    }
    if (kinds > 1 && best < o.cat_max_ratio * total) break;
  }
  pair.bgr = pair.bgr(crop).clone();
  pair.label = pair.label(crop).clone();
  if (o.flip && u01(rng) < 0.5) {
    cv::flip(pair.bgr, pair.bgr, 1);
    cv::flip(pair.label, pair.label, 1);
  }
  // Drawn only when on, so the shipped recipe's random stream is unchanged.
  if (o.stray_light_probability > 0 && u01(rng) < o.stray_light_probability) AddStrayLight(pair, rng);
  if (o.photometric) {
    cv::Mat f;
    pair.bgr.convertTo(f, CV_32FC3);
    if (u01(rng) < 0.5) f += cv::Scalar::all(U(-32, 32));  // Brightness.
    bool contrast_first = u01(rng) < 0.5;
    auto contrast = [&] {
      if (u01(rng) < 0.5) f *= U(0.5, 1.5);
    };
    if (contrast_first) contrast();
    cv::Mat clipped;
    f.convertTo(clipped, CV_8UC3);
    if (u01(rng) < 0.5 || u01(rng) < 0.5) {  // Saturation / hue in HSV.
      cv::Mat hsv;
      cv::cvtColor(clipped, hsv, cv::COLOR_BGR2HSV);
      std::vector<cv::Mat> ch;
      cv::split(hsv, ch);
      if (u01(rng) < 0.5) ch[1].convertTo(ch[1], CV_8U, U(0.5, 1.5));
      if (u01(rng) < 0.5) {
        int dh = static_cast<int>(U(-9, 9));  // OpenCV hue is 0..179: ±18° in mmseg units.
        cv::Mat h16;
        ch[0].convertTo(h16, CV_16S);
        h16 += dh + 180;
        for (int r = 0; r < h16.rows; ++r) {
          auto* p = h16.ptr<std::int16_t>(r);
          for (int c = 0; c < h16.cols; ++c) p[c] = static_cast<std::int16_t>(p[c] % 180);
        }
        h16.convertTo(ch[0], CV_8U);
      }
      cv::merge(ch, hsv);
      cv::cvtColor(hsv, clipped, cv::COLOR_HSV2BGR);
    }
    if (!contrast_first) {
      clipped.convertTo(f, CV_32FC3);
      contrast();
      f.convertTo(clipped, CV_8UC3);
    }
    pair.bgr = clipped;
  }
  if (o.blur_noise) {
    if (u01(rng) < 0.3) cv::GaussianBlur(pair.bgr, pair.bgr, cv::Size(0, 0), U(0.3, 1.5));
    if (u01(rng) < 0.3) {
      cv::Mat noise(pair.bgr.size(), CV_16SC3), img16;
      cv::RNG cv_rng(rng());
      cv_rng.fill(noise, cv::RNG::NORMAL, 0, U(2, 10));
      pair.bgr.convertTo(img16, CV_16SC3);
      img16 += noise;
      img16.convertTo(pair.bgr, CV_8UC3);
    }
  }
}

}  // namespace asbuilt
