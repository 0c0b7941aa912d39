#ifndef ASBUILT_REVIEW_HOME_REVIEW_H_
#define ASBUILT_REVIEW_HOME_REVIEW_H_

// `asbuilt review OUT/` on a home survey (docs/home.md "Correcting the
// placement"): the home's placement under a person's edits, re-placed after
// each (home/placement.h takes them as constraints), and saved as the home's
// plan. Edits (JSON, POST /api/edit):
//   {"op": "move_room", "room": i, "dx": m, "dy": m, "dyaw_deg": a}
//       the room moved by (dx, dy) and turned by dyaw_deg about its middle,
//       from where it is drawn; then held there, the others re-placed round it
//   {"op": "release_room", "room": i}          placed by its doors again
//   {"op": "link_openings", "a": {"room": i, "opening": j}, "b": {...}}
//       these two doors are one
//   {"op": "unlink_openings", "a": {...}, "b": {...}}   these two are not
//   {"op": "undo"}, {"op": "redo"}
// A bad edit throws EditError (HTTP 400) and leaves the state as it was.
// Save writes OUT's plan files, OUT/review/home_corrections.json and
// OUT/review/home_state.json (reopening starts from it), each atomically.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/home/home_plan.h"
#include "asbuilt/home/placement.h"
#include "asbuilt/review/review_backend.h"

namespace asbuilt {

class HomeReviewSession : public ReviewBackend {
 public:
  // Reads OUT/review/home.json (pipeline/home_survey.h; InputError naming it
  // when OUT is not a home survey) and the saved review, and places.
  static HomeReviewSession Open(const std::filesystem::path& out_dir);
  static bool IsHomeSurvey(const std::filesystem::path& out_dir);

  // {"kind": "home", "rooms", "links", "same", "different", "held", "verdict",
  //  "alternatives", "wall_thickness_m", "edits", "can_undo", "can_redo",
  //  "images", "refit_ms"}.
  nlohmann::json State() const override;
  nlohmann::json Edit(const nlohmann::json& edit) override;
  std::vector<std::string> SaveAll() override;
  std::vector<std::filesystem::path> ImagePaths() const override;
  const char* PageHtml() const override;

  const Plan& plan() const { return plan_; }
  const PlacementResult& placement() const { return placement_; }

 private:
  HomeReviewSession() = default;
  // Applies `edit` (already made absolute) to `c`; throws EditError.
  void Apply(const nlohmann::json& edit, PlacementConstraints& c) const;
  // Constraints from the edits so far, then places and draws.
  void Replace();
  // A move_room made absolute: the pose it puts the room at.
  nlohmann::json Absolute(const nlohmann::json& edit) const;
  OpeningRef Opening(const nlohmann::json& edit, const char* key) const;

  std::filesystem::path out_;
  std::vector<HomeRoomInput> rooms_;
  std::vector<std::filesystem::path> images_;  // Per room with a photo.
  std::vector<int> image_of_room_;             // Per room: index into images_, or −1.
  std::vector<nlohmann::json> edits_, undone_;
  PlacementConstraints constraints_;
  PlacementResult placement_;
  std::vector<Eigen::Isometry2d> drawn_;  // Where each room is drawn (beside the plan when unplaced).
  Plan plan_;
  double refit_ms_ = 0.0;
};

}  // namespace asbuilt

#endif  // ASBUILT_REVIEW_HOME_REVIEW_H_
