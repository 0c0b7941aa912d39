#include "asbuilt/seg/learn.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/dataset/level_views.h"
#include "asbuilt/dataset/mix.h"
#include "asbuilt/seg/evaluate.h"
#include "asbuilt/seg/seg_data.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/seg/train.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

std::string Fmt(double x) { return std::isnan(x) ? "–" : fmt::format("{:.3f}", x); }
std::string Change(double before, double after) {
  return std::isnan(before) || std::isnan(after) ? "–" : fmt::format("{:+.3f}", after - before);
}

// A labelled set as a review save writes it: images/ and labels/.
bool IsExample(const fs::path& dir) { return fs::is_directory(dir / "images") && fs::is_directory(dir / "labels"); }

// The training folder of one survey folder, or empty.
fs::path ExampleOfSurvey(const fs::path& survey) {
  const fs::path training = survey / "review" / "training";
  return IsExample(training) ? training : fs::path();
}

// Each example as level views (dataset/level_views.h: a panorama's tall views
// cut to the renders' aspect and scale) in ROOT/NAME, NAME its survey's, so
// that ROOT read as one dataset tree keeps each room one room.
void AsLevelViews(const std::vector<fs::path>& examples, const fs::path& root) {
  fs::remove_all(root);
  std::vector<fs::path> written;
  for (const fs::path& e : examples) {
    std::string name = RoomNameOfFolder(e);
    if (name.empty()) name = "room";
    fs::path dir = root / name;
    for (int k = 2; std::find(written.begin(), written.end(), dir) != written.end(); ++k) {
      dir = root / fmt::format("{}-{}", name, k);
    }
    CutLevelViews(e, dir);
    written.push_back(dir);
  }
}

}  // namespace

void LearnOptions::Check() const {
  CheckArgument(!reviews.empty(), "LearnOptions.reviews is empty: name the corrected surveys (REVIEWS...)");
  CheckArgument(!model.empty(), "LearnOptions.model is empty: name the model to improve (--model)");
  CheckArgument(!out_dir.empty(), "LearnOptions.out_dir is empty: give -o");
  const auto mix = MixConfig::Parse(config);
  CheckArgument(mix.has_value(), fmt::format("LearnOptions.config = '{}': not R100 or RSxxyy (xx + yy = 100)", config));
  CheckArgument(mix->real_percent > 0,
                fmt::format("LearnOptions.config = {}: learning from corrections needs real rooms in the mix", config));
  CheckArgument(mix->synthetic_percent == 0 || !synthetic_dir.empty(),
                fmt::format("LearnOptions.config = {} mixes in renders: give them with --synthetic DIR (made by "
                            "`asbuilt dataset synth`), or use --config R100",
                            config));
  CheckArgument(test_fraction > 0 && test_fraction < 1,
                fmt::format("LearnOptions.test_fraction = {}, must be in (0, 1)", test_fraction));
  CheckArgument(epochs >= 0 && steps_per_epoch >= 0 && threads >= 0,
                "LearnOptions: epochs, steps_per_epoch and threads must be >= 0");
}

std::vector<fs::path> FindReviewExamples(const std::vector<fs::path>& paths) {
  std::vector<fs::path> out;
  for (const fs::path& p : paths) {
    if (!fs::is_directory(p)) {
      throw InputError(p.string(), "", "not found (give a survey folder whose review was saved)");
    }
    if (IsExample(p)) {
      out.push_back(p);
      continue;
    }
    if (fs::path e = ExampleOfSurvey(p); !e.empty()) {
      out.push_back(e);
      continue;
    }
    if (fs::exists(p / "review" / "corrections.json")) {
      throw InputError(p.string(), "review/training",
                       fmt::format("the review was saved before training examples were written: run `asbuilt review "
                                   "{} --export-training`",
                                   p.string()));
    }
    if (fs::exists(p / "summary.json")) {
      throw InputError(
          p.string(), "review/corrections.json",
          fmt::format("no saved review: correct the survey with `asbuilt review {}` and save", p.string()));
    }
    // A folder of surveys.
    std::vector<fs::path> found;
    for (const auto& entry : fs::directory_iterator(p)) {
      if (!entry.is_directory()) continue;
      if (fs::path e = ExampleOfSurvey(entry.path()); !e.empty()) found.push_back(e);
    }
    if (found.empty()) {
      throw InputError(p.string(), "", "holds no survey with a saved review (OUT/review/training/)");
    }
    std::sort(found.begin(), found.end());
    out.insert(out.end(), found.begin(), found.end());
  }
  return out;
}

std::string LearnSummary::ToMarkdown() const {
  std::string s =
      fmt::format("Held-out rooms: {} views; trained on {} + {} (val) pairs from {} corrected rooms and renders.\n\n",
                  test_pairs, train_pairs, val_pairs, examples.size());
  s += "| class | IoU before | IoU after | change |\n|---|---|---|---|\n";
  for (std::size_t c = 0; c < before.classes.size() && c < after.classes.size(); ++c) {
    s += fmt::format("| {} | {} | {} | {} |\n", before.classes[c].name, Fmt(before.classes[c].iou),
                     Fmt(after.classes[c].iou), Change(before.classes[c].iou, after.classes[c].iou));
  }
  s += fmt::format("| **mIoU** | {} | {} | {} |\n\n", Fmt(before.miou), Fmt(after.miou),
                   Change(before.miou, after.miou));
  s += improved ? "The new model is better on the held-out rooms: written to model.pt.\n"
                : "The new model is not better on the held-out rooms: no model.pt written; keep the old one.\n";
  return s;
}

std::string LearnSummary::BriefReport() const {
  return fmt::format("held-out rooms ({} views): mIoU {} → {} ({}); {}; {:.0f} s", test_pairs, Fmt(before.miou),
                     Fmt(after.miou), Change(before.miou, after.miou),
                     improved ? "new model written" : "not better, old model kept", wall_s);
}

LearnSummary LearnFromReviews(const LearnOptions& options, const ProgressCallback& progress, std::stop_token stop) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  LearnSummary summary;
  summary.examples = FindReviewExamples(options.reviews);
  fs::path held_out;
  if (!options.hold_out.empty()) {
    held_out = FindReviewExamples({options.hold_out}).at(0);
    std::erase_if(summary.examples, [&](const fs::path& e) { return fs::equivalent(e, held_out); });
    if (summary.examples.empty()) {
      throw InputError(options.hold_out.string(), "", "is the only review given: none left to learn from");
    }
  }
  // Read the model first: a file that is not a model fails before any work.
  TrainOptions train = FinetuneOptions(options.model, ReadSegmenterInfo(options.model));
  fs::create_directories(options.out_dir);

  // 1. The rooms as level views, and the mix, split by room.
  const fs::path views = options.out_dir / "views", held_out_views = options.out_dir / "test" / "views";
  AsLevelViews(summary.examples, views);
  if (!held_out.empty()) AsLevelViews({held_out}, held_out_views);
  const fs::path manifest = options.out_dir / "mix.json";
  MixOptions mix{.config = options.config, .test_fraction = options.test_fraction, .seed = options.seed};
  MixSummary mixed = MixDataset(mix, {views}, options.synthetic_dir, held_out.empty() ? fs::path() : held_out_views,
                                manifest, progress);
  spdlog::info("learn: {}", mixed.BriefReport());
  const SegDataSplit split = SplitFromManifest(manifest);
  summary.train_pairs = static_cast<std::int64_t>(split.train.size());
  summary.val_pairs = static_cast<std::int64_t>(split.val.size());
  summary.test_pairs = static_cast<std::int64_t>(split.test.size());

  // 2. Fine-tune.
  train.manifest = manifest;
  train.out_dir = options.out_dir / "train";
  train.seed = options.seed;
  train.threads = options.threads;
  if (options.epochs > 0) train.epochs = options.epochs;
  if (options.steps_per_epoch > 0) train.steps_per_epoch = options.steps_per_epoch;
  const TrainSummary trained = TrainSegmenter(train, progress, stop);
  summary.train_s = trained.wall_s;
  if (trained.stopped) throw Error("learn: stopped during fine-tuning; run it again to resume");

  // 3. Old against new on the held-out rooms.
  summary.before = EvaluateSegmentation(*LoadSegmenter(options.model), split.test, {}, progress, stop);
  summary.after = EvaluateSegmentation(*LoadSegmenter(train.out_dir / "best.pt"), split.test, {}, progress, stop);
  summary.improved = summary.after.miou > summary.before.miou;
  if (summary.improved) {
    WriteFileAtomic(options.out_dir / "model.pt", ReadFile(train.out_dir / "best.pt"));
  } else {
    fs::remove(options.out_dir / "model.pt");  // An earlier run's, no longer what this run says.
  }
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  nlohmann::json report = {
      {"model", options.model.string()},  {"examples", nlohmann::json::array()}, {"hold_out", held_out.string()},
      {"mix", mixed.BriefReport()},       {"train_pairs", summary.train_pairs},  {"val_pairs", summary.val_pairs},
      {"test_pairs", summary.test_pairs}, {"before", summary.before.ToJson()},   {"after", summary.after.ToJson()},
      {"improved", summary.improved},     {"train_s", summary.train_s},          {"wall_s", summary.wall_s}};
  for (const fs::path& e : summary.examples) report["examples"].push_back(e.string());
  WriteFileAtomic(options.out_dir / "report.json", report.dump(2) + "\n");
  WriteFileAtomic(options.out_dir / "report.md",
                  fmt::format("# asbuilt learn\n\nModel: `{}`. Mix: {}.\n\n{}", options.model.string(),
                              mixed.BriefReport(), summary.ToMarkdown()));
  return summary;
}

}  // namespace asbuilt
