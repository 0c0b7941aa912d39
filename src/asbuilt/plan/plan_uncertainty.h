#ifndef ASBUILT_PLAN_PLAN_UNCERTAINTY_H_
#define ASBUILT_PLAN_PLAN_UNCERTAINTY_H_

// Plan stage 5, ± (internal to plan/): 1σ of the ring's wall lengths and of
// the room's area from the variances of its lines' angle θ and offset ρ.
//
// A line's fitted variances shrink with its number of points, but what its
// points share does not average out over them: its offset variance first
// gains the larger of (f · median σ of its points)², f =
// PlanOptions::shared_sigma_fraction for contact points and
// shared_stereo_sigma_fraction for stereo points, and what its floor and
// ceiling contacts' disagreement shows ((r_f − r_c)²/2 · (a² + (1 − a)²),
// r the two sets' median distances to the line, a the floor's share of the
// weight; docs/plan.md, "±", says how they were measured). The variances are
// then propagated numerically (central differences of the corners,
// RingCorners, under each line's θ and ρ moved by 10⁻³ σ) to every wall
// length and to the area; lines with zero variance (inferred connectors along
// a fixed direction) add nothing. With a viewpoint, a room-wide scale error
// of the contacts (PlanOptions::contact_scale_sigma, auto read as segmented
// labels') moves every line by its contacts' share of the weight times the
// scale times its distance from the viewpoint, all lines together, and adds
// its variance to each length and the area. A second such mode, the
// ceiling's height (PlanOptions::ceiling_scale_sigma, σ_H / (H − h)), moves
// each line by its ceiling contacts' share of the weight.

#include <vector>

#include "asbuilt/plan/plan_wall_line.h"

namespace asbuilt {

// Floor contacts lie at z = 0, ceiling ones at the ceiling's height: a contact
// point above this height (m) is a ceiling contact.
inline constexpr double kCeilingContactMinZ = 0.1;

struct RingSigmas {
  std::vector<double> wall_length_m;  // Per wall of the ring, from corner i to corner i + 1.
  double area_m2 = 0;                 // Of |area of the corner polygon|.
};

RingSigmas PropagateRingSigmas(const WallPoints& walls, const std::vector<WallLine>& ring, const PlanOptions& o);

}  // namespace asbuilt

#endif  // ASBUILT_PLAN_PLAN_UNCERTAINTY_H_
