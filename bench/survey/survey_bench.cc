// bench_survey: how long `asbuilt survey` takes on a 12-view 640×480 capture
// (issue 9: ≤ 15 s on 2 cores), split by stage. Renders the demo classroom
// once (kept under the build folder, resumable), then times RunSurvey with
// the capture's exact labels, with the same capture declared unrectified (so
// the rectify stage runs on an ideal calibration), and with the shipped
// segmentation model. Writes its section into bench/results/survey.md
// between <!-- bench_survey --> markers, keeping the hand-written accuracy
// figures around it.
//
//   bench_survey [RESULTS.md]
//   env ASBUILT_BENCH_REPEATS (default 3; runs with the model: default 1,
//   ASBUILT_BENCH_MODEL_REPEATS — each is a few times slower).

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/formats/capture.h"
#include "asbuilt/pipeline/demo.h"
#include "asbuilt/pipeline/survey.h"
#include "asbuilt/render/capture_render.h"
#include "asbuilt/scene/scene_text.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/stereo/rectify.h"
#include "bench/bench_util.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

double CpuSeconds() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec + 1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// The demo's classroom, 12 turn-in-place views, 640×480, 4 spp.
fs::path RenderOnce(const fs::path& dir, double& render_seconds) {
  const fs::path capture = dir / "capture.json";
  if (fs::exists(capture)) return capture;
  SceneTextResult text = SceneFromText(kDemoSentence, {.seed = 7});
  Scene scene = text.scene;
  scene.seed = 7;
  CaptureRenderOptions render;
  render.views = 12;
  render.width_px = 640;
  render.height_px = 480;
  render.render.samples_per_pixel = 4;
  render.render.seed = 7;
  auto start = std::chrono::steady_clock::now();
  RenderCapture(scene, dir, render);
  render_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return capture;
}

// The same capture declared unrectified, with an ideal calibration (no
// distortion, parallel axes): survey then runs its rectify stage for real.
fs::path UnrectifiedTwin(const fs::path& capture_json) {
  Capture capture = ReadCapture(capture_json);
  const CaptureCamera& cam = capture.camera;
  StereoCalibration c;
  c.image_size = cv::Size(cam.width, cam.height);
  c.K1 = (cv::Mat_<double>(3, 3) << cam.fx, 0, cam.cx, 0, cam.fy, cam.cy, 0, 0, 1);
  c.K2 = c.K1.clone();
  c.D1 = cv::Mat::zeros(1, 5, CV_64F);
  c.D2 = cv::Mat::zeros(1, 5, CV_64F);
  c.R = cv::Mat::eye(3, 3, CV_64F);
  c.T = (cv::Mat_<double>(3, 1) << -cam.baseline_m, 0, 0);
  const fs::path dir = capture_json.parent_path();
  WriteCalibration(c, dir / "ideal_calibration.yml");
  capture.rectified = false;
  capture.calibration = "ideal_calibration.yml";
  const fs::path out = dir / "capture_unrectified.json";
  WriteCapture(capture, out);
  return out;
}

struct Mode {
  std::string name;
  fs::path capture;
  SurveyOptions options;
  bool model = false;
};

struct Runs {
  std::vector<std::map<std::string, double>> stages;  // Per run: stage → s.
  std::vector<double> wall_s, cpu_s;
  std::string brief;
};

Runs Time(const Mode& mode, int repeats, const fs::path& out_dir) {
  Runs runs;
  for (int i = 0; i < repeats; ++i) {
    fs::remove_all(out_dir);
    const double cpu0 = CpuSeconds();
    const auto start = std::chrono::steady_clock::now();
    SurveyResult r = RunSurvey(mode.capture, out_dir, mode.options);
    r.summary.out_dir.clear();  // The brief without the temporary folder.
    runs.wall_s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    runs.cpu_s.push_back(CpuSeconds() - cpu0);
    std::map<std::string, double> stages;
    for (const StageTiming& s : r.summary.stages) stages[s.stage] += s.seconds;
    // The report is written after the summary's stage list is closed.
    double listed = 0;
    for (const auto& [_, s] : stages) listed += s;
    stages["report (html)"] = std::max(0.0, runs.wall_s.back() - listed);
    runs.stages.push_back(stages);
    runs.brief = r.summary.BriefReport();
    std::fprintf(stderr, "  %s run %d: %.2f s wall, %.2f s CPU — %s\n", mode.name.c_str(), i + 1, runs.wall_s.back(),
                 runs.cpu_s.back(), runs.brief.c_str());
  }
  return runs;
}

}  // namespace
}  // namespace asbuilt

int main(int argc, char** argv) {
  using namespace asbuilt;
  using namespace asbuilt::bench;
  const std::string results = ResultsPath(argc, argv, "survey");
  const int repeats = EnvPositiveInt("ASBUILT_BENCH_REPEATS", 3);
  const int model_repeats = EnvPositiveInt("ASBUILT_BENCH_MODEL_REPEATS", 1);
  const fs::path dir = fs::path(ASBUILT_BINARY_DIR) / "bench" / "survey_capture";
  const fs::path out = fs::temp_directory_path() / fmt::format("asbuilt_bench_survey_{}", ::getpid());
  const double load_start = asbuilt::bench::LoadAverage1();

  double render_seconds = -1;
  const fs::path capture = RenderOnce(dir, render_seconds);
  const fs::path unrectified = UnrectifiedTwin(capture);

  std::vector<Mode> modes = {
      {"exact labels", capture, {.use_capture_labels = true}},
      {"exact labels, unrectified (rectify runs)", unrectified, {.use_capture_labels = true}},
  };
  const bool model = SegmenterAvailable() && fs::exists(DefaultModelPath());
  if (model) modes.push_back({"shipped model", capture, {}, true});
  std::vector<Runs> runs;
  for (const Mode& m : modes) runs.push_back(Time(m, m.model ? model_repeats : repeats, out));
  fs::remove_all(out);

  // The segment stage two ways, same run: left and right as two forward
  // passes, or as one batch of two.
  std::string seg_line;
  if (model) {
    const Capture c = ReadCapture(capture);
    std::unique_ptr<Segmenter> segmenter = LoadSegmenter(DefaultModelPath());
    std::vector<double> two_calls, one_batch;
    constexpr std::size_t kFrames = 4;
    for (int rep = 0; rep < model_repeats; ++rep) {
      for (std::size_t i = 0; i < std::min(kFrames, c.frames.size()); ++i) {
        const CaptureFrame& f = c.frames[i];
        const cv::Mat left = cv::imread(c.Resolve(f.left).string(), cv::IMREAD_COLOR);
        const cv::Mat right = cv::imread(c.Resolve(f.right).string(), cv::IMREAD_COLOR);
        two_calls.push_back(MedianSeconds(1, [&] {
          segmenter->Segment(left);
          segmenter->Segment(right);
        }));
        one_batch.push_back(MedianSeconds(1, [&] { segmenter->SegmentBatch({left, right}); }));
      }
    }
    seg_line = fmt::format(
        "- segmenting one frame's two views ({} frames × {} repeats, interleaved): two forward passes {:.3f} s, "
        "one batch of two {:.3f} s (ratio {:.2f})\n",
        std::min(kFrames, c.frames.size()), model_repeats, Median(two_calls), Median(one_batch),
        Median(one_batch) / Median(two_calls));
  }

  // Stages in pipeline order (as RunSurvey lists them), then the rest.
  std::vector<std::string> order = {"read capture", "load model",    "read images",      "rectify",
                                    "segment",      "disparity",     "corners + points", "report pictures",
                                    "plan",         "write outputs", "report (html)"};
  for (const Runs& r : runs)
    for (const auto& [s, _] : r.stages.front())
      if (std::find(order.begin(), order.end(), s) == order.end()) order.insert(order.end() - 1, s);

  std::string md = "### speed: a 12-view 640×480 survey (bench_survey)\n\n";
  md += fmt::format(
      "`RunSurvey` on the demo classroom (\"{}\"), rendered once by asbuilt (12 turn-in-place views, "
      "640×480, 4 spp). Median of {} runs per column ({} with the model), seconds; each run writes every output "
      "(plan.json/svg/dxf/pdf/png, points, report.html). {} hardware threads, OpenCV {} threads, load average "
      "{:.1f} at start and {:.1f} at the end (other jobs share the machine: the same-run ratios are the "
      "figures to compare). Target (issue 9): ≤ 15 s on 2 cores with the shipped model.\n\n",
      kDemoSentence, repeats, model_repeats, std::thread::hardware_concurrency(), cv::getNumThreads(), load_start,
      asbuilt::bench::LoadAverage1());
  md += "| stage |";
  for (const Mode& m : modes) md += " " + m.name + " |";
  md += "\n|---|";
  for (std::size_t i = 0; i < modes.size(); ++i) md += "---:|";
  md += "\n";
  for (const std::string& s : order) {
    bool any = false;
    std::string row = "| " + s + " |";
    for (const Runs& r : runs) {
      std::vector<double> v;
      for (const auto& stages : r.stages)
        if (auto it = stages.find(s); it != stages.end()) v.push_back(it->second);
      any |= !v.empty();
      row += v.empty() ? " – |" : fmt::format(" {:.2f} |", Median(v));
    }
    if (any) md += row + "\n";
  }
  md += "| **total (wall)** |";
  for (const Runs& r : runs) md += fmt::format(" **{:.2f}** |", Median(r.wall_s));
  md += "\n| CPU time (user+sys) |";
  for (const Runs& r : runs) md += fmt::format(" {:.2f} |", Median(r.cpu_s));
  md += "\n| ratio to exact labels |";
  for (const Runs& r : runs) md += fmt::format(" {:.2f}× |", Median(r.wall_s) / Median(runs[0].wall_s));
  md += "\n\n";
  if (!model) md += "The shipped model column is missing: this build has no LibTorch or no models/ file.\n\n";
  for (std::size_t i = 0; i < modes.size(); ++i) md += fmt::format("- {}: {}\n", modes[i].name, runs[i].brief);
  md += seg_line;
  if (render_seconds >= 0)
    md += fmt::format("- rendering the capture (once, not timed above): {:.1f} s\n", render_seconds);
  md += "\n";
  // Replace only this program's section of the file.
  constexpr char kBegin[] = "<!-- bench_survey: written by bench/survey, edits are lost -->\n";
  constexpr char kEnd[] = "<!-- /bench_survey -->\n";
  std::string file = fs::exists(results) ? ReadFile(results) : std::string("## survey\n\n");
  const std::size_t b = file.find(kBegin), e = file.find(kEnd);
  const std::string section = kBegin + md + kEnd;
  if (b != std::string::npos && e != std::string::npos && e > b) {
    file.replace(b, e + std::string(kEnd).size() - b, section);
  } else {
    if (!file.empty() && file.back() != '\n') file += "\n";
    file += "\n" + section;
  }
  WriteSection(results, file);
  return 0;
}
