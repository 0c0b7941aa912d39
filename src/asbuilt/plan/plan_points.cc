#include "asbuilt/plan/plan_points.h"

#include <algorithm>

namespace asbuilt {
namespace {

// A line with this many times min_wall_points votes is a wall however sparse
// it is next to the densest one, and however small a share of all votes (a
// far wall's contacts against a near wall's dense points).
constexpr double kStrongLineVotes = 5.0;

}  // namespace

PlanPoints PlanarizePoints(const std::vector<ClassPoint>& points, const PlanOptions& o) {
  PlanPoints out;
  const bool weigh_votes = std::any_of(points.begin(), points.end(), [](const ClassPoint& p) {
    return p.label == LabelClass::kWall && p.source == PointSource::kContact;
  });
  out.walls.weigh_votes = weigh_votes;
  if (weigh_votes) out.walls.strong_line_votes = kStrongLineVotes * o.min_wall_points;
  for (const ClassPoint& p : points) {
    if (!p.position_m.allFinite()) continue;
    double sigma = p.sigma_m > 0 ? p.sigma_m : o.nominal_sigma_m;
    if (p.label == LabelClass::kWall && p.source == PointSource::kVertex) {
      out.vertices.push_back({p.position_m.head<2>(), sigma});
    } else if (p.label == LabelClass::kWall) {
      double thr = std::min(o.max_inlier_distance_m, std::max(o.epsilon_m, o.inlier_sigmas * sigma));
      const double vote = weigh_votes ? std::min(1.0, (o.vote_sigma_m / sigma) * (o.vote_sigma_m / sigma)) : 1.0;
      out.walls.points.push_back({p.position_m.head<2>(), p.position_m.z(), 1.0 / (sigma * sigma), sigma, thr, vote,
                                  p.source == PointSource::kContact});
    } else if (p.label == LabelClass::kDoor || p.label == LabelClass::kWindow) {
      out.openings.push_back(&p);
      (p.label == LabelClass::kDoor ? out.door_points : out.window_points)++;
    }
  }
  return out;
}

}  // namespace asbuilt
