#include "asbuilt/plan/plan_wall_line.h"

#include <algorithm>

#include <spdlog/spdlog.h>

namespace asbuilt {

double WallPoints::TotalVotes() const {
  double total = 0;
  for (const WallPoint& p : points) total += p.vote;
  return total;
}

double SortedQuantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  double pos = q * (sorted.size() - 1);
  size_t i = static_cast<size_t>(std::floor(pos));
  size_t j = std::min(i + 1, sorted.size() - 1);
  return sorted[i] + (pos - i) * (sorted[j] - sorted[i]);
}

double Votes(const std::vector<WallPoint>& points, const std::vector<int>& idx) {
  double v = 0;
  for (int i : idx) v += points[i].vote;
  return v;
}

BinnedPositions BinPositions(const std::vector<double>& ts, double bin_m) {
  BinnedPositions binned{.t0 = ts.front(), .bin_m = bin_m};
  const int nbins = static_cast<int>((ts.back() - binned.t0) / bin_m) + 1;
  binned.counts.assign(nbins, 0);
  for (double t : ts) binned.counts[std::min(nbins - 1, static_cast<int>((t - binned.t0) / bin_m))]++;
  return binned;
}

int BinnedPositions::WellFilled() const {
  std::vector<int> filled;
  for (int c : counts) {
    if (c > 0) filled.push_back(c);
  }
  std::sort(filled.begin(), filled.end());
  return filled[filled.size() * 3 / 4];
}

std::vector<std::pair<size_t, size_t>> DenseRuns(const std::vector<double>& ts, double max_gap) {
  std::vector<std::pair<size_t, size_t>> runs;
  if (ts.empty()) return runs;
  if (ts.size() < 100) {
    size_t begin = 0;
    for (size_t i = 1; i <= ts.size(); ++i) {
      if (i < ts.size() && ts[i] - ts[i - 1] <= max_gap) continue;
      runs.push_back({begin, i});
      begin = i;
    }
    return runs;
  }
  const BinnedPositions binned = BinPositions(ts, 0.1);
  const double bin = binned.bin_m, t0 = binned.t0;
  const std::vector<int>& counts = binned.counts;
  const int nbins = static_cast<int>(counts.size());
  // A tenth of a well-filled bin, or of the fullest bin within max_gap where
  // that is less: a wall seen from one spot thins out towards its far end
  // (its columns' footprints grow with the square of the distance), and its
  // far bins are as much the wall as the near ones.
  const int reach = static_cast<int>(std::ceil(max_gap / bin));
  const double well_filled = binned.WellFilled();
  std::vector<double> level(nbins);
  for (int i = 0; i < nbins; ++i) {
    int local = 0;
    for (int j = std::max(0, i - reach); j <= std::min(nbins - 1, i + reach); ++j) local = std::max(local, counts[j]);
    level[i] = std::max(2.0, 0.1 * std::min<double>(well_filled, local));
  }
  int run_first = -1, run_last = -1;
  auto emit = [&]() {
    if (run_first < 0) return;
    double lo = t0 + run_first * bin, hi = t0 + (run_last + 1) * bin;
    size_t b = std::lower_bound(ts.begin(), ts.end(), lo) - ts.begin();
    size_t e = std::upper_bound(ts.begin(), ts.end(), hi) - ts.begin();
    if (e > b) runs.push_back({b, e});
  };
  for (int i = 0; i < nbins; ++i) {
    if (counts[i] < level[i]) continue;
    if (run_first >= 0 && (i - run_last - 1) * bin > max_gap) {
      emit();
      run_first = -1;
    }
    if (run_first < 0) run_first = i;
    run_last = i;
  }
  emit();
  return runs;
}

WallLine FitWallLine(const std::vector<WallPoint>& pts, std::vector<int> idx, std::optional<double> fixed_theta,
                     int max_independent, double max_gap) {
  WallLine line;
  double sw = 0;
  Vec2 c = Vec2::Zero();
  for (int i : idx) {
    sw += pts[i].w;
    c += pts[i].w * pts[i].p;
  }
  c /= sw;
  if (fixed_theta) {
    line.theta = *fixed_theta;
  } else if (const auto free = TlsDirection(
                 pts, idx, [](size_t) { return true; }, max_independent)) {
    line.theta = free->first;
  }
  line.c = c;
  Vec2 dir = line.Dir(), n = line.Normal();
  double chi2 = 0, swt2 = 0;
  std::vector<double> ts;
  ts.reserve(idx.size());
  for (int i : idx) {
    Vec2 d = pts[i].p - c;
    double r = n.dot(d), t = dir.dot(d);
    chi2 += pts[i].w * r * r;
    swt2 += pts[i].w * t * t;
    ts.push_back(t);
  }
  std::sort(ts.begin(), ts.end());
  const int count = static_cast<int>(idx.size());
  std::pair<size_t, size_t> main_run{0, ts.size()};
  for (auto r : DenseRuns(ts, max_gap)) {
    if (r.second - r.first > main_run.second - main_run.first || main_run.second - main_run.first == ts.size()) {
      main_run = r;
    }
  }
  double reduced = count > 2 ? chi2 / (count - 2) : 1.0;
  double correlation = std::max(1.0, static_cast<double>(count) / max_independent);
  line.var_rho = reduced / sw * correlation;
  line.var_theta = fixed_theta ? 0.0 : reduced / std::max(swt2, 1e-12) * correlation;
  line.t_min = ts[main_run.first];
  line.t_max = ts[main_run.second - 1];
  line.chi2 = chi2;
  line.sum_w = sw;
  std::vector<double> zs;
  zs.reserve(idx.size());
  for (int i : idx) zs.push_back(pts[i].z);
  std::sort(zs.begin(), zs.end());
  line.z_top = SortedQuantile(zs, 0.995);
  line.votes = Votes(pts, idx);
  line.members = std::move(idx);
  return line;
}

std::optional<Vec2> IntersectLines(const WallLine& a, const WallLine& b) {
  double den = Cross(a.Dir(), b.Dir());
  if (std::abs(den) < 1e-9) return std::nullopt;
  double s = Cross(b.c - a.c, b.Dir()) / den;
  return a.c + s * a.Dir();
}

// Why a short piece may lie 10° off: docs/plan.md, step 2.
double CollinearTolerance(const WallLine& a, const WallLine& b, const PlanOptions& o) {
  return std::max(2 * o.epsilon_m, 3 * std::sqrt(a.var_rho + b.var_rho));
}

bool CollinearLines(const WallLine& a, const WallLine& b, const PlanOptions& o) {
  const double diff = std::abs(AngleDiffModPi(a.theta, b.theta));
  if (diff > DegToRad(10.0)) return false;
  const double tol = CollinearTolerance(a, b, o);
  if (diff <= DegToRad(3.0) && std::abs(a.Distance(b.c)) < tol && std::abs(b.Distance(a.c)) < tol) return true;
  const bool a_longer = a.t_max - a.t_min >= b.t_max - b.t_min;
  const WallLine& longer = a_longer ? a : b;
  const WallLine& shorter = a_longer ? b : a;
  return std::abs(longer.Distance(shorter.Start())) < tol && std::abs(longer.Distance(shorter.End())) < tol;
}

void LogWallLines(const char* stage, const std::vector<WallLine>& lines) {
  if (!spdlog::should_log(spdlog::level::debug)) return;
  spdlog::debug("plan: {}: {} lines", stage, lines.size());
  for (const WallLine& l : lines) {
    spdlog::debug("  ({:.3f}, {:.3f}) → ({:.3f}, {:.3f}) θ {:.3f}° ±{:.4f}° ρ ±{:.4f} m, {} points{}", l.Start().x(),
                  l.Start().y(), l.End().x(), l.End().y(), RadToDeg(l.theta), RadToDeg(std::sqrt(l.var_theta)),
                  std::sqrt(l.var_rho), l.members.size(), l.inferred ? " (inferred)" : "");
  }
}

}  // namespace asbuilt
