// bench_zind: the shipped segmenter on real photographs (issue 21). Every
// primary panorama of the ZInD sample tour (../shared/data/zind_sample_tour,
// read at run time: ZInD is for academic use only, a test set, never
// training data, and nothing derived from it is committed) turned into 12
// level 640×480 views (fx = fy = 400, yaw step 30°), labelled from its
// annotated layout and segmented at 640×480 (pipeline/zind_eval.h). Writes
// the figures to bench/results/zind.md; the contact sheets and report.html go
// under the build folder (bench/zind/), never into the repository.
//
//   bench_zind [RESULTS.md]
//   env ASBUILT_BENCH_ZIND_PANORAMAS (default all), ASBUILT_BENCH_ZIND_MODEL (default the shipped model).

#include <sys/resource.h>

#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <string>
#include <thread>

#include <fmt/format.h>

#include "asbuilt/formats/zind.h"
#include "asbuilt/pipeline/survey.h"
#include "asbuilt/pipeline/zind_eval.h"
#include "asbuilt/seg/segmenter.h"
#include "bench/bench_util.h"

namespace {}  // namespace

int main(int argc, char** argv) {
  using namespace asbuilt;
  using namespace asbuilt::bench;
  namespace fs = std::filesystem;
  const std::string results = ResultsPath(argc, argv, "zind");
  const fs::path tour_dir = fs::path(ASBUILT_SHARED_DATA_DIR) / "zind_sample_tour";
  const char* model_env = std::getenv("ASBUILT_BENCH_ZIND_MODEL");
  const fs::path model = model_env != nullptr ? fs::path(model_env) : DefaultModelPath();
  if (!fs::exists(tour_dir / "zind_data.json")) {
    std::fprintf(stderr, "bench_zind: %s not present; %s left as it was\n", tour_dir.c_str(), results.c_str());
    return 0;
  }
  if (!SegmenterAvailable() || !fs::exists(model)) {
    std::fprintf(stderr, "bench_zind: no LibTorch in this build or no model %s; %s left as it was\n", model.c_str(),
                 results.c_str());
    return 0;
  }
  const fs::path out = fs::path(ASBUILT_BINARY_DIR) / "bench" / "zind";
  ZindEvalOptions options;
  options.max_panoramas = EnvPositiveInt("ASBUILT_BENCH_ZIND_PANORAMAS", 0);
  const SegmentOptions segment{.scale_width_px = options.turn.width_px, .scale_height_px = options.turn.height_px};
  std::unique_ptr<Segmenter> segmenter = LoadSegmenter(model, segment);
  options.segmenter_name = fmt::format("`{}` ({}, whole-image inference at {}x{})", model.filename().string(),
                                       segmenter->info().ToString(), segment.scale_width_px, segment.scale_height_px);
  const ZindTour tour = ReadZindTour(tour_dir);
  double load[1] = {0};
  const bool have_load = ::getloadavg(load, 1) == 1;
  ZindEvalSummary s = EvaluateOnZind(*segmenter, tour, out, options);
  std::fprintf(stderr, "bench_zind: %s\n", s.BriefReport().c_str());
  s.tour = "../shared/data/zind_sample_tour";  // As the repository sees it, not this machine's path.

  std::string md = "## segmenter on real photos: ZInD sample tour (bench_zind)\n\n";
  md += fmt::format(
      "`asbuilt eval zind --model models/{} --zind ../shared/data/zind_sample_tour` (issue 21): each view labelled "
      "from its panorama's annotated layout (docs/seg.md \"Real photos\"). Measured {} on {} hardware threads{}. "
      "Contact sheets: `{}/report.html` (build folder, never committed).\n\n",
      model.filename().string(), Today(), std::thread::hardware_concurrency(),
      have_load ? fmt::format(", load average {:.1f} at start", load[0]) : std::string(),
      fs::relative(out, ASBUILT_SOURCE_DIR).string());
  md += s.ToMarkdown();
  md += "\n";
  WriteSection(results, md);
  return 0;
}
