#ifndef ASBUILT_BENCH_VERDICT_STATS_H_
#define ASBUILT_BENCH_VERDICT_STATS_H_

// The verdict's figures against truth (issue 42), shared by bench_verdict
// and bench_pano_survey: how plans of each room IoU got each verdict, how
// well the confidence ranks them (Spearman ρ), and how often a "good" wall
// is more than 10 % off.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/pipeline/survey.h"
#include "asbuilt/plan/score.h"

namespace asbuilt::bench {

struct VerdictSample {
  std::string name;
  Verdict verdict = Verdict::kUnreliable;
  double confidence = 0.0;
  double iou = 0.0;                         // 0 without a plan.
  int good_walls = 0;                       // Walls called good…
  int good_walls_matched = 0;               // …matched to a truth wall…
  int good_walls_off = 0;                   // …and more than 10 % off in length.
  UncertaintyCalibration walls_with_sigma;  // Matched walls that keep a ± (not unreliable).
};

inline VerdictSample SampleOf(const std::string& name, const SurveySummary& s) {
  VerdictSample v{.name = name, .verdict = s.verdict.verdict, .confidence = s.verdict.confidence};
  v.iou = s.room_overlap ? s.room_overlap->Iou() : 0.0;
  if (s.score) {
    for (const WallMatch& m : s.score->wall_matches) {
      if (m.predicted_length_sigma_m && *m.predicted_length_sigma_m > 0)
        v.walls_with_sigma.Add(m.predicted_length_m, m.truth_length_m, m.predicted_length_sigma_m);
    }
  }
  for (std::size_t w = 0; w < s.verdict.walls.size(); ++w) {
    if (s.verdict.walls[w].verdict != Verdict::kGood) continue;
    ++v.good_walls;
    if (!s.score) continue;
    for (const WallMatch& m : s.score->wall_matches) {
      if (m.predicted != static_cast<int>(w)) continue;
      ++v.good_walls_matched;
      v.good_walls_off += m.RelativeLengthError() > 0.10;
    }
  }
  return v;
}

// Spearman's ρ with mid-ranks for ties (NaN for fewer than 3 samples or no spread).
inline double SpearmanRho(const std::vector<double>& a, const std::vector<double>& b) {
  auto ranks = [](const std::vector<double>& v) {
    std::vector<std::size_t> order(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return v[x] < v[y]; });
    std::vector<double> r(v.size());
    for (std::size_t i = 0; i < order.size();) {
      std::size_t j = i;
      while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
      for (std::size_t k = i; k <= j; ++k) r[order[k]] = 0.5 * double(i + j);
      i = j + 1;
    }
    return r;
  };
  if (a.size() < 3) return NAN;
  const std::vector<double> ra = ranks(a), rb = ranks(b);
  const double n = static_cast<double>(a.size()), mean = 0.5 * (n - 1);
  double cov = 0, va = 0, vb = 0;
  for (std::size_t i = 0; i < ra.size(); ++i) {
    cov += (ra[i] - mean) * (rb[i] - mean), va += (ra[i] - mean) * (ra[i] - mean),
        vb += (rb[i] - mean) * (rb[i] - mean);
  }
  return va > 0 && vb > 0 ? cov / std::sqrt(va * vb) : NAN;
}

// One row of the verdict table: a set of plans.
inline std::string VerdictRow(const std::string& set, const std::vector<VerdictSample>& samples) {
  int good = 0, check = 0, unreliable = 0, low_good = 0, high = 0, high_good = 0, walls = 0, matched = 0, off = 0;
  UncertaintyCalibration walls_with_sigma;
  std::vector<double> confidence, iou;
  for (const VerdictSample& s : samples) {
    good += s.verdict == Verdict::kGood, check += s.verdict == Verdict::kCheck;
    unreliable += s.verdict == Verdict::kUnreliable;
    low_good += s.iou < 0.80 && s.verdict == Verdict::kGood;
    high += s.iou >= 0.95, high_good += s.iou >= 0.95 && s.verdict == Verdict::kGood;
    walls += s.good_walls, matched += s.good_walls_matched, off += s.good_walls_off;
    walls_with_sigma.items.insert(walls_with_sigma.items.end(), s.walls_with_sigma.items.begin(),
                                  s.walls_with_sigma.items.end());
    confidence.push_back(s.confidence), iou.push_back(s.iou);
  }
  const double rho = SpearmanRho(confidence, iou);
  std::string coverage = "–";
  if (!walls_with_sigma.items.empty()) {
    const double p1 = *walls_with_sigma.Within(1.0), p2 = *walls_with_sigma.Within(2.0);
    coverage = fmt::format("{:.0f} % {} / {:.0f} % {} of {}", 100 * p1, p1 >= 0.55 && p1 <= 0.80 ? "✓" : "✗", 100 * p2,
                           p2 >= 0.85 && p2 <= 0.98 ? "✓" : "✗", walls_with_sigma.items.size());
  }
  return fmt::format("| {} | {} | {} / {} / {} | {} {} | {} | {} | {} of {} ({} matched) {} | {} |\n", set,
                     samples.size(), good, check, unreliable, low_good, low_good == 0 ? "✓" : "✗",
                     high > 0 ? fmt::format("{}/{} {}", high_good, high, 5 * high_good >= 4 * high ? "✓" : "✗") : "–",
                     std::isfinite(rho) ? fmt::format("{:.2f} {}", rho, rho >= 0.7 ? "✓" : "✗") : "–", off, walls,
                     matched, off == 0 ? "✓" : "✗", coverage);
}

inline std::string VerdictTableHeader() {
  return "| plans | n | good / check / unreliable | IoU < 0.80 called good (target 0) | IoU ≥ 0.95 called good "
         "(target ≥ 80 %) | Spearman ρ, confidence vs IoU (target ≥ 0.7) | good walls > 10 % off (target 0) | "
         "true wall lengths within 1σ / 2σ, of matched walls with a ± (target 55–80 % / 85–98 %) |\n"
         "|---|---|---|---|---|---|---|---|\n";
}

inline std::string VerdictList(const std::vector<VerdictSample>& samples) {
  std::string md = "| plan | verdict | confidence | room IoU |\n|---|---|---|---|\n";
  for (const VerdictSample& s : samples) {
    md += fmt::format("| {} | {} | {:.2f} | {:.3f} |\n", s.name, VerdictName(s.verdict), s.confidence, s.iou);
  }
  return md;
}

}  // namespace asbuilt::bench

#endif  // ASBUILT_BENCH_VERDICT_STATS_H_
