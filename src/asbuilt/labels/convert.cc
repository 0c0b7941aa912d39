#include "asbuilt/labels/convert.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>

#include <fmt/format.h>
#include <tbb/task_arena.h>
#include <tbb/parallel_for.h>

#include "asbuilt/imageio/image_io.h"
#include "asbuilt/labels/label_io.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace fs = std::filesystem;

void ConvertOptions::Check() const {
  CheckArgument(std::isfinite(threshold) && threshold > 0,
                fmt::format("ConvertOptions.threshold = {}, must be > 0 (RGB distance)", threshold));
  CheckArgument(num_threads >= 0, fmt::format("ConvertOptions.num_threads = {}, must be >= 0", num_threads));
}

cv::Mat ConvertIdMap(const cv::Mat& idmap_bgr, const Palette& palette, double threshold,
                     std::int64_t* beyond_threshold) {
  CheckArgument(!palette.colours.empty(), "ConvertIdMap: the palette has no colours");
  CheckArgument(idmap_bgr.type() == CV_8UC3, "ConvertIdMap: the ID map must be CV_8UC3 (BGR)");
  // Squared distances in float: exact enough for 8-bit inputs, and the
  // comparison with the nearest colour is what matters.
  const int k = static_cast<int>(palette.colours.size());
  std::vector<float> ref(3 * k);
  std::vector<std::uint8_t> ids(k);
  for (int i = 0; i < k; ++i) {
    const PaletteColour& c = palette.colours[i];
    ref[3 * i + 0] = static_cast<float>(c.rgb[2]);  // B
    ref[3 * i + 1] = static_cast<float>(c.rgb[1]);  // G
    ref[3 * i + 2] = static_cast<float>(c.rgb[0]);  // R
    ids[i] = c.id;
  }
  const float threshold_sq = static_cast<float>(threshold * threshold);
  cv::Mat labels(idmap_bgr.size(), CV_8UC1);
  std::int64_t beyond = 0;
  for (int y = 0; y < idmap_bgr.rows; ++y) {
    const std::uint8_t* in = idmap_bgr.ptr<std::uint8_t>(y);
    std::uint8_t* out = labels.ptr<std::uint8_t>(y);
    for (int x = 0; x < idmap_bgr.cols; ++x) {
      const float b = in[3 * x], g = in[3 * x + 1], r = in[3 * x + 2];
      float best = std::numeric_limits<float>::max();
      int best_i = 0;
      for (int i = 0; i < k; ++i) {
        const float db = b - ref[3 * i], dg = g - ref[3 * i + 1], dr = r - ref[3 * i + 2];
        const float d = db * db + dg * dg + dr * dr;
        if (d < best) {
          best = d;
          best_i = i;
        }
      }
      if (best > threshold_sq) {
        out[x] = 0;
        ++beyond;
      } else {
        out[x] = ids[best_i];
      }
    }
  }
  if (beyond_threshold) *beyond_threshold = beyond;
  return labels;
}

std::string ConvertSummary::BriefReport() const {
  std::string out = fmt::format("converted {} ID map{} ({:.1f} Mpx, {:.2f} % beyond threshold) in {:.2f} s", converted,
                                converted == 1 ? "" : "s", pixels / 1e6,
                                pixels > 0 ? 100.0 * beyond_threshold / pixels : 0.0, seconds);
  if (!failed.empty()) out += fmt::format("; {} failed", failed.size());
  return out;
}

ConvertSummary ConvertIdMapFiles(const ConvertOptions& options, const Palette& palette,
                                 const std::vector<fs::path>& idmaps, const fs::path& output_dir,
                                 const ProgressCallback& progress) {
  options.Check();
  CheckArgument(!palette.colours.empty(), "ConvertIdMapFiles: the palette has no colours");
  const auto start = std::chrono::steady_clock::now();
  ConvertSummary summary;
  std::mutex mutex;
  std::atomic<int> done{0};
  tbb::task_arena arena(options.num_threads > 0 ? options.num_threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, idmaps.size(), [&](std::size_t i) {
      const fs::path& input = idmaps[i];
      try {
        cv::Mat idmap = ReadColourImage(input);
        std::int64_t beyond = 0;
        cv::Mat labels = ConvertIdMap(idmap, palette, options.threshold, &beyond);
        WriteLabelImage(output_dir / (input.stem().string() + ".png"), labels);
        std::lock_guard lock(mutex);
        ++summary.converted;
        summary.pixels += labels.total();
        summary.beyond_threshold += beyond;
      } catch (const InputError& e) {
        std::lock_guard lock(mutex);
        for (const Problem& p : e.problems()) summary.failed.push_back(p);
      } catch (const Error& e) {
        std::lock_guard lock(mutex);
        summary.failed.push_back({input.string(), "", e.what()});
      }
      int n = ++done;
      std::lock_guard lock(mutex);
      ReportProgress(progress, {"convert", n, static_cast<std::int64_t>(idmaps.size()), input.filename().string()});
    });
  });
  std::sort(summary.failed.begin(), summary.failed.end(),
            [](const Problem& a, const Problem& b) { return a.file < b.file; });
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

std::vector<fs::path> ListImageFiles(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir.string(), "", "not a folder");
  std::vector<fs::path> out;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    const fs::path& p = entry.path();
    std::string name = p.filename().string();
    if (name.empty() || name[0] == '.' || IsAtomicTempName(p) || !entry.is_regular_file(ec)) continue;
    if (IsImageExtension(p)) {
      out.push_back(p);
    }
  }
  if (ec) throw InputError(dir.string(), "", "cannot read: " + ec.message());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace asbuilt
