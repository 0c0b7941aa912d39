#ifndef ASBUILT_PLAN_SCORE_H_
#define ASBUILT_PLAN_SCORE_H_

// Scoring a predicted floor plan against the truth (blender-rooms-public
// README, "Comparing a plan with the truth"; issue 8 "Scoring"):
//
// - Walls match one-to-one when their lines differ by less than
//   `wall_max_angle_deg`, the mean distance of the predicted wall's endpoints
//   to the truth wall's line is below `wall_max_distance_m`, and their
//   projections onto the truth line overlap by at least
//   `wall_min_overlap_fraction` of the shorter wall. Among candidates the
//   closest pairs are matched first (greedy on mean endpoint distance).
// - For matched walls: relative length error |Lp − Lt| / Lt.
// - Openings match one-to-one per kind when their centres are closer than
//   `opening_max_centre_distance_m` (greedy, closest first); for matched
//   openings: relative width error |Wp − Wt| / Wt.
// - Rooms: relative error of the total room area |Ap − At| / At.
//
// Both plans must be in the same world frame (metres).

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/formats/plan_file.h"

namespace asbuilt {

struct ScoreOptions {
  double wall_max_angle_deg = 10.0;            // Max angle between matched wall lines.
  double wall_max_distance_m = 0.25;           // Max mean endpoint-to-line distance.
  double wall_min_overlap_fraction = 0.5;      // Min overlap, as a fraction of the shorter wall.
  double opening_max_centre_distance_m = 0.3;  // Max distance between matched opening centres.

  void Check() const;
};

// How many predicted and truth items there were and how many matched.
struct MatchCount {
  int predicted = 0;
  int truth = 0;
  int matched = 0;

  // matched / truth and matched / predicted; nullopt when the denominator is 0.
  std::optional<double> Recall() const;
  std::optional<double> Precision() const;
  std::string ToString() const;  // "3/4 matched (recall 75.0 %, precision 100.0 %)"
};

// Median and max of a set of relative errors (fractions, not %). nullopt
// when there were no matched pairs.
struct RelativeErrors {
  std::vector<double> values;  // One per matched pair, in match order.

  std::optional<double> Median() const;
  std::optional<double> Max() const;
  std::string ToString() const;  // "median 0.52 %, max 1.10 % (n = 4)"
};

struct WallMatch {
  int predicted = 0;  // Index into the predicted plan's walls.
  int truth = 0;      // Index into the truth plan's walls.
  double predicted_length_m = 0.0;
  double truth_length_m = 0.0;
  double mean_distance_m = 0.0;
  double angle_deg = 0.0;
  std::optional<double> predicted_length_sigma_m;  // The plan's ±, when it has one.
  double RelativeLengthError() const;
};

struct OpeningMatch {
  OpeningKind kind = OpeningKind::kDoor;
  int predicted = 0;  // Index into the predicted plan's openings.
  int truth = 0;
  double predicted_width_m = 0.0;
  double truth_width_m = 0.0;
  double centre_distance_m = 0.0;
  std::optional<double> predicted_width_sigma_m;  // The plan's ±, when it has one.
  double RelativeWidthError() const;
};

struct PlanScore {
  MatchCount walls;
  RelativeErrors wall_length;  // |Lp − Lt| / Lt over matched walls.
  MatchCount doors;
  MatchCount windows;
  RelativeErrors door_width;
  RelativeErrors window_width;
  RelativeErrors opening_width;                   // Doors and windows together.
  std::optional<double> predicted_area_m2;        // nullopt when the plan has no room.
  std::optional<double> predicted_area_sigma_m2;  // Its ±, combined over rooms.
  std::optional<double> truth_area_m2;
  std::optional<double> area_relative_error;  // nullopt when either has no room.
  std::vector<WallMatch> wall_matches;
  std::vector<OpeningMatch> opening_matches;

  // One line: "walls 4/4, length err median 0.41 % max 0.90 %, doors 1/1, ...".
  std::string ToString() const;
  // A readable multi-line table for terminals and reports.
  std::string Table() const;
};

// Whether a plan's ± means what it says: over many measured dimensions,
// the share whose truth lies within 1σ and 2σ of the measured value (a
// Gaussian gives 68 % and 95 %) and the mean signed relative error (the
// bias). One per kind of dimension (wall lengths, opening widths, areas).
struct UncertaintyCalibration {
  struct Item {
    double measured = 0.0, truth = 0.0, sigma = 0.0;
  };
  std::vector<Item> items;  // Those with a σ; the others are only counted.
  int without_sigma = 0;

  void Add(double measured, double truth, std::optional<double> sigma);
  // Shares of items with |measured − truth| ≤ k·σ; nullopt when empty.
  std::optional<double> Within(double k) const;
  // Mean of (measured − truth)/truth over every item; nullopt when empty.
  std::optional<double> MeanSignedRelativeError() const;
  // "n 136: 72.1 % within 1σ, 94.9 % within 2σ, bias −0.05 %".
  std::string ToString() const;
};

// Every matched wall length, opening width and room area of `score`.
void AddToCalibration(const PlanScore& score, UncertaintyCalibration* walls, UncertaintyCalibration* widths,
                      UncertaintyCalibration* areas);

PlanScore ScorePlan(const Plan& predicted, const Plan& truth, const ScoreOptions& options = {});

// JSON form (fractions, not %; null for what was never computed).
nlohmann::json PlanScoreToJson(const PlanScore& score);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_SCORE_H_
