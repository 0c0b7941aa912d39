#ifndef ASBUILT_PLAN_FIT_PLAN_H_
#define ASBUILT_PLAN_FIT_PLAN_H_

// The one plan entry point of a capture: `survey`, `plan` and `review` call
// FitPlan (or a PlanFitter, which keeps the earlier stages for re-fits).
//
//  - PlanInput says what the points are and where they were seen from; the
//    plan settings that follow from it (the viewpoint, one viewpoint or not,
//    the ceiling's σ, exact or segmented labels) are decided here, in
//    ResolvePlanOptions, not by each caller.
//  - PlanConstraints are what a person said about the room (docs/review.md):
//    corners (fixed floor points, in the room's order), the ceiling height,
//    the openings. With none, FitPlan is ReconstructPlan (plan/reconstruct.h)
//    on the resolved options, to the bit.
//  - The re-fit with corners: the ring of walls runs through the given
//    corners in their order. A wall next to a fixed (user) corner is
//    re-fitted through it from the wall points seen between its two corners
//    (the floor and ceiling contacts of those image columns, seen from the
//    viewpoint): the direction that gathers most votes among the room's
//    dominant directions, the survey's lines and the line to the other
//    corner, then refined by weighted least squares through the fixed point
//    and snapped to the Manhattan frame where the room has one. A wall
//    between two free (survey) corners keeps the survey's line when both
//    corners are the survey's, else takes the best-supported survey line in
//    its bearings. A free corner is where its walls cross (unless that makes
//    the room cross itself more than its corners as given do: then the free
//    corners that moved most go back to where they were given, one by one).
//    So one click fixes a wall and its neighbours, not just a point.

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/formats/points_file.h"
#include "asbuilt/geometry/polygon.h"
#include "asbuilt/plan/plan_options.h"
#include "asbuilt/plan/reconstruct.h"

namespace asbuilt {

// One frame of the capture the points came from (ClassPoint::frame).
struct PlanFrame {
  int index = 0;
  Vec3 position_m = Vec3::Zero();  // Rig or camera centre, world m (capture.json's position_m).
  Vec3 camera_m = Vec3::Zero();    // Optical centre of the camera whose pixels gave the contacts, world m.
};

struct PlanInput {
  std::vector<ClassPoint> points;
  std::string source;             // The file or capture the points came from; errors start with it.
  std::vector<PlanFrame> frames;  // Empty: where the points were seen from is unknown.
  bool one_camera = false;        // A mono or panorama capture (one camera turning in place), not a stereo rig.
  bool exact_labels = false;      // The capture's own exact labels, not segmented or given ones.
  double ceiling_height_m = NAN;  // From the wall–ceiling contacts (NaN: not measured).
  double ceiling_height_sigma_m = NAN;
  // 1σ of the camera height the capture states (a tape's error; NaN:
  // unknown). It scales every contact's distance alike: a room-wide mode.
  double camera_height_sigma_m = NAN;
};

// The options a fit of this input runs with: `options` with what the input
// decides filled in where unset — viewpoint_m (the frames' mean position),
// one_viewpoint (one camera, every frame within 5 cm of the viewpoint), the
// label-dependent σ (PlanOptions::ForLabels) with, in contact_scale_sigma,
// the camera height's share σ_h / h added in quadrature, ceiling_scale_sigma
// (σ_H / (H − h), h the viewpoint's height).
PlanOptions ResolvePlanOptions(const PlanInput& input, const PlanOptions& options);

// A corner of the room: a point on the floor where two walls meet.
struct PlanCorner {
  Vec2 xy_m = Vec2::Zero();
  bool fixed = false;  // A person put it there: walls pass through it. Else a hint, re-placed by the fit.
};

// A door or window a person gave, in plan: FitPlan puts it on the nearest
// wall (ends projected onto it).
struct PlanUserOpening {
  OpeningKind kind = OpeningKind::kDoor;
  Vec2 start_m = Vec2::Zero(), end_m = Vec2::Zero();
  double bottom_m = 0.0;  // Sill above the floor (0 for a door), m.
  double top_m = 2.0;     // Head above the floor, m.
};

struct PlanConstraints {
  // Empty: the ring the points give. Else the room's corners in order, the
  // room on the left (counter-clockwise seen from above), at least 3.
  std::vector<PlanCorner> corners;
  // The ceiling's height above the floor: ceiling contacts are moved along
  // their rays to it, and the walls are this high. Unset: as measured.
  std::optional<double> ceiling_height_m;
  // Unset: the openings the points give. Else exactly these.
  std::optional<std::vector<PlanUserOpening>> openings;

  // Throws InvalidArgument naming the field (fewer than 3 corners, a
  // non-finite number, an opening with top ≤ bottom). A corner polygon that
  // crosses itself is allowed (a survey's own ring may; the review refuses
  // an edit that adds a crossing).
  void Check() const;
};

// Keeps stages 1–4 of a fit (per ceiling height) so that a re-fit with new
// corners or openings runs only the stages they touch (milliseconds).
class PlanFitter {
 public:
  // Runs the stages the constraints do not touch. Throws InvalidArgument for
  // bad options. Points that hold fewer than two walls are no error here:
  // Fit() then throws as ReconstructPlan, unless given corners, whose plan
  // needs no points (a review that traces a room the survey did not find).
  PlanFitter(PlanInput input, const PlanOptions& options);
  ~PlanFitter();
  PlanFitter(PlanFitter&&) noexcept;
  PlanFitter& operator=(PlanFitter&&) noexcept;

  // The plan under these constraints. Throws InvalidArgument for bad
  // constraints (PlanConstraints::Check) and Error / InputError as the
  // constructor (a ceiling height leaving too few wall points).
  PlanResult Fit(const PlanConstraints& constraints = {}) const;

  const PlanInput& input() const;
  const PlanOptions& options() const;  // Resolved (ResolvePlanOptions).
  // What the fit was ordered around (the viewpoint, or the lines' centre), plan m.
  Vec2 viewpoint() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// PlanFitter(input, options).Fit(constraints).
PlanResult FitPlan(const PlanInput& input, const PlanOptions& options = {}, const PlanConstraints& constraints = {});

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_FIT_PLAN_H_
