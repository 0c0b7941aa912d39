#include "asbuilt/seg/experiment.h"

#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <spdlog/spdlog.h>

#include "asbuilt/dataset/mix.h"
#include "asbuilt/dataset/pairs.h"
#include "asbuilt/seg/evaluate.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

std::string Fmt(double x) { return std::isnan(x) ? "nan" : fmt::format("{:.4f}", x); }

// Grouped bars: four metrics per config.
void WritePlot(const fs::path& path, const std::vector<RatioExperimentRow>& rows) {
  const int W = 720, H = 400, L = 50, B = 60, T = 40;
  cv::Mat img(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
  const cv::Scalar colours[4] = {{200, 80, 0}, {0, 160, 0}, {0, 120, 230}, {160, 0, 160}};
  const char* names[4] = {"mIoU", "mFscore", "mPrecision", "mRecall"};
  const int n = static_cast<int>(rows.size());
  const double group_w = n > 0 ? static_cast<double>(W - L - 20) / n : 1;
  cv::line(img, {L, H - B}, {W - 10, H - B}, cv::Scalar(0, 0, 0));
  cv::line(img, {L, T}, {L, H - B}, cv::Scalar(0, 0, 0));
  for (int t = 0; t <= 4; ++t) {
    int y = H - B - t * (H - B - T) / 4;
    cv::putText(img, fmt::format("{:.2f}", t / 4.0), {5, y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0));
  }
  for (int i = 0; i < n; ++i) {
    const auto& m = rows[i].test;
    const double v[4] = {m.miou, m.mfscore, m.mprecision, m.mrecall};
    for (int k = 0; k < 4; ++k) {
      if (std::isnan(v[k])) continue;
      int x0 = L + static_cast<int>(i * group_w + 10 + k * (group_w - 20) / 4);
      int x1 = x0 + static_cast<int>((group_w - 20) / 4) - 2;
      int y = H - B - static_cast<int>(v[k] * (H - B - T));
      cv::rectangle(img, {x0, y}, {x1, H - B}, colours[k], cv::FILLED);
    }
    cv::putText(img, rows[i].config, {L + static_cast<int>(i * group_w + group_w / 2 - 25), H - B + 20},
                cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  cv::putText(img, "score on the test set (higher is better)", {L, H - 15}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
              cv::Scalar(80, 80, 80), 1, cv::LINE_AA);
  for (int k = 0; k < 4; ++k) {
    cv::rectangle(img, {L + 10 + k * 150, 10}, {L + 22 + k * 150, 22}, colours[k], cv::FILLED);
    cv::putText(img, names[k], {L + 26 + k * 150, 21}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1,
                cv::LINE_AA);
  }
  AtomicFile out(path);
  if (!cv::imwrite(out.temp_path().string(), img)) throw Error(path.string() + ": cannot write plot");
  out.Commit();
}

}  // namespace

void RatioExperimentOptions::Check() const {
  CheckArgument(!out_dir.empty(), "RatioExperimentOptions.out_dir is empty: give -o");
  CheckArgument(!configs.empty(), "RatioExperimentOptions.configs is empty");
  for (const std::string& c : configs) {
    auto parsed = MixConfig::Parse(c);
    CheckArgument(parsed.has_value(), fmt::format("RatioExperimentOptions.configs: '{}' is not R100, S100 or RSxxyy "
                                                  "(xx + yy = 100)",
                                                  c));
    CheckArgument(parsed->real_percent == 0 || !real_dir.empty(),
                  fmt::format("config {} needs real pairs: give --real", c));
    CheckArgument(parsed->synthetic_percent == 0 || !synthetic_dir.empty(),
                  fmt::format("config {} needs synthetic pairs: give --synthetic", c));
  }
  CheckArgument(!real_dir.empty() || !real_test_dir.empty(),
                "RatioExperimentOptions: the test set is real: give --real (or --real-test)");
  CheckArgument(total >= 0, fmt::format("RatioExperimentOptions.total = {}, must be >= 0", total));
  for (const auto& dir : extra_test_dirs) {
    CheckArgument(!dir.empty(), "RatioExperimentOptions.extra_test_dirs: an empty path");
  }
}

std::string RatioExperimentSummary::ToMarkdown() const {
  auto table = [&](auto metrics_of) {
    std::string t = "| config | train | val | test | mIoU | mFscore | mPrecision | mRecall |\n";
    t += "|---|---|---|---|---|---|---|---|\n";
    for (const auto& r : rows) {
      const SegmentationMetrics& m = metrics_of(r);
      t += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} |\n", r.config, r.train_pairs, r.val_pairs, m.images,
                       Fmt(m.miou), Fmt(m.mfscore), Fmt(m.mprecision), Fmt(m.mrecall));
    }
    return t;
  };
  std::string s = table([](const RatioExperimentRow& r) -> const SegmentationMetrics& { return r.test; });
  for (size_t e = 0; e < extra_names.size(); ++e) {
    s += fmt::format("\nAlso scored on `{}`:\n\n", extra_names[e]);
    s += table([e](const RatioExperimentRow& r) -> const SegmentationMetrics& { return r.extra.at(e); });
  }
  return s;
}

std::string RatioExperimentSummary::BriefReport() const {
  std::string s = fmt::format("{} config{} in {:.0f} s:", rows.size(), rows.size() == 1 ? "" : "s", wall_s);
  for (const auto& r : rows) s += fmt::format(" {} mIoU {}", r.config, Fmt(r.test.miou));
  return s;
}

RatioExperimentSummary RunRatioExperiment(const RatioExperimentOptions& options, const ProgressCallback& progress,
                                          std::stop_token stop) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  RatioExperimentSummary summary;
  // Extra test sets are listed once, up front: a bad folder fails before any training.
  std::vector<std::vector<SegSample>> extra_sets;
  for (const fs::path& dir : options.extra_test_dirs) {
    std::vector<SegSample> set;
    for (const ImagePair& p : ListDatasetPairs(dir).pairs) set.push_back({p.name, p.image, p.label});
    if (set.empty()) throw InputError(dir.string(), "", "no (image, label) pairs for the extra test set");
    extra_sets.push_back(std::move(set));
    summary.extra_names.push_back(dir.filename().empty() ? dir.parent_path().filename().string()
                                                         : dir.filename().string());
  }
  nlohmann::json rows = nlohmann::json::array();
  for (const std::string& name : options.configs) {
    if (stop.stop_requested()) break;
    const std::string config = MixConfig::Parse(name)->Name();
    const fs::path dir = options.out_dir / config;
    MixOptions mix{.config = config, .total = options.total, .seed = options.seed};
    MixSummary mixed = MixDataset(mix, options.real_dir, options.synthetic_dir, options.real_test_dir,
                                  dir / "manifest.json", progress);
    spdlog::info("experiment: {}", mixed.BriefReport());
    TrainOptions train = options.train;
    train.manifest = dir / "manifest.json";
    train.images_dir.clear();
    train.labels_dir.clear();
    train.out_dir = dir / "run";
    TrainSummary trained = TrainSegmenter(train, progress, stop);
    if (trained.stopped) break;
    spdlog::info("experiment: {}: {}", config, trained.BriefReport());
    auto segmenter = LoadSegmenter(dir / "run" / "best.pt");
    SegDataSplit split = SplitFromManifest(dir / "manifest.json");
    RatioExperimentRow row;
    row.config = config;
    row.train_pairs = static_cast<int>(split.train.size());
    row.val_pairs = static_cast<int>(split.val.size());
    row.test_pairs = static_cast<int>(split.test.size());
    row.real_train_val = static_cast<int>(mixed.real_used);
    row.synthetic_train_val = static_cast<int>(mixed.synthetic_used);
    row.best_val_miou = trained.best_miou;
    row.best_epoch = trained.best_epoch;
    row.train_wall_s = trained.wall_s;
    row.test = EvaluateSegmentation(*segmenter, split.test, {}, progress, stop);
    WriteFileAtomic(dir / "test_metrics.json", row.test.ToJson().dump(2) + "\n");
    nlohmann::json j = row.test.ToJson();
    j.erase("confusion");
    j["config"] = config;
    j["train_pairs"] = row.train_pairs;
    j["val_pairs"] = row.val_pairs;
    j["test_pairs"] = row.test_pairs;
    j["real_train_val"] = row.real_train_val;
    j["synthetic_train_val"] = row.synthetic_train_val;
    j["best_val_mIoU"] = std::isnan(row.best_val_miou) ? nlohmann::json(nullptr) : nlohmann::json(row.best_val_miou);
    j["best_epoch"] = row.best_epoch;
    j["train_wall_s"] = row.train_wall_s;
    j["extra"] = nlohmann::json::array();
    for (size_t e = 0; e < extra_sets.size(); ++e) {
      row.extra.push_back(EvaluateSegmentation(*segmenter, extra_sets[e], {}, progress, stop));
      nlohmann::json x = row.extra.back().ToJson();
      x["set"] = summary.extra_names[e];
      j["extra"].push_back(x);
    }
    rows.push_back(j);
    summary.rows.push_back(std::move(row));
  }
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json results;
  results["rows"] = rows;
  results["real_dir"] = options.real_dir.string();
  results["synthetic_dir"] = options.synthetic_dir.string();
  results["real_test_dir"] = options.real_test_dir.string();
  results["extra_test_dirs"] = nlohmann::json::array();
  for (const auto& d : options.extra_test_dirs) results["extra_test_dirs"].push_back(d.string());
  results["total"] = options.total;
  results["seed"] = options.seed;
  results["train"] = options.train.ToJson();
  results["wall_s"] = summary.wall_s;
  WriteFileAtomic(options.out_dir / "results.json", results.dump(2) + "\n");
  const std::string test_set =
      options.real_test_dir.empty()
          ? fmt::format("held-out pairs of `{}` (same for every config)", options.real_dir.string())
          : fmt::format("`{}`", options.real_test_dir.string());
  WriteFileAtomic(
      options.out_dir / "results.md",
      fmt::format("# Ratio experiment\n\nTest set: {}. Real: `{}`; synthetic: `{}`; arch {}, {} epochs.\n\n", test_set,
                  options.real_dir.string(), options.synthetic_dir.string(), options.train.arch, options.train.epochs) +
          summary.ToMarkdown());
  WritePlot(options.out_dir / "plot.png", summary.rows);
  return summary;
}

}  // namespace asbuilt
