#include "asbuilt/dataset/check.h"

#include <chrono>
#include <mutex>

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "asbuilt/dataset/manifest.h"
#include "asbuilt/dataset/pairs.h"
#include "asbuilt/labels/label_io.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

constexpr const char* kClassNames[] = {"background", "wall", "door", "window", "ignore"};

struct Job {
  std::string name;
  fs::path image, label;
  std::vector<std::string> groups;
};

// Checks one pair; returns its histogram or throws InputError naming the bad
// file.
ClassHistogram CheckPair(const Job& job) {
  cv::Mat label = ReadLabelImage(job.label);
  const cv::Size image_size = ReadColourImage(job.image).size();
  if (image_size != label.size()) {
    throw InputError(job.label.string(), "",
                     fmt::format("label is {}x{} but image {} is {}x{}", label.cols, label.rows,
                                 job.image.filename().string(), image_size.width, image_size.height));
  }
  std::array<std::int64_t, 256> counts{};
  for (int y = 0; y < label.rows; ++y) {
    const std::uint8_t* p = label.ptr<std::uint8_t>(y);
    for (int x = 0; x < label.cols; ++x) ++counts[p[x]];
  }
  std::string bad;
  for (int v = 4; v < 255; ++v) {
    if (counts[v]) bad += fmt::format("{}{} ({} px)", bad.empty() ? "" : ", ", v, counts[v]);
  }
  if (!bad.empty()) {
    throw InputError(job.label.string(), "", fmt::format("label ids outside {{0, 1, 2, 3, 255}}: {}", bad));
  }
  ClassHistogram h;
  h.pairs = 1;
  for (int k = 0; k < 5; ++k) {
    h.pixels[k] = counts[k < 4 ? k : 255];
    h.images_with[k] = h.pixels[k] > 0;
  }
  return h;
}

}  // namespace

void DatasetCheckOptions::Check() const {
  CheckArgument(num_threads >= 0, fmt::format("DatasetCheckOptions.num_threads = {}, must be >= 0", num_threads));
}

void ClassHistogram::Add(const ClassHistogram& o) {
  pairs += o.pairs;
  for (int k = 0; k < 5; ++k) {
    pixels[k] += o.pixels[k];
    images_with[k] += o.images_with[k];
  }
}

std::string ClassHistogram::ToString() const {
  std::int64_t total = 0;
  for (std::int64_t n : pixels) total += n;
  std::string out = fmt::format("{} pair{}", pairs, pairs == 1 ? "" : "s");
  for (int k = 0; k < 5; ++k) {
    out += fmt::format("{} {} {:.1f} %", k ? "," : ":", kClassNames[k], total ? 100.0 * pixels[k] / total : 0.0);
  }
  return out;
}

std::string DatasetCheckSummary::BriefReport() const {
  return fmt::format("checked {} pair{} in {:.2f} s: {} ok, {} bad, {} problem{}", pairs, pairs == 1 ? "" : "s",
                     seconds, pairs - bad_pairs, bad_pairs, problems.size(), problems.size() == 1 ? "" : "s");
}

std::string DatasetCheckSummary::HistogramTable() const {
  std::string out = fmt::format("{:<10} {:>7}", "group", "pairs");
  for (const char* n : kClassNames) out += fmt::format(" {:>18}", n);
  out += "\n";
  static const char* kOrder[] = {"all", "train", "val", "test", "real", "synthetic"};
  for (const char* g : kOrder) {
    auto it = histograms.find(g);
    if (it == histograms.end()) continue;
    const ClassHistogram& h = it->second;
    std::int64_t total = 0;
    for (std::int64_t n : h.pixels) total += n;
    out += fmt::format("{:<10} {:>7}", g, h.pairs);
    for (int k = 0; k < 5; ++k) {
      out += fmt::format(" {:>7.2f} % {:>6} im", total ? 100.0 * h.pixels[k] / total : 0.0, h.images_with[k]);
    }
    out += "\n";
  }
  return out;
}

DatasetCheckSummary CheckDataset(const DatasetCheckOptions& options, const fs::path& path,
                                 const ProgressCallback& progress) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  DatasetCheckSummary summary;
  std::vector<Job> jobs;
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    PairListing l = ListDatasetPairs(path);
    for (const ImagePair& p : l.pairs) jobs.push_back({p.name, p.image, p.label, {"all"}});
    for (const fs::path& p : l.images_without_label)
      summary.problems.push_back({p.string(), "", "image without label"});
    for (const fs::path& p : l.labels_without_image)
      summary.problems.push_back({p.string(), "", "label without image"});
  } else if (fs::is_regular_file(path, ec)) {
    // Checksums are compared by `validate`; here the pairs' contents matter.
    FileReport report;
    Manifest m = ReadManifestLenient(path, {}, report);
    summary.problems = report.errors;
    const char* kSplits[] = {"train", "val", "test"};
    int s = 0;
    for (const auto* list : {&m.train, &m.val, &m.test}) {
      for (std::size_t i = 0; i < list->size(); ++i) {
        const ManifestEntry& e = (*list)[i];
        if (e.image.empty() || e.label.empty()) continue;  // Already reported.
        jobs.push_back({fmt::format("{}[{}]", kSplits[s], i),
                        m.Resolve(e.image),
                        m.Resolve(e.label),
                        {"all", kSplits[s], PairSourceName(e.source)}});
      }
      ++s;
    }
  } else {
    throw InputError(path.string(), "", "not found (expected a dataset folder or a manifest file)");
  }

  std::mutex mutex;
  std::int64_t done = 0;
  tbb::task_arena arena(options.num_threads > 0 ? options.num_threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, jobs.size(), [&](std::size_t i) {
      const Job& job = jobs[i];
      ClassHistogram h;
      std::optional<Problem> problem;
      try {
        h = CheckPair(job);
      } catch (const InputError& e) {
        Problem p = e.problems().front();
        p.message = fmt::format("pair {}: {}", job.name, p.message);
        problem = p;
      } catch (const std::exception& e) {  // OpenCV or allocation failure on one pair.
        problem = Problem{job.label.string(), "", fmt::format("pair {}: {}", job.name, e.what())};
      }
      std::lock_guard lock(mutex);
      if (problem) {
        summary.problems.push_back(*problem);
        ++summary.bad_pairs;
      } else {
        for (const std::string& g : job.groups) summary.histograms[g].Add(h);
      }
      ReportProgress(progress, {"check", ++done, static_cast<std::int64_t>(jobs.size()), job.name});
    });
  });
  summary.pairs = static_cast<std::int64_t>(jobs.size());
  std::stable_sort(summary.problems.begin(), summary.problems.end(),
                   [](const Problem& a, const Problem& b) { return a.file < b.file; });
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace asbuilt
