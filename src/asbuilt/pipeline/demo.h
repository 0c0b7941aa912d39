#ifndef ASBUILT_PIPELINE_DEMO_H_
#define ASBUILT_PIPELINE_DEMO_H_

// `asbuilt demo`: the whole method on a built-in example, with no data, no
// GPU and no network: a sentence → scene → rendered turn-in-place stereo
// capture → survey with the shipped model → measured vs true sizes.

#include <filesystem>
#include <string>

#include "asbuilt/pipeline/survey.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

inline constexpr char kDemoSentence[] =
    "a 6 by 8 m classroom, 3 m high, with a 1 m wide door on the east wall and two 1.5 m windows "
    "on the north wall";

struct DemoOptions {
  std::string sentence = kDemoSentence;
  int views = 12;  // Turn-in-place views (30° steps).
  int width_px = 640;
  int height_px = 480;
  int samples_per_pixel = 4;  // Renderer samples; more = less noise, slower.
  std::uint64_t seed = 7;
  SurveyOptions survey;  // Model, labels source, …

  void Check() const;
};

struct DemoSummary {
  std::filesystem::path out_dir;
  std::string scene_brief;
  double render_seconds = 0.0;
  SurveySummary survey;
  std::string comparison;  // Measured vs true sizes, a text table.
  std::string BriefReport() const;
};

// Writes scene.json, capture/ (with truth.json) and survey/ under out_dir.
DemoSummary RunDemo(const std::filesystem::path& out_dir, const DemoOptions& options = {},
                    const ProgressCallback& progress = {});

// A text table of measured vs true wall lengths, opening widths and area,
// from a score of a measured plan against `truth`.
std::string ComparisonTable(const Plan& truth, const PlanScore& score);

}  // namespace asbuilt

#endif  // ASBUILT_PIPELINE_DEMO_H_
