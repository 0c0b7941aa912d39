#include "asbuilt/plan/score.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

std::string Percent(std::optional<double> v) { return v ? fmt::format("{:.2f} %", 100.0 * *v) : std::string("n/a"); }

std::optional<double> Ratio(int num, int den) {
  if (den <= 0) return std::nullopt;
  return static_cast<double>(num) / den;
}

// Angle between two undirected lines, radians in [0, π/2].
double LineAngle(const Vec2& a, const Vec2& b) {
  double c = std::abs(a.normalized().dot(b.normalized()));
  return std::acos(std::min(1.0, c));
}

double DistanceToLine(const Vec2& p, const Vec2& a, const Vec2& b) {
  Vec2 d = (b - a).normalized();
  Vec2 n(-d.y(), d.x());
  return std::abs(n.dot(p - a));
}

double TotalArea(const Plan& plan) {
  double area = 0.0;
  for (const PlanRoom& r : plan.rooms) {
    area += r.polygon.size() >= 3 ? std::abs(PolygonArea(r.polygon)) : std::abs(r.area_m2);
  }
  return area;
}

struct Candidate {
  double cost;
  int p;
  int t;
};

// Greedy one-to-one assignment, lowest cost first (ties by index, so the
// result is deterministic).
std::vector<Candidate> Assign(std::vector<Candidate> candidates, int np, int nt) {
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.cost != b.cost) return a.cost < b.cost;
    if (a.p != b.p) return a.p < b.p;
    return a.t < b.t;
  });
  std::vector<bool> used_p(np, false), used_t(nt, false);
  std::vector<Candidate> out;
  for (const Candidate& c : candidates) {
    if (used_p[c.p] || used_t[c.t]) continue;
    used_p[c.p] = used_t[c.t] = true;
    out.push_back(c);
  }
  return out;
}

nlohmann::json OptionalJson(std::optional<double> v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }

nlohmann::json CountJson(const MatchCount& c) {
  return {{"predicted", c.predicted},
          {"truth", c.truth},
          {"matched", c.matched},
          {"recall", OptionalJson(c.Recall())},
          {"precision", OptionalJson(c.Precision())}};
}

nlohmann::json ErrorsJson(const RelativeErrors& e) {
  return {{"count", e.values.size()},
          {"median", OptionalJson(e.Median())},
          {"max", OptionalJson(e.Max())},
          {"values", e.values}};
}

}  // namespace

void ScoreOptions::Check() const {
  CheckArgument(wall_max_angle_deg > 0 && wall_max_angle_deg <= 90,
                fmt::format("ScoreOptions.wall_max_angle_deg = {}, must be in (0, 90]", wall_max_angle_deg));
  CheckArgument(wall_max_distance_m > 0,
                fmt::format("ScoreOptions.wall_max_distance_m = {}, must be > 0", wall_max_distance_m));
  CheckArgument(
      wall_min_overlap_fraction >= 0 && wall_min_overlap_fraction <= 1,
      fmt::format("ScoreOptions.wall_min_overlap_fraction = {}, must be in [0, 1]", wall_min_overlap_fraction));
  CheckArgument(
      opening_max_centre_distance_m > 0,
      fmt::format("ScoreOptions.opening_max_centre_distance_m = {}, must be > 0", opening_max_centre_distance_m));
}

std::optional<double> MatchCount::Recall() const { return Ratio(matched, truth); }
std::optional<double> MatchCount::Precision() const { return Ratio(matched, predicted); }

std::string MatchCount::ToString() const {
  return fmt::format("{}/{} matched (recall {}, precision {})", matched, truth,
                     Recall() ? fmt::format("{:.1f} %", 100 * *Recall()) : "n/a",
                     Precision() ? fmt::format("{:.1f} %", 100 * *Precision()) : "n/a");
}

std::optional<double> RelativeErrors::Median() const {
  if (values.empty()) return std::nullopt;
  std::vector<double> v = values;
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::optional<double> RelativeErrors::Max() const {
  if (values.empty()) return std::nullopt;
  return *std::max_element(values.begin(), values.end());
}

std::string RelativeErrors::ToString() const {
  return fmt::format("median {}, max {} (n = {})", Percent(Median()), Percent(Max()), values.size());
}

double WallMatch::RelativeLengthError() const { return std::abs(predicted_length_m - truth_length_m) / truth_length_m; }

double OpeningMatch::RelativeWidthError() const { return std::abs(predicted_width_m - truth_width_m) / truth_width_m; }

PlanScore ScorePlan(const Plan& predicted, const Plan& truth, const ScoreOptions& options) {
  options.Check();
  PlanScore score;

  // Walls.
  const int np = static_cast<int>(predicted.walls.size());
  const int nt = static_cast<int>(truth.walls.size());
  std::vector<Candidate> candidates;
  for (int p = 0; p < np; ++p) {
    const PlanWall& wp = predicted.walls[p];
    for (int t = 0; t < nt; ++t) {
      const PlanWall& wt = truth.walls[t];
      if (wp.Length() <= 0 || wt.Length() <= 0) continue;
      double angle = LineAngle(wp.end - wp.start, wt.end - wt.start);
      if (RadToDeg(angle) >= options.wall_max_angle_deg) continue;
      double dist = 0.5 * (DistanceToLine(wp.start, wt.start, wt.end) + DistanceToLine(wp.end, wt.start, wt.end));
      if (dist >= options.wall_max_distance_m) continue;
      // Overlap of the two walls projected onto the truth wall's direction.
      Vec2 d = (wt.end - wt.start).normalized();
      double t0 = 0, t1 = wt.Length();
      double p0 = d.dot(wp.start - wt.start), p1 = d.dot(wp.end - wt.start);
      if (p0 > p1) std::swap(p0, p1);
      double overlap = std::min(t1, p1) - std::max(t0, p0);
      if (overlap < options.wall_min_overlap_fraction * std::min(wp.Length(), wt.Length())) continue;
      candidates.push_back({dist, p, t});
    }
  }
  for (const Candidate& c : Assign(candidates, np, nt)) {
    const PlanWall& wp = predicted.walls[c.p];
    const PlanWall& wt = truth.walls[c.t];
    WallMatch m{.predicted = c.p,
                .truth = c.t,
                .predicted_length_m = wp.Length(),
                .truth_length_m = wt.Length(),
                .mean_distance_m = c.cost,
                .angle_deg = RadToDeg(LineAngle(wp.end - wp.start, wt.end - wt.start)),
                .predicted_length_sigma_m = wp.length_sigma_m};
    score.wall_matches.push_back(m);
  }
  std::sort(score.wall_matches.begin(), score.wall_matches.end(),
            [](const WallMatch& a, const WallMatch& b) { return a.truth < b.truth; });
  score.wall_length.values.clear();
  for (const WallMatch& m : score.wall_matches) score.wall_length.values.push_back(m.RelativeLengthError());
  score.walls = {np, nt, static_cast<int>(score.wall_matches.size())};

  // Openings, per kind.
  for (OpeningKind kind : {OpeningKind::kDoor, OpeningKind::kWindow}) {
    std::vector<int> pi, ti;
    for (int i = 0; i < static_cast<int>(predicted.openings.size()); ++i) {
      if (predicted.openings[i].kind == kind) pi.push_back(i);
    }
    for (int i = 0; i < static_cast<int>(truth.openings.size()); ++i) {
      if (truth.openings[i].kind == kind) ti.push_back(i);
    }
    std::vector<Candidate> oc;
    for (int a = 0; a < static_cast<int>(pi.size()); ++a) {
      for (int b = 0; b < static_cast<int>(ti.size()); ++b) {
        double d = (predicted.openings[pi[a]].Centre() - truth.openings[ti[b]].Centre()).norm();
        if (d < options.opening_max_centre_distance_m) oc.push_back({d, a, b});
      }
    }
    std::vector<Candidate> matched = Assign(oc, static_cast<int>(pi.size()), static_cast<int>(ti.size()));
    std::sort(matched.begin(), matched.end(), [](const Candidate& a, const Candidate& b) { return a.t < b.t; });
    MatchCount& count = kind == OpeningKind::kDoor ? score.doors : score.windows;
    RelativeErrors& errors = kind == OpeningKind::kDoor ? score.door_width : score.window_width;
    count = {static_cast<int>(pi.size()), static_cast<int>(ti.size()), static_cast<int>(matched.size())};
    for (const Candidate& c : matched) {
      const PlanOpening& op = predicted.openings[pi[c.p]];
      const PlanOpening& ot = truth.openings[ti[c.t]];
      OpeningMatch m{.kind = kind,
                     .predicted = pi[c.p],
                     .truth = ti[c.t],
                     .predicted_width_m = op.width,
                     .truth_width_m = ot.width,
                     .centre_distance_m = c.cost,
                     .predicted_width_sigma_m = op.width_sigma_m};
      errors.values.push_back(m.RelativeWidthError());
      score.opening_width.values.push_back(m.RelativeWidthError());
      score.opening_matches.push_back(m);
    }
  }

  // Room area.
  if (!predicted.rooms.empty()) {
    score.predicted_area_m2 = TotalArea(predicted);
    double variance = 0.0;
    bool all = true;
    for (const PlanRoom& r : predicted.rooms) {
      all = all && r.area_sigma_m2.has_value();
      variance += r.area_sigma_m2.value_or(0.0) * r.area_sigma_m2.value_or(0.0);
    }
    if (all) score.predicted_area_sigma_m2 = std::sqrt(variance);
  }
  if (!truth.rooms.empty()) score.truth_area_m2 = TotalArea(truth);
  if (score.predicted_area_m2 && score.truth_area_m2 && *score.truth_area_m2 > 0) {
    score.area_relative_error = std::abs(*score.predicted_area_m2 - *score.truth_area_m2) / *score.truth_area_m2;
  }
  return score;
}

void UncertaintyCalibration::Add(double measured, double truth, std::optional<double> sigma) {
  if (sigma && *sigma > 0.0) {
    items.push_back({measured, truth, *sigma});
  } else {
    ++without_sigma;
    items.push_back({measured, truth, 0.0});
  }
}

std::optional<double> UncertaintyCalibration::Within(double k) const {
  if (items.empty()) return std::nullopt;
  int inside = 0;
  for (const Item& i : items) inside += std::abs(i.measured - i.truth) <= k * i.sigma;
  return static_cast<double>(inside) / static_cast<double>(items.size());
}

std::optional<double> UncertaintyCalibration::MeanSignedRelativeError() const {
  if (items.empty()) return std::nullopt;
  double sum = 0.0;
  for (const Item& i : items) sum += (i.measured - i.truth) / i.truth;
  return sum / static_cast<double>(items.size());
}

std::string UncertaintyCalibration::ToString() const {
  const auto pct = [](std::optional<double> v) { return v ? fmt::format("{:.1f} %", 100 * *v) : std::string("–"); };
  const std::optional<double> bias = MeanSignedRelativeError();
  return fmt::format("n {}: {} within 1σ, {} within 2σ, bias {}{}", items.size(), pct(Within(1.0)), pct(Within(2.0)),
                     bias ? fmt::format("{:+.2f} %", 100 * *bias) : std::string("–"),
                     without_sigma > 0 ? fmt::format(" ({} without ±)", without_sigma) : std::string());
}

void AddToCalibration(const PlanScore& score, UncertaintyCalibration* walls, UncertaintyCalibration* widths,
                      UncertaintyCalibration* areas) {
  for (const WallMatch& m : score.wall_matches)
    walls->Add(m.predicted_length_m, m.truth_length_m, m.predicted_length_sigma_m);
  for (const OpeningMatch& m : score.opening_matches) {
    widths->Add(m.predicted_width_m, m.truth_width_m, m.predicted_width_sigma_m);
  }
  if (score.predicted_area_m2 && score.truth_area_m2) {
    areas->Add(*score.predicted_area_m2, *score.truth_area_m2, score.predicted_area_sigma_m2);
  }
}

std::string PlanScore::ToString() const {
  return fmt::format(
      "walls {}/{} (precision {}), length err median {} max {}; doors {}/{}, windows {}/{}, "
      "width err median {} max {}; area err {}",
      walls.matched, walls.truth,
      walls.Precision() ? fmt::format("{:.1f} %", 100 * *walls.Precision()) : std::string("n/a"),
      Percent(wall_length.Median()), Percent(wall_length.Max()), doors.matched, doors.truth, windows.matched,
      windows.truth, Percent(opening_width.Median()), Percent(opening_width.Max()), Percent(area_relative_error));
}

std::string PlanScore::Table() const {
  auto ratio = [](std::optional<double> v) { return v ? fmt::format("{:.1f} %", 100 * *v) : std::string("n/a"); };
  std::string out;
  out += fmt::format("{:<10} {:>9} {:>6} {:>8} {:>9} {:>10} {:>16} {:>13}\n", "item", "predicted", "truth", "matched",
                     "recall", "precision", "rel. err median", "rel. err max");
  auto row = [&](const char* name, const MatchCount& c, const RelativeErrors& e) {
    out += fmt::format("{:<10} {:>9} {:>6} {:>8} {:>9} {:>10} {:>16} {:>13}\n", name, c.predicted, c.truth, c.matched,
                       ratio(c.Recall()), ratio(c.Precision()), Percent(e.Median()), Percent(e.Max()));
  };
  row("walls", walls, wall_length);
  row("doors", doors, door_width);
  row("windows", windows, window_width);
  out += fmt::format("room area: predicted {}, truth {}, relative error {}\n",
                     predicted_area_m2 ? fmt::format("{:.3f} m²", *predicted_area_m2) : "n/a",
                     truth_area_m2 ? fmt::format("{:.3f} m²", *truth_area_m2) : "n/a", Percent(area_relative_error));
  out += "(walls: length error; doors, windows: width error)\n";
  for (const WallMatch& m : wall_matches) {
    out +=
        fmt::format("  wall {:>2} ↔ truth {:>2}: {:.3f} m vs {:.3f} m ({:+.2f} %), offset {:.3f} m, {:.2f}°\n",
                    m.predicted, m.truth, m.predicted_length_m, m.truth_length_m,
                    100 * (m.predicted_length_m - m.truth_length_m) / m.truth_length_m, m.mean_distance_m, m.angle_deg);
  }
  for (const OpeningMatch& m : opening_matches) {
    out += fmt::format("  {:<6} {:>2} ↔ truth {:>2}: width {:.3f} m vs {:.3f} m ({:+.2f} %), centres {:.3f} m apart\n",
                       OpeningKindName(m.kind), m.predicted, m.truth, m.predicted_width_m, m.truth_width_m,
                       100 * (m.predicted_width_m - m.truth_width_m) / m.truth_width_m, m.centre_distance_m);
  }
  return out;
}

nlohmann::json PlanScoreToJson(const PlanScore& score) {
  nlohmann::json j;
  j["walls"] = CountJson(score.walls);
  j["wall_length_relative_error"] = ErrorsJson(score.wall_length);
  j["doors"] = CountJson(score.doors);
  j["windows"] = CountJson(score.windows);
  j["door_width_relative_error"] = ErrorsJson(score.door_width);
  j["window_width_relative_error"] = ErrorsJson(score.window_width);
  j["opening_width_relative_error"] = ErrorsJson(score.opening_width);
  j["room_area"] = {{"predicted_m2", OptionalJson(score.predicted_area_m2)},
                    {"predicted_sigma_m2", OptionalJson(score.predicted_area_sigma_m2)},
                    {"truth_m2", OptionalJson(score.truth_area_m2)},
                    {"relative_error", OptionalJson(score.area_relative_error)}};
  nlohmann::json wm = nlohmann::json::array();
  for (const WallMatch& m : score.wall_matches) {
    wm.push_back({{"predicted", m.predicted},
                  {"truth", m.truth},
                  {"predicted_length_m", m.predicted_length_m},
                  {"truth_length_m", m.truth_length_m},
                  {"mean_distance_m", m.mean_distance_m},
                  {"angle_deg", m.angle_deg},
                  {"relative_length_error", m.RelativeLengthError()},
                  {"predicted_length_sigma_m", OptionalJson(m.predicted_length_sigma_m)}});
  }
  j["wall_matches"] = wm;
  nlohmann::json om = nlohmann::json::array();
  for (const OpeningMatch& m : score.opening_matches) {
    om.push_back({{"kind", OpeningKindName(m.kind)},
                  {"predicted", m.predicted},
                  {"truth", m.truth},
                  {"predicted_width_m", m.predicted_width_m},
                  {"truth_width_m", m.truth_width_m},
                  {"centre_distance_m", m.centre_distance_m},
                  {"relative_width_error", m.RelativeWidthError()},
                  {"predicted_width_sigma_m", OptionalJson(m.predicted_width_sigma_m)}});
  }
  j["opening_matches"] = om;
  return j;
}

}  // namespace asbuilt
