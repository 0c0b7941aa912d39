// bench_segmenters [RESULTS.md] [REPEATS=15] — seconds to label one 640×480
// view with each shipped model (kShippedModels) and the ADE20K teacher
// zero-shot, through LoadSegmenter as `asbuilt survey` reads a 640×480 stereo
// view (at its own size). The models take turns within each repetition, in
// an order that rotates, so all see the same load drift; the ratio to the
// renders-only B0 is the median of the per-repetition ratios (issue 43's
// speed target: at most as slow as B0, ratio ≤ 1.0).

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/pipeline/survey.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/util/file.h"
#include "bench/bench_util.h"

namespace {
namespace fs = std::filesystem;
using asbuilt::bench::Median;

struct Entry {
  std::string name, what;
  std::unique_ptr<asbuilt::Segmenter> segmenter;
  std::vector<double> seconds;
};

}  // namespace

int main(int argc, char** argv) {
  const std::string results = asbuilt::bench::ResultsPath(argc, argv, "segmenters");
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 15;
  if (!asbuilt::SegmenterAvailable()) {
    std::fprintf(stderr, "bench_segmenters: no segmenter in this build; %s left as it was\n", results.c_str());
    return 0;
  }
  const fs::path frame =
      fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public" / "p01_rect_1door_2win" / "left" / "000.png";
  cv::Mat image = cv::imread(frame.string(), cv::IMREAD_COLOR);
  if (image.empty()) {
    std::fprintf(stderr, "bench_segmenters: %s not present; %s left as it was\n", frame.c_str(), results.c_str());
    return 0;
  }
  cv::resize(image, image, {640, 480});
  const asbuilt::SegmentOptions at_view_size{.scale_width_px = 640, .scale_height_px = 480};
  std::vector<Entry> entries;
  for (const asbuilt::ShippedModel& m : asbuilt::kShippedModels) {
    const fs::path path = asbuilt::ModelPathFor(m.name);
    if (!fs::exists(path)) continue;
    entries.push_back({m.name, m.what, asbuilt::LoadSegmenter(path, at_view_size), {}});
  }
  const fs::path teacher =
      fs::path(ASBUILT_SHARED_DATA_DIR) / "ade20k-teachers" / "deeplabv3_mnv2_ade20k32_uint8.tflite";
  if (fs::exists(teacher)) {
    entries.push_back({"teacher",
                       "MLCommons' DeepLabV3-MobileNetV2, zero-shot (read at run time, not shipped)",
                       asbuilt::LoadSegmenter(teacher, at_view_size),
                       {}});
  }
  std::size_t reference = entries.size();
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (entries[i].name == "renders") reference = i;
  }
  if (reference == entries.size()) {
    std::fprintf(stderr, "bench_segmenters: the renders model is missing; %s left as it was\n", results.c_str());
    return 0;
  }
  for (Entry& e : entries) e.segmenter->Segment(image);  // Warm-up.
  const double load_start = asbuilt::bench::LoadAverage1();
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::vector<double>> ratios(entries.size());
  for (int r = 0; r < repeats; ++r) {
    std::vector<double> t(entries.size());
    for (std::size_t k = 0; k < entries.size(); ++k) {
      const std::size_t i = (k + static_cast<std::size_t>(r)) % entries.size();
      const auto t0 = std::chrono::steady_clock::now();
      entries[i].segmenter->Segment(image);
      t[i] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      entries[i].seconds.push_back(t[i]);
    }
    for (std::size_t i = 0; i < entries.size(); ++i) ratios[i].push_back(t[i] / t[reference]);
  }
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::string md = fmt::format(
      "## segmenters — seconds to label one 640×480 view, each model\n\n"
      "Issue 43's speed target: the default model at most as slow as the renders-only SegFormer-B0 on 2 cores. "
      "Each model labels blender-rooms-public p01 frame 000 (640×480) through `LoadSegmenter` at the view's own "
      "size, as `asbuilt survey` reads a 640×480 view; {} repetitions, the models taking turns in a rotating "
      "order within each. Ratio = the model's time / B0's in the same repetition, median over repetitions "
      "(≤ 1.0: no slower). Measured {} on {} hardware threads, load average {:.1f} at start; {:.0f} s.\n\n"
      "| model | what | median | ratio to `renders` (median pair) |\n|---|---|---|---|\n",
      repeats, asbuilt::bench::Today(), std::thread::hardware_concurrency(), load_start, wall_s);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    md += fmt::format("| `{}` | {} | {:.3f} s | {:.2f} |\n", entries[i].name, entries[i].what,
                      Median(entries[i].seconds), Median(ratios[i]));
  }
  asbuilt::WriteFileAtomic(results, md + "\n");
  std::fprintf(stderr, "%s", md.c_str());
  return 0;
}
