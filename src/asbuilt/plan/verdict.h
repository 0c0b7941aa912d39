#ifndef ASBUILT_PLAN_VERDICT_H_
#define ASBUILT_PLAN_VERDICT_H_

// Is a fitted plan a measurement? A verdict per plan and per wall from
// evidence that needs no truth (docs/verdict.md):
//
//  - agreement: every wall point is seen along a ray from its frame's
//    camera; the plan, cast along the same ray, should put a wall at the
//    point's distance. Rays are binned by bearing about the viewpoint; a bin
//    agrees when its points' median relative distance error is small. A plan
//    whose walls are not where the photo's floor and ceiling edges say they
//    are disagrees in many bins, whatever caused it (a misread photo, a
//    missed or spurious wall).
//  - floor vs ceiling: a one-camera capture places each wall twice, from its
//    floor edge (camera height) and from its ceiling edge (measured ceiling
//    height); a tilted photo, a wrong height or furniture before the wall
//    makes the two disagree.
//  - coverage: the share of bearings (and of each wall's span) with points.
//  - shape and scale: many very short walls, walls at odd angles in a
//    square room, a ceiling or doors of a height no room has (a wrong
//    camera height scales the whole room), an open ring.
//
// A wall's length runs between the corners its neighbours make, so a wall
// is only as good as its own line and both neighbours'. Each reason says
// what was measured, in words a surveyor can act on.

#include <cmath>
#include <string>
#include <vector>

#include "asbuilt/plan/fit_plan.h"

namespace asbuilt {

enum class Verdict { kGood = 0, kCheck = 1, kUnreliable = 2 };
const char* VerdictName(Verdict v);  // "good", "check", "unreliable"

struct VerdictOptions {
  double bin_deg = 2.0;               // Bearing bins about the viewpoint, deg.
  double agree_relative = 0.05;       // A bin agrees when its median |d_point − d_plan| / d_plan is below this…
  double agree_sigmas = 2.5;          // …or below this many of its points' median σ (stereo noise)…
  double agree_max_relative = 0.12;   // …but never above this.
  double good_agreement = 0.85;       // Plan: share of seen bins that agree, at least this for "good"…
  double unreliable_agreement = 0.6;  // …below this "unreliable".
  double good_coverage = 0.6;  // Plan (one-camera 360° captures): share of bins seen, at least this for "good"…
  double unreliable_coverage = 0.3;        // …below this "unreliable".
  double wall_good_seen = 0.4;             // Wall: share of its span's bins seen, at least this for "good"…
  double wall_unreliable_seen = 0.15;      // …below this "unreliable".
  double wall_good_agreement = 0.8;        // Wall: share of its seen bins that agree, at least this for "good"…
  double wall_unreliable_agreement = 0.5;  // …below this "unreliable".
  double floor_ceiling_check = 0.04;       // Median relative floor/ceiling disagreement above this: "check"…
  double floor_ceiling_unreliable = 0.12;  // …above this "unreliable".
  double short_wall_m = 0.3;               // Walls shorter than this are suspect (spurious jogs)…
  int max_short_walls = 2;                 // …more of them than this make the shape doubtful.
  double odd_angle_deg = 10.0;             // In a Manhattan room, corners this far from 90°/180° are odd…
  double max_odd_corner_share = 0.25;      // …more than this share of them (and more than 2) make the shape doubtful.
  double max_tilt_scatter_m =
      0.04;  // A lean is read from the ceiling samples only when they scatter less than this about it.
  double max_photo_tilt_deg =
      5.0;  // A photo levelled from a larger tilt: "check" (lens, stitching, a room not square)…
  double max_photo_tilt_sigma_deg = 0.3;  // …and one whose levelling is less sure than this.
  double min_ceiling_m = 2.0;             // A ceiling measured outside [min, max] is implausible (camera height?).
  double max_ceiling_m = 5.0;
  double min_door_height_m = 1.75;  // Doors outside [min, max] are implausible (camera height?).
  double max_door_height_m = 2.6;
  double min_area_m2 = 2.0;          // Smaller rooms are implausible.
  double tilt_check_deg = 0.4;       // A photo tilted more than this (read from its edges): "check"…
  double tilt_unreliable_deg = 1.5;  // …more than this "unreliable".
  double hidden_floor_check =
      0.9;  // A wall whose floor edge is hidden along more than this share of its seen span: "check".
  double check_label_confidence = 0.8;  // The segmenter's mean confidence below this: "check".

  void Check() const;
};

// What the capture adds to the points (each part optional).
struct VerdictContext {
  // ResolvedContacts::ceiling_samples (formats/points_file.h).
  std::vector<CeilingSample> ceiling_samples;
  // Per plan wall: placed by a person (asbuilt review: both its corners
  // set by hand). Such a wall is good, and the photo's evidence about it
  // does not count against the plan.
  std::vector<bool> confirmed_walls;
  // The photo's tilt as estimated from its lines before it was levelled
  // (pano/level.h); NaN: not estimated.
  double photo_tilt_deg = NAN;
  double photo_tilt_sigma_deg = NAN;
  // How sure the segmenter was of the labels (LabelSource::MeanConfidence);
  // NaN: labels given or exact.
  double label_confidence = NAN;
};

// A camera's tilt read from its floor and ceiling edges: round the room,
// the ceiling height each column implies rises and falls with the lean.
struct LabelTilt {
  double tilt_deg = NAN;  // NaN: too few columns saw both edges.
  double sigma_deg = NAN;
  double toward_deg = NAN;  // The bearing the camera leans toward (plan frame).
  double ceiling_m = NAN;   // The ceiling height with the lean taken out.
  int samples = 0;
  double inlier_share = 0.0;  // Of the samples, those the lean explains (the rest: tops, stray edges).
  double scatter_m = NAN;     // Robust σ of the samples about the fitted lean.
  // A lean is read only when it explains most samples closely: a misread
  // photo's edges scatter, and some sinusoid always fits part of them.
  bool Found(double max_scatter_m = 0.04) const {
    return std::isfinite(tilt_deg) && inlier_share >= 0.6 && scatter_m <= max_scatter_m;
  }
};
LabelTilt TiltFromCeilingSamples(const PlanInput& input, const std::vector<CeilingSample>& samples);

// The evidence behind one wall's verdict.
struct WallEvidenceFigures {
  double seen = 0.0;           // Share of the bins its span covers that hold points.
  double agreement = NAN;      // Share of its seen bins that agree (NaN: none seen).
  double floor_ceiling = NAN;  // Median relative floor/ceiling distance disagreement (NaN: not measured).
  double median_error = NAN;   // Median signed relative distance error of its points ((point − plan) / plan).
  double hidden_floor = 0.0;   // Share of its seen span with ceiling contacts but no floor contact.
  double offset_sigma_m =
      NAN;  // 68th percentile of its bins' |median distance error|, m: how far its points scatter off it.
  // How far it may run on past a jog at either end, m: the walls beyond a
  // jog (a wall under short_wall_m) that are parallel to it, one wall with
  // it if the jog is a misread step. Enters its length's ± (MarkPlan).
  double run_on_m = 0.0;
  // Where an end is in doubt (an unreliable neighbour, a shorter one at an
  // odd angle), how far the walls beyond it reach along its line, m: where
  // it may at most run on. As 1.5σ it enters its length's ± (MarkPlan).
  double doubtful_reach_m = 0.0;
};

struct WallVerdict {
  Verdict verdict = Verdict::kGood;
  Verdict own = Verdict::kGood;  // From its own line's evidence (not its neighbours' or its length).
  double confidence = 1.0;       // 0–1.
  std::vector<std::string> reasons;
  WallEvidenceFigures evidence;

  std::string Why() const;  // The reasons, joined by "; ".
};

struct PlanVerdict {
  Verdict verdict = Verdict::kGood;
  double confidence = 1.0;           // 0–1; ranks plans by how far they can be trusted.
  std::vector<std::string> reasons;  // Why not "good" (empty when good).
  std::vector<WallVerdict> walls;    // Per plan wall.
  // Plan-wide evidence.
  double agreement = NAN;         // Share of seen bins that agree.
  double coverage = NAN;          // Share of bins (of the turn about the viewpoint) seen.
  double floor_ceiling = NAN;     // Median relative floor/ceiling disagreement.
  double label_confidence = NAN;  // The segmenter's (VerdictContext).
  int short_walls = 0;
  int odd_corners = 0;
  LabelTilt tilt;

  // "check (confidence 0.62): only 71 % of the bearings seen agree with the plan; …".
  std::string BriefReport() const;
};

// Judges `fit` (the plan FitPlan made from `input`). A plan without walls is
// unreliable. For one-camera captures (input.one_camera) coverage of the
// turn counts, and the ceiling must have been measured.
PlanVerdict JudgePlan(const PlanInput& input, const PlanResult& fit, const VerdictOptions& options = {},
                      const VerdictContext& context = {});

// Writes the verdict into the plan (formats/plan_file.h): the plan's
// PlanVerdictNote and each wall's word; an unreliable wall loses its ±, and
// an unreliable plan its area's ±. Every other wall's ± takes in, in
// quadrature, how far the points scatter about its two neighbours (their
// offset_sigma_m): its ends are where they cross it; and how far it may run
// on past a jog (run_on_m).
void MarkPlan(const PlanVerdict& verdict, Plan& plan);

// Worse of two verdicts.
inline Verdict Worse(Verdict a, Verdict b) { return static_cast<int>(a) >= static_cast<int>(b) ? a : b; }

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_VERDICT_H_
