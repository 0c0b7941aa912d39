#include "asbuilt/labels/calibrate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <random>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>
#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "asbuilt/labels/label_io.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;

// Colour statistics per palette colour inside the masks: exact integer sums
// (so merging in any order gives the same result) and a coarse colour
// histogram (8 levels per bin and channel) for the spread's quantile.
constexpr int kBinShift = 3;
constexpr int kBinsPerChannel = 256 >> kBinShift;
constexpr int kBins = kBinsPerChannel * kBinsPerChannel * kBinsPerChannel;

struct MaskSums {
  explicit MaskSums(std::size_t k)
      : sum(k, {0, 0, 0}), count(k, 0), histogram(k, std::vector<std::uint32_t>(kBins, 0)) {}
  std::vector<std::array<std::int64_t, 3>> sum;  // BGR.
  std::vector<std::int64_t> count;
  std::vector<std::vector<std::uint32_t>> histogram;

  void Merge(const MaskSums& o) {
    for (std::size_t i = 0; i < sum.size(); ++i) {
      for (int c = 0; c < 3; ++c) sum[i][c] += o.sum[i][c];
      count[i] += o.count[i];
      for (int b = 0; b < kBins; ++b) histogram[i][b] += o.histogram[i][b];
    }
  }
};

// Pixels whose (2m+1)² neighbourhood holds one label only.
cv::Mat InteriorMask(const cv::Mat& labels, int margin_px) {
  if (margin_px <= 0) return cv::Mat(labels.size(), CV_8UC1, cv::Scalar(255));
  cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, {2 * margin_px + 1, 2 * margin_px + 1});
  cv::Mat lo, hi;
  cv::erode(labels, lo, kernel, {-1, -1}, 1, cv::BORDER_REPLICATE);
  cv::dilate(labels, hi, kernel, {-1, -1}, 1, cv::BORDER_REPLICATE);
  return lo == hi;
}

MaskSums SumInsideMasks(const PaletteCalibrateOptions& options, const cv::Mat& idmap, const cv::Mat& mask) {
  const Palette& nominal = options.nominal;
  MaskSums sums(nominal.colours.size());
  // Palette index of each label id (first colour with that id).
  std::array<int, 256> index;
  index.fill(-1);
  for (std::size_t i = 0; i < nominal.colours.size(); ++i) {
    if (index[nominal.colours[i].id] < 0) index[nominal.colours[i].id] = static_cast<int>(i);
  }
  cv::Mat interior = InteriorMask(mask, options.edge_margin_px);
  for (int y = 0; y < idmap.rows; ++y) {
    const std::uint8_t* px = idmap.ptr<std::uint8_t>(y);
    const std::uint8_t* id = mask.ptr<std::uint8_t>(y);
    const std::uint8_t* in = interior.ptr<std::uint8_t>(y);
    for (int x = 0; x < idmap.cols; ++x) {
      int i = index[id[x]];
      if (i < 0 || !in[x]) continue;
      const std::uint8_t* p = px + 3 * x;
      for (int c = 0; c < 3; ++c) sums.sum[i][c] += p[c];
      ++sums.count[i];
      ++sums.histogram[i][((p[0] >> kBinShift) * kBinsPerChannel + (p[1] >> kBinShift)) * kBinsPerChannel +
                          (p[2] >> kBinShift)];
    }
  }
  return sums;
}

// The suggested threshold covers this fraction of every class's pixels.
constexpr double kSpreadQuantile = 0.999;

// The q-quantile of weighted values.
double Quantile(std::vector<std::pair<double, std::int64_t>> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  std::int64_t total = 0;
  for (const auto& v : values) total += v.second;
  const double target = q * total;
  std::int64_t seen = 0;
  for (const auto& [value, weight] : values) {
    seen += weight;
    if (seen >= target) return value;
  }
  return values.back().first;
}

// The largest per-class distance quantile plus a margin for the histogram's
// bin size (half a bin diagonal) — never below 10.
void SuggestThreshold(Palette& palette, const std::vector<double>& quantiles) {
  double q = 0;
  for (double v : quantiles) q = std::max(q, v);
  if (q > 0) palette.threshold = std::max(10.0, q + 0.5 * std::sqrt(3.0) * (1 << kBinShift));
}

// Turns the sums into a palette; a colour with no pixels stays nominal.
void FinishMaskPalette(const PaletteCalibrateOptions& options, const MaskSums& sums, CalibrateSummary& summary) {
  summary.palette.method = "masks";
  summary.palette.colours = options.nominal.colours;
  std::vector<double> quantiles;
  for (std::size_t i = 0; i < sums.sum.size(); ++i) {
    PaletteColour& c = summary.palette.colours[i];
    if (sums.count[i] == 0) {
      summary.warnings.push_back(fmt::format("no {} pixels in the masks: kept the nominal colour", LabelIdName(c.id)));
      continue;
    }
    // Sums are BGR; the palette is RGB.
    for (int ch = 0; ch < 3; ++ch) c.rgb[2 - ch] = static_cast<double>(sums.sum[i][ch]) / sums.count[i];
    // Distances of the histogram bins' centres to the centroid.
    std::vector<std::pair<double, std::int64_t>> distances;
    double sq_sum = 0;
    for (int b = 0; b < kBins; ++b) {
      if (sums.histogram[i][b] == 0) continue;
      const int bins[3] = {b / (kBinsPerChannel * kBinsPerChannel), (b / kBinsPerChannel) % kBinsPerChannel,
                           b % kBinsPerChannel};
      double d2 = 0;
      for (int ch = 0; ch < 3; ++ch) {
        const double centre = (bins[ch] << kBinShift) + 0.5 * ((1 << kBinShift) - 1);
        d2 += (centre - c.rgb[2 - ch]) * (centre - c.rgb[2 - ch]);
      }
      distances.emplace_back(std::sqrt(d2), sums.histogram[i][b]);
      sq_sum += d2 * sums.histogram[i][b];
    }
    c.rms_distance = std::sqrt(sq_sum / sums.count[i]);
    quantiles.push_back(Quantile(std::move(distances), kSpreadQuantile));
    c.pixels = sums.count[i];
    summary.pixels += sums.count[i];
  }
  SuggestThreshold(summary.palette, quantiles);
}

using Sample = std::array<std::uint8_t, 3>;  // BGR.

std::vector<Sample> SamplePixels(const cv::Mat& idmap, std::int64_t max_samples, std::uint64_t seed) {
  std::vector<Sample> out;
  const std::int64_t n = static_cast<std::int64_t>(idmap.total());
  if (n == 0 || max_samples <= 0) return out;
  auto at = [&](std::int64_t i) {
    const std::uint8_t* p = idmap.ptr<std::uint8_t>(static_cast<int>(i / idmap.cols)) + 3 * (i % idmap.cols);
    return Sample{p[0], p[1], p[2]};
  };
  if (n <= max_samples) {
    out.reserve(n);
    for (std::int64_t i = 0; i < n; ++i) out.push_back(at(i));
    return out;
  }
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::int64_t> pick(0, n - 1);
  out.reserve(max_samples);
  for (std::int64_t i = 0; i < max_samples; ++i) out.push_back(at(pick(rng)));
  return out;
}

// Lloyd iterations seeded at the nominal colours, with a capture radius.
void Cluster(const PaletteCalibrateOptions& options, const std::vector<Sample>& samples, CalibrateSummary& summary) {
  const std::size_t k = options.nominal.colours.size();
  std::vector<std::array<double, 3>> centre(k);  // BGR.
  for (std::size_t i = 0; i < k; ++i) {
    for (int c = 0; c < 3; ++c) centre[i][c] = options.nominal.colours[i].rgb[2 - c];
  }
  const double radius_sq = options.kmeans_radius * options.kmeans_radius;
  std::vector<std::int64_t> count(k, 0);
  std::vector<int> owner(samples.size(), -1);
  for (int iter = 0; iter < options.kmeans_iterations; ++iter) {
    std::vector<std::array<double, 3>> sum(k, {0, 0, 0});
    std::fill(count.begin(), count.end(), 0);
    for (std::size_t si = 0; si < samples.size(); ++si) {
      const Sample& s = samples[si];
      double best = radius_sq;
      int best_i = -1;
      for (std::size_t i = 0; i < k; ++i) {
        double d = 0;
        for (int c = 0; c < 3; ++c) d += (s[c] - centre[i][c]) * (s[c] - centre[i][c]);
        if (d <= best) {
          best = d;
          best_i = static_cast<int>(i);
        }
      }
      owner[si] = best_i;
      if (best_i < 0) continue;
      for (int c = 0; c < 3; ++c) sum[best_i][c] += s[c];
      ++count[best_i];
    }
    double moved = 0;
    for (std::size_t i = 0; i < k; ++i) {
      if (count[i] == 0) continue;
      for (int c = 0; c < 3; ++c) {
        double v = sum[i][c] / count[i];
        moved = std::max(moved, std::abs(v - centre[i][c]));
        centre[i][c] = v;
      }
    }
    if (moved < 0.01) break;
  }
  summary.palette.method = "kmeans";
  summary.palette.colours = options.nominal.colours;
  for (std::size_t i = 0; i < k; ++i) {
    PaletteColour& c = summary.palette.colours[i];
    if (count[i] == 0) {
      summary.warnings.push_back(fmt::format("no pixels near the nominal {} colour: kept it", LabelIdName(c.id)));
      continue;
    }
    for (int ch = 0; ch < 3; ++ch) c.rgb[2 - ch] = centre[i][ch];
    c.pixels = count[i];
    summary.pixels += count[i];
  }
  // Spread: distances of the samples captured in the last pass to their
  // final centre.
  std::vector<std::vector<std::pair<double, std::int64_t>>> distances(k);
  std::vector<double> sq_sum(k, 0);
  for (std::size_t si = 0; si < samples.size(); ++si) {
    if (owner[si] < 0) continue;
    double d2 = 0;
    for (int c = 0; c < 3; ++c) d2 += (samples[si][c] - centre[owner[si]][c]) * (samples[si][c] - centre[owner[si]][c]);
    distances[owner[si]].emplace_back(std::sqrt(d2), 1);
    sq_sum[owner[si]] += d2;
  }
  std::vector<double> quantiles;
  for (std::size_t i = 0; i < k; ++i) {
    if (count[i] == 0) continue;
    summary.palette.colours[i].rms_distance = std::sqrt(sq_sum[i] / count[i]);
    quantiles.push_back(Quantile(std::move(distances[i]), kSpreadQuantile));
  }
  SuggestThreshold(summary.palette, quantiles);
}

void CheckPair(const cv::Mat& idmap, const cv::Mat& mask) {
  CheckArgument(idmap.type() == CV_8UC3, "Calibrate: ID maps must be CV_8UC3 (BGR)");
  CheckArgument(mask.type() == CV_8UC1, "Calibrate: masks must be CV_8UC1 label maps");
  CheckArgument(idmap.size() == mask.size(), "Calibrate: an ID map and its mask differ in size");
}

double Since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

void LogWarnings(const CalibrateSummary& summary) {
  for (const std::string& w : summary.warnings) spdlog::warn("calibrate: {}", w);
}

}  // namespace

void PaletteCalibrateOptions::Check() const {
  CheckArgument(!nominal.colours.empty(), "PaletteCalibrateOptions.nominal has no colours");
  CheckArgument(edge_margin_px >= 0 && edge_margin_px <= 16,
                fmt::format("PaletteCalibrateOptions.edge_margin_px = {}, must be in 0..16", edge_margin_px));
  CheckArgument(kmeans_iterations >= 1,
                fmt::format("PaletteCalibrateOptions.kmeans_iterations = {}, must be >= 1", kmeans_iterations));
  CheckArgument(std::isfinite(kmeans_radius) && kmeans_radius > 0,
                fmt::format("PaletteCalibrateOptions.kmeans_radius = {}, must be > 0", kmeans_radius));
  CheckArgument(max_sample_pixels >= 1000,
                fmt::format("PaletteCalibrateOptions.max_sample_pixels = {}, must be >= 1000", max_sample_pixels));
  CheckArgument(num_threads >= 0, fmt::format("PaletteCalibrateOptions.num_threads = {}, must be >= 0", num_threads));
}

std::string CalibrateSummary::BriefReport() const {
  std::string out = fmt::format("calibrated {} ID map{} by {} ({:.2f} Mpx) in {:.2f} s: ", idmaps,
                                idmaps == 1 ? "" : "s", palette.method, pixels / 1e6, seconds);
  for (std::size_t i = 0; i < palette.colours.size(); ++i) {
    const PaletteColour& c = palette.colours[i];
    out +=
        fmt::format("{}{} rgb({:.1f}, {:.1f}, {:.1f})", i ? ", " : "", LabelIdName(c.id), c.rgb[0], c.rgb[1], c.rgb[2]);
  }
  if (!failed.empty()) out += fmt::format("; {} skipped", failed.size());
  return out;
}

CalibrateSummary CalibrateWithMasks(const PaletteCalibrateOptions& options, const std::vector<cv::Mat>& idmaps,
                                    const std::vector<cv::Mat>& masks) {
  options.Check();
  CheckArgument(idmaps.size() == masks.size(), "CalibrateWithMasks: one mask per ID map expected");
  const auto start = Clock::now();
  MaskSums total(options.nominal.colours.size());
  for (std::size_t i = 0; i < idmaps.size(); ++i) {
    CheckPair(idmaps[i], masks[i]);
    total.Merge(SumInsideMasks(options, idmaps[i], masks[i]));
  }
  CalibrateSummary summary;
  summary.idmaps = static_cast<int>(idmaps.size());
  FinishMaskPalette(options, total, summary);
  summary.seconds = Since(start);
  LogWarnings(summary);
  return summary;
}

CalibrateSummary CalibrateByClustering(const PaletteCalibrateOptions& options, const std::vector<cv::Mat>& idmaps) {
  options.Check();
  const auto start = Clock::now();
  std::vector<Sample> samples;
  const std::int64_t per_map = options.max_sample_pixels / std::max<std::int64_t>(1, idmaps.size());
  for (std::size_t i = 0; i < idmaps.size(); ++i) {
    CheckArgument(idmaps[i].type() == CV_8UC3, "Calibrate: ID maps must be CV_8UC3 (BGR)");
    std::vector<Sample> s = SamplePixels(idmaps[i], per_map, options.seed + i);
    samples.insert(samples.end(), s.begin(), s.end());
  }
  CalibrateSummary summary;
  summary.idmaps = static_cast<int>(idmaps.size());
  Cluster(options, samples, summary);
  summary.seconds = Since(start);
  LogWarnings(summary);
  return summary;
}

CalibrateSummary CalibrateFiles(const PaletteCalibrateOptions& options, const std::vector<fs::path>& idmaps,
                                const std::vector<fs::path>& masks, const ProgressCallback& progress) {
  options.Check();
  const bool with_masks = !masks.empty();
  CheckArgument(!with_masks || masks.size() == idmaps.size(), "CalibrateFiles: one mask per ID map expected");
  const auto start = Clock::now();
  const std::size_t n = idmaps.size();
  const std::int64_t per_map = options.max_sample_pixels / std::max<std::size_t>(1, n);

  // Per input: sums (masks) or samples (clustering); merged in input order so
  // the result does not depend on thread scheduling.
  MaskSums total(options.nominal.colours.size());
  std::vector<std::vector<Sample>> samples(n);
  std::vector<std::optional<Problem>> failures(n);
  std::mutex mutex;
  int done = 0;
  tbb::task_arena arena(options.num_threads > 0 ? options.num_threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
      try {
        cv::Mat idmap = ReadColourImage(idmaps[i]);
        if (with_masks) {
          cv::Mat mask = ReadLabelImage(masks[i]);
          if (mask.size() != idmap.size()) {
            throw InputError(masks[i].string(), "",
                             fmt::format("mask is {}x{} but its ID map {} is {}x{}", mask.cols, mask.rows,
                                         idmaps[i].filename().string(), idmap.cols, idmap.rows));
          }
          MaskSums sums = SumInsideMasks(options, idmap, mask);
          std::lock_guard lock(mutex);
          total.Merge(sums);
        } else {
          samples[i] = SamplePixels(idmap, per_map, options.seed + i);
        }
      } catch (const InputError& e) {
        failures[i] = e.problems().front();
      }
      std::lock_guard lock(mutex);
      ReportProgress(progress, {"calibrate", ++done, static_cast<std::int64_t>(n), idmaps[i].filename().string()});
    });
  });

  CalibrateSummary summary;
  std::vector<Sample> all;
  for (std::size_t i = 0; i < n; ++i) {
    if (failures[i]) {
      summary.failed.push_back(*failures[i]);
      continue;
    }
    ++summary.idmaps;
    if (!with_masks) all.insert(all.end(), samples[i].begin(), samples[i].end());
  }
  if (summary.idmaps == 0) {
    std::vector<Problem> problems = summary.failed;
    if (problems.empty()) problems.push_back({"", "", "no ID maps given"});
    throw InputError(problems);
  }
  if (with_masks) {
    FinishMaskPalette(options, total, summary);
  } else {
    Cluster(options, all, summary);
  }
  summary.seconds = Since(start);
  LogWarnings(summary);
  return summary;
}

}  // namespace asbuilt
