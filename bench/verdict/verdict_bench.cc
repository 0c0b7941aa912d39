// bench_verdict: does the verdict (plan/verdict.h, issue 42) tell good plans
// from bad ones on rooms with truth that ZInD is not (bench_pano_survey has
// ZInD's): the three hand-annotated CC0 photos of real rooms (the shipped
// model, the `real` model and the ADE20K teacher zero-shot), the rooms
// Blender rendered (both models and their exact labels), and the synthetic rooms with
// faults put in of pipeline/verdict_survey_test.cc are its tests.

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/seg/segmenter.h"
#include "bench/bench_util.h"
#include "bench/verdict_stats.h"

namespace fs = std::filesystem;
using namespace asbuilt;
using namespace asbuilt::bench;

int main(int argc, char** argv) {
  const std::string results = ResultsPath(argc, argv, "verdict");
  const fs::path data = ASBUILT_SHARED_DATA_DIR;
  const fs::path out = fs::path(ASBUILT_BINARY_DIR) / "bench" / "verdict";
  const fs::path teacher = data / "ade20k-teachers" / "deeplabv3_mnv2_ade20k32_uint8.tflite";
  if (!SegmenterAvailable() || !fs::exists(DefaultModelPath())) {
    std::fprintf(stderr, "bench_verdict: no segmenter in this build; %s left as it was\n", results.c_str());
    return 0;
  }
  const fs::path real = ModelPathFor("real");
  const bool with_real = fs::exists(real) && !fs::equivalent(real, DefaultModelPath());
  const auto start = std::chrono::steady_clock::now();
  auto survey = [&](const fs::path& capture, const std::string& name, SurveyOptions options) {
    options.report_frames = 4;
    try {
      const SurveySummary s = RunSurvey(capture, out / name, options).summary;
      std::fprintf(stderr, "bench_verdict: %s: %s; verdict %s\n", name.c_str(), s.BriefReport().c_str(),
                   s.verdict.BriefReport().c_str());
      return SampleOf(name, s);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "bench_verdict: %s: %s\n", name.c_str(), e.what());
      return VerdictSample{.name = name};
    }
  };
  std::vector<VerdictSample> cc0, blender;
  for (const char* room : {"comfy_cafe", "colorful_studio", "pine_attic"}) {
    const fs::path capture = data / "cc0-panoramas" / "annotated" / room / "capture.json";
    if (!fs::exists(capture)) continue;
    cc0.push_back(survey(capture, fmt::format("cc0_{}_default", room), {}));
    if (with_real) cc0.push_back(survey(capture, fmt::format("cc0_{}_real", room), {.model_path = real}));
    if (fs::exists(teacher))
      cc0.push_back(survey(capture, fmt::format("cc0_{}_teacher", room), {.model_path = teacher}));
  }
  for (const char* room : {"p01_rect_1door_2win", "p02_L_shape"}) {
    const fs::path capture = data / "blender-rooms-public" / room / "capture.json";
    if (!fs::exists(capture)) continue;
    blender.push_back(survey(capture, fmt::format("blender_{}_default", room), {}));
    if (with_real) blender.push_back(survey(capture, fmt::format("blender_{}_real", room), {.model_path = real}));
    blender.push_back(survey(capture, fmt::format("blender_{}_exact_labels", room), {.use_capture_labels = true}));
  }
  std::vector<VerdictSample> all = cc0;
  all.insert(all.end(), blender.begin(), blender.end());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::string md = "## the verdict on plans with truth (bench_verdict)\n\n";
  md += fmt::format(
      "Issue 42. Each plan's verdict (`good` / `check` / `unreliable`, plan/verdict.h, docs/verdict.md) against its "
      "room IoU with the truth. Sets: the three CC0 photos of real rooms with hand-made truth "
      "(`../shared/data/cc0-panoramas/annotated`, tone-mapped, camera height 1.6 m as assumed there), surveyed with "
      "the shipped model, with `--model real` and with the ADE20K teacher zero-shot; the two Blender-rendered rooms "
      "of `../shared/data/blender-rooms-public` (stereo), with both models and with their exact labels. ZInD's "
      "figures are in the pano_survey section. Measured {} on {} hardware threads, {:.0f} s.\n\n",
      Today(), std::thread::hardware_concurrency(), seconds);
  md += VerdictTableHeader();
  md += VerdictRow("CC0 real rooms", cc0);
  md += VerdictRow("Blender rooms", blender);
  md += VerdictRow("all of the above", all) + "\n";
  md += VerdictList(all) + "\n";
  WriteSection(results, md);
  return 0;
}
