#ifndef ASBUILT_PLAN_PLAN_STAGES_H_
#define ASBUILT_PLAN_PLAN_STAGES_H_

// The plan stages split where a re-fit may start again (internal to plan/;
// the public entry points are plan/reconstruct.h and plan/fit_plan.h):
// stages 1–4 (planarize, lines, directions, the closed ring) are kept by a
// fit state, stages 5–6 (walls with ±, openings) run again on any ring.

#include <optional>
#include <string>
#include <vector>

#include "asbuilt/plan/plan_directions.h"
#include "asbuilt/plan/plan_points.h"
#include "asbuilt/plan/plan_ring.h"
#include "asbuilt/plan/reconstruct.h"

namespace asbuilt {

struct RingStages {
  PlanPoints planar;  // Points into the caller's points, which must outlive this.
  DirectionFrame frame;
  Ring ring;            // The ring the points give on their own.
  PlanSummary summary;  // Counts of stages 1–4 (input, wall, door, window points, lines, directions).
};

// Stages 1–4 of ReconstructPlan; throws as ReconstructPlan does (too few
// wall points or lines). `options` must already be checked.
RingStages FitRingStages(const std::vector<ClassPoint>& points, const PlanOptions& options,
                         const std::string& points_source);

// Stages 5–6 on `ring` (stages.ring, or one built from a user's corners):
// walls with ±, the room polygon, openings. With `corners` (one per wall of
// the ring) the walls run between those points instead of where neighbours
// cross. With `skip_openings` the plan has none (the caller sets them).
// summary.seconds is left 0.
PlanResult PlanFromRingStages(const RingStages& stages, const Ring& ring, const PlanOptions& options,
                              const std::vector<Vec2>* corners = nullptr, bool skip_openings = false);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_PLAN_STAGES_H_
